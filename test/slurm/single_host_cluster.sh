#!/usr/bin/env bash
# Sourced: a Slurm cluster of this host alone (slurmctld, slurmd, munged with their own key),
# everything in one temporary folder, for tests and measurements. Needs root (slurmd starts jobs
# as their users) and Debian 12's slurm-wlm and munge; works without /etc/slurm: SLURM_CONF
# points the commands at the generated slurm.conf, whose AuthInfo names munged's socket.
# Defines:
#   start_cluster   starts the three daemons and waits for the node; returns 77 with the reason
#                   on stdout when that is not possible here (not root, a daemon missing or
#                   failing: its log's end follows)
#   stop_cluster    cancels every job, stops the daemons and whatever they left, removes the
#                   folder; safe to call twice (the caller's EXIT trap calls it); slurm_left
#                   is then what it could not stop (empty)
#   slurm_dir       the folder; slurm_cmd CMD ARGS... runs a Slurm command on this cluster
# Every process of the cluster carries PS_SLURM_CLUSTER=<slurm_dir> in its environment (the
# daemons, and the jobs through sbatch) or holds a file of the folder open (slurmstepd):
# stop_cluster finds what is left by that, by process id, and nothing that is not this cluster's.
slurm_dir=""
slurm_pids=()
slurm_left=""

slurm_cmd() {
  env PS_SLURM_CLUSTER="$slurm_dir" SLURM_CONF="$slurm_dir/slurm.conf" "$@"
}

slurm_log_tails() {
  local f
  for f in "$slurm_dir"/log/*.log; do
    [ -f "$f" ] && { echo "--- $(basename "$f")"; tail -n 15 "$f"; }
  done
}

# Free TCP port on loopback (the kernel's choice; another program could take it before the
# daemon does, which start_cluster then reports).
free_port() {
  /usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

start_cluster() {
  if [ "$(id -u)" -ne 0 ]; then
    echo "not root: slurmd must run as root to start jobs"
    return 77
  fi
  local p
  for p in munged mungekey slurmctld slurmd sbatch squeue scontrol scancel sinfo; do
    command -v "$p" >/dev/null || { echo "$p is not installed (Debian: slurm-wlm, munge)"; return 77; }
  done
  slurm_dir=$(mktemp -d "${TMPDIR:-/tmp}/slurm_cluster.XXXXXX")
  # munged wants every folder on its socket's path searchable by all, its key private.
  chmod 755 "$slurm_dir"
  mkdir -p "$slurm_dir/munge/private" "$slurm_dir/state" "$slurm_dir/spool" "$slurm_dir/log" \
    "$slurm_dir/work"
  chmod 755 "$slurm_dir/munge"
  chmod 700 "$slurm_dir/munge/private"
  local sock="$slurm_dir/munge/munge.socket"
  mungekey --create --keyfile="$slurm_dir/munge/private/munge.key" >/dev/null 2>&1 || {
    echo "mungekey could not create a key"
    return 77
  }
  env PS_SLURM_CLUSTER="$slurm_dir" munged --foreground --socket="$sock" \
    --key-file="$slurm_dir/munge/private/munge.key" --pid-file="$slurm_dir/munge/munged.pid" \
    --log-file="$slurm_dir/log/munged.log" --seed-file="$slurm_dir/munge/private/munged.seed" \
    >/dev/null 2>>"$slurm_dir/log/munged.log" &
  slurm_pids+=($!)
  local i
  for i in $(seq 50); do
    munge --socket="$sock" --no-input >/dev/null 2>&1 && break
    if ! kill -0 "${slurm_pids[0]}" 2>/dev/null || [ "$i" -eq 50 ]; then
      echo "munged did not start:"
      slurm_log_tails
      return 77
    fi
    sleep 0.1
  done

  # The node as slurmd sees this machine (CPUs, sockets, cores, memory): no drained node.
  local host hw
  host=$(hostname -s)
  hw=$(slurmd -C 2>/dev/null | head -n 1 | sed 's/^NodeName=[^ ]* //')
  case "$hw" in
    *CPUs=*RealMemory=*) ;;
    *) echo "slurmd -C did not describe this machine: '$hw'"; return 77 ;;
  esac
  cat >"$slurm_dir/slurm.conf" <<CONF
ClusterName=ps_single_host
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
StateSaveLocation=$slurm_dir/state
SlurmdSpoolDir=$slurm_dir/spool
SlurmctldPidFile=$slurm_dir/slurmctld.pid
SlurmdPidFile=$slurm_dir/slurmd.pid
SlurmctldLogFile=$slurm_dir/log/slurmctld.log
SlurmdLogFile=$slurm_dir/log/slurmd.log
PlugStackConfig=$slurm_dir/plugstack.conf
# A container has no cgroups to give Slurm: processes are tracked through /proc.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
SwitchType=switch/none
MailProg=/bin/true
ReturnToService=2
SlurmdParameters=config_overrides
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 $hw State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  : >"$slurm_dir/plugstack.conf"
  # slurmd 22.05 starts a cgroup plugin even with proctrack/linuxproc and task/none, and its
  # autodetection fails where /sys/fs/cgroup is not mounted (a chroot): name the v1 plugin, which
  # touches no cgroup until a cgroup plugin of proctrack or task asks for one.
  printf 'CgroupPlugin=cgroup/v1\nCgroupAutomount=no\n' >"$slurm_dir/cgroup.conf"
  env PS_SLURM_CLUSTER="$slurm_dir" SLURM_CONF="$slurm_dir/slurm.conf" slurmctld -D -i \
    >>"$slurm_dir/log/slurmctld.out" 2>&1 &
  slurm_pids+=($!)
  env PS_SLURM_CLUSTER="$slurm_dir" SLURM_CONF="$slurm_dir/slurm.conf" slurmd -D \
    >>"$slurm_dir/log/slurmd.out" 2>&1 &
  slurm_pids+=($!)
  local state=""
  for i in $(seq 150); do
    state=$(slurm_cmd sinfo -h -N -o %T 2>/dev/null || true)
    [ "$state" = idle ] && return 0
    for p in "${slurm_pids[@]}"; do
      kill -0 "$p" 2>/dev/null || { echo "a Slurm daemon exited at start:"; slurm_log_tails; tail -n 5 "$slurm_dir"/log/*.out; return 77; }
    done
    sleep 0.2
  done
  echo "the node did not become idle within 30 s (state '$state'):"
  slurm_log_tails
  return 77
}

# This cluster's processes still running, but not this shell: those with its mark in their
# environment, and slurmstepd (it starts with an empty environment), which holds slurmd's log open.
slurm_leftovers() {
  local e p
  for e in /proc/[0-9]*/environ; do
    p=${e#/proc/}
    p=${p%/environ}
    [ "$p" != $$ ] && [ "$p" != "$BASHPID" ] || continue
    if grep -qzxF "PS_SLURM_CLUSTER=$slurm_dir" "$e" 2>/dev/null ||
      find "/proc/$p/fd" -lname "$slurm_dir/*" -print -quit 2>/dev/null | grep -q .; then
      echo "$p"
    fi
  done
  return 0
}

stop_cluster() {
  [ -n "$slurm_dir" ] || return 0
  local p i left
  # Jobs first, while slurmd can still end their steps.
  if slurm_cmd scancel --quiet --user="$(id -un)" 2>/dev/null; then
    for i in $(seq 50); do
      [ -z "$(slurm_cmd squeue -h 2>/dev/null)" ] && break
      sleep 0.2
    done
  fi
  # The controller and slurmd, then munged (last: the others need it to the end).
  for p in "${slurm_pids[@]:1}" "${slurm_pids[0]:-}"; do
    [ -n "$p" ] || continue
    kill -TERM "$p" 2>/dev/null || true
    for i in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$p" 2>/dev/null || true
    wait "$p" 2>/dev/null || true
  done
  slurm_pids=()
  # slurmstepd and the jobs outlive slurmd by design. A job that was starting may still exec its
  # script (a child of slurmstepd between fork and exec has neither mark): done only after
  # three empty looks in a row, 5 s at most.
  local quiet=0
  for i in $(seq 25); do
    left=$(slurm_leftovers)
    if [ -n "$left" ]; then
      # shellcheck disable=SC2086
      kill -KILL $left 2>/dev/null || true
      quiet=0
    else
      quiet=$((quiet + 1))
      [ "$quiet" -lt 3 ] || break
    fi
    sleep 0.2
  done
  slurm_left=$(slurm_leftovers)
  [ -z "$slurm_left" ] || echo "stop_cluster: still running after SIGKILL: $slurm_left" >&2
  rm -rf "$slurm_dir"
  slurm_dir=""
}

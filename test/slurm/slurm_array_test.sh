#!/usr/bin/env bash
# scripts/slurm on a real Slurm cluster of this host (test/slurm/single_host_cluster.sh): a
# 4-task array job of sample_array.sbatch (Lift, physics settle: every array of the .npz), every
# task completed under Slurm, merge.py's file equal array for array to one process's run; then a
# lost piece: merge.py names it and prints one sbatch command, which, run as printed, re-runs
# that task alone, and the merge is equal again. No process of the cluster is left.
# Exits 77 (skipped) with the reason when not root, or Slurm or munge cannot start here.
# usage: slurm_array_test.sh SAMPLE_SCENES SOURCE_DIR
set -euo pipefail
export SAMPLE_SCENES=$1
root=$2
source "$root/test/slurm/single_host_cluster.sh"
trap stop_cluster EXIT
trap "exit 143" TERM  # the EXIT trap stops the cluster on these too
trap "exit 130" INT HUP
config=$root/config/lift.yaml
seed=11
per_task=25
tasks=4
python=/usr/bin/python3

fail() {
  echo "FAIL: $*"
  [ -n "$slurm_dir" ] && slurm_log_tails
  exit 1
}

status=0
start_cluster || status=$?
if [ "$status" -ne 0 ]; then
  echo "skipped: no single-host Slurm cluster here (see above)"
  exit 77
fi
echo "cluster up: $(slurm_cmd sinfo -h -N -o '%N %T %c CPUs %m MB')"
work=$slurm_dir/work
out=$work/pieces

# wait_job ID: until the job (every task of the array) has left the queue, 300 s at most.
wait_job() {
  local i
  for i in $(seq 1500); do
    [ -z "$(slurm_cmd squeue -h -j "$1" 2>/dev/null)" ] && return 0
    sleep 0.2
  done
  fail "job $1 still queued or running after 300 s: $(slurm_cmd squeue -h -j "$1")"
}
# job_states ID: each task's "ArrayTaskId=T JobState=S", sorted.
job_states() {
  slurm_cmd scontrol show job "$1" | tr ' ' '\n' | grep -E '^(ArrayTaskId|JobState)=' |
    paste -d ' ' - - | sort -V
}

"$SAMPLE_SCENES" --config "$config" --seed "$seed" --scenes $((tasks * per_task)) \
  --physics settle --output "$work/one.npz" 2>/dev/null || [ $? -eq 1 ] ||
  fail "the one-process run failed"

cd "$work"
job=$(slurm_cmd sbatch --parsable --array=0-$((tasks - 1)) "$root/scripts/slurm/sample_array.sbatch" \
  "$config" "$seed" "$per_task" "$out" --physics settle) || fail "sbatch refused the array job"
echo "submitted array job $job"
wait_job "$job"
states=$(job_states "$job")
expected=$(for t in $(seq 0 $((tasks - 1))); do echo "ArrayTaskId=$t JobState=COMPLETED"; done)
[ "$states" = "$expected" ] || { cat slurm-*.out; fail "expected every task COMPLETED, got: $states"; }
# Each piece was written by its Slurm task (the record names the array job and its size).
for t in $(seq 0 $((tasks - 1))); do
  $python - "$out/$(printf 'task_%06d' "$t").json" "$job" "$t" "$((tasks - 1))" <<'PY' || fail "task $t's record"
import json, sys
r = json.load(open(sys.argv[1]))
want = {"state": "done", "status": 0, "job_id": sys.argv[2], "task": int(sys.argv[3]),
        "array_task_max": int(sys.argv[4])}
got = {k: r.get(k) for k in want}
assert got == want, "%s: %s, expected %s" % (sys.argv[1], got, want)
PY
done

"$root/scripts/slurm/merge.py" "$out" "$work/merged.npz" || fail "merge.py failed"
$python "$root/test/slurm/npz_equal.py" "$work/merged.npz" "$work/one.npz" ||
  fail "the merged array job differs from one process"

# A lost piece: named, and the printed command re-runs it alone.
rm "$out/task_000002.npz"
status=0
msg=$("$root/scripts/slurm/merge.py" "$out" "$work/merged2.npz" 2>&1) || status=$?
echo "$msg"
[ "$status" -eq 1 ] || fail "merge.py with a lost piece: status $status, expected 1"
[ ! -e "$work/merged2.npz" ] || fail "merge.py wrote a file with a piece missing"
echo "$msg" | grep -qxF "  task 2: done on $(hostname) at $(
  $python -c 'import json,sys; print(json.load(open(sys.argv[1]))["time"])' "$out/task_000002.json"
), but task_000002.npz is not in OUT_DIR" || fail "merge.py did not name task 2 and why"
[ "$(echo "$msg" | grep -c '^  task ')" -eq 1 ] || fail "merge.py named other tasks than 2"
rerun=$(echo "$msg" | tail -n 1 | sed 's/^  //')
case "$rerun" in
  "sbatch --array=2 --partition=local $root/scripts/slurm/sample_array.sbatch $config $seed $per_task $out --physics settle") ;;
  *) fail "unexpected re-run command: $rerun" ;;
esac
job2=$(slurm_cmd bash -c "${rerun/#sbatch /sbatch --parsable }") || fail "the printed command failed: $rerun"
wait_job "$job2"
[ "$(job_states "$job2")" = "ArrayTaskId=2 JobState=COMPLETED" ] ||
  fail "the re-run: $(job_states "$job2")"
"$root/scripts/slurm/merge.py" "$out" "$work/merged2.npz" || fail "merge.py after the re-run"
$python "$root/test/slurm/npz_equal.py" "$work/merged2.npz" "$work/one.npz" ||
  fail "the merge after the re-run differs from one process"

trap - EXIT
stop_cluster
[ -z "$slurm_left" ] || fail "processes of the cluster left running: $slurm_left"
echo "slurm array: $tasks tasks of $per_task scenes merged = one process; a lost task re-run by the printed command"

#!/usr/bin/env bash
# Sourced by the shell tests that need a master of their own (they cannot run under rostest:
# they start nodes the way a user does). Defines: a free port in ROS_MASTER_URI, start_master,
# launch (roslaunch in the background), stop_launch, wait_service, fail, and an exit trap that
# stops every process the test started, by its id.
# The README's environment for a terminal: Debian's python first (tf2_tools' echo.py runs
# `env python3`), traffic on loopback.
export PATH=/usr/bin:$PATH ROS_HOSTNAME=localhost
unset ROS_IP
port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI=http://localhost:$port
log=$(mktemp -d)
core_pid=""
launch_pid=""
extra_pids=()
cleanup() {
  stop_launch
  for p in "${extra_pids[@]}"; do
    kill -INT "$p" 2>/dev/null || true
    wait "$p" 2>/dev/null || true
  done
  if [ -n "$core_pid" ]; then
    kill -INT "$core_pid" 2>/dev/null || true
    wait "$core_pid" 2>/dev/null || true
  fi
  rm -rf "$log"
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*"
  for f in "$log"/*.log; do
    [ -f "$f" ] && { echo "--- $(basename "$f")"; tail -n 30 "$f"; }
  done
  exit 1
}
start_master() {
  roscore -p "$port" >"$log/core.log" 2>&1 &
  core_pid=$!
  for _ in $(seq 100); do rosparam list >/dev/null 2>&1 && return 0; sleep 0.2; done
  fail "the master did not start"
}
# launch ARGS...: roslaunch placement_samplers placement_server.launch ARGS in the background.
launch() {
  roslaunch placement_samplers placement_server.launch "$@" >"$log/launch.log" 2>&1 &
  launch_pid=$!
}
stop_launch() {
  if [ -n "$launch_pid" ]; then
    kill -INT "$launch_pid" 2>/dev/null || true
    wait "$launch_pid" 2>/dev/null || true
    launch_pid=""
  fi
}
# wait_service NAME [PID]: until NAME is registered (20 s at most); fails at once when PID (a
# roslaunch or a node that must keep running) exits first.
wait_service() {
  for _ in $(seq 100); do
    rosservice list 2>/dev/null | grep -qx "$1" && return 0
    if [ -n "${2:-}" ] && ! kill -0 "$2" 2>/dev/null; then
      fail "the process serving $1 exited"
    fi
    sleep 0.2
  done
  fail "$1 not registered within 20 s"
}

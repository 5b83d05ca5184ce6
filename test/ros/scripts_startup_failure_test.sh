#!/usr/bin/env bash
# scripts/run --once and scripts/screenshot with a configuration the node refuses: each notices
# the node's exit at once (not after the client's 60 s wait for the service), prints the node's
# FATAL line, exits with 2 and leaves no process behind. Runs on a master port of its own, with
# the build as it is (PLACEMENT_SAMPLERS_SKIP_BUILD); exits 77 (skipped) for screenshot when
# Xvfb, rviz or ImageMagick is not installed.
# usage: scripts_startup_failure_test.sh run|screenshot SOURCE_DIR BUILD_DIR
set -euo pipefail
which=$1
root=$2
export PLACEMENT_SAMPLERS_BUILD=$3 PLACEMENT_SAMPLERS_SKIP_BUILD=1
if [ "$which" = screenshot ]; then
  for p in Xvfb rviz import; do
    command -v "$p" >/dev/null || { echo "skipped: $p is not installed"; exit 77; }
  done
fi
port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI=http://localhost:$port ROS_HOSTNAME=localhost
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
name=broken_server_$$
cat >"$tmp/broken.yaml" <<YAML
objects:
  cube: {shape: box, size: [0.04, 0.04, 0.04]}
samplers:
  - {name: S, objects: [cube], x_range: [0.3, -0.3]}
YAML

# In a session of its own: whatever it started and left running is found by the session id.
start=$(date +%s)
case "$which" in
  run) setsid "$root/scripts/run" --once config:="$tmp/broken.yaml" name:="$name" \
         >"$tmp/out" 2>&1 </dev/null & ;;
  screenshot) setsid "$root/scripts/screenshot" "$tmp/shot.png" 7 config:="$tmp/broken.yaml" \
                name:="$name" >"$tmp/out" 2>&1 </dev/null & ;;
  *) echo "usage: $0 run|screenshot SOURCE_DIR BUILD_DIR"; exit 2 ;;
esac
session=$!
status=0
wait "$session" || status=$?
elapsed=$(( $(date +%s) - start ))

failed=0
check() {  # check DESCRIPTION TEST...
  local what=$1
  shift
  if "$@"; then echo "ok: $what"; else echo "FAIL: $what"; failed=1; fi
}
check "exit status 2 (got $status)" [ "$status" -eq 2 ]
fatal="[FATAL]"
line="/$name: invalid configuration: /$name/samplers[0]/x_range: expected [min, max] with min <= max, got [0.3, -0.3]"
check "the reason is given" grep -qF "the placement server exited before serving /$name/sample_placements:" "$tmp/out"
check "the node's FATAL line is printed, named after the node" \
  grep -qF "$line" <(sed 's/\x1b\[[0-9;]*m//g' "$tmp/out" | grep -F "$fatal")
# The client would wait 60 s for the service: the node's exit must end it long before.
check "it returned without waiting for the service (${elapsed} s)" [ "$elapsed" -lt 40 ]
[ "$which" = screenshot ] && check "no picture is saved" [ ! -e "$tmp/shot.png" ]
left=""
for _ in $(seq 25); do
  left=$(pgrep -s "$session" -a || true)
  [ -z "$left" ] && break
  sleep 0.2
done
check "no process of the script is left" [ -z "$left" ]
if [ -n "$left" ]; then
  echo "$left"
  for p in $(pgrep -s "$session" || true); do kill -KILL "$p" 2>/dev/null || true; done
fi
if [ "$failed" -ne 0 ]; then
  echo "--- output"
  cat "$tmp/out"
  exit 1
fi
echo "scripts/$which with a broken configuration: ${elapsed} s, status 2, the FATAL line, nothing left"

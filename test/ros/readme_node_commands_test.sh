#!/usr/bin/env bash
# The README's commands for a running node, run as written and in the README's order: every
# rosservice, rostopic, rosparam, `rosrun tf2_tools` and `rosrun placement_samplers
# placement_server` line of its ```bash blocks. The node runs as the README starts it
# (roslaunch, config/default.yaml); a block that starts one by hand runs with none running, and
# default's is launched again after it. Each call must succeed: sample_placements and reload
# answer `success: True`, validate_placements `valid: True`, the tf echo prints the frame, and
# the hand-started node serves lift.yaml's cube alone. Needs the devel space's environment
# (ctest gives it through env.sh).
# usage: readme_node_commands_test.sh SOURCE_DIR
set -euo pipefail
root=$1
source "$root/test/ros/shell_test_helpers.sh"
cd "$root"

# One command per record: "BLOCK<TAB>COMMAND", NUL-terminated; a command goes on over lines
# while a double quote is open or a line ends in a backslash.
commands() {
  /usr/bin/python3 - README.md <<'PY'
import re, sys
text = open(sys.argv[1]).read()
wanted = re.compile(r"(rosservice |rostopic |rosparam |rosrun tf2_tools |rosrun placement_samplers placement_server(\s|$))")
for block, body in enumerate(re.findall(r"^```bash\n(.*?)^```", text, re.S | re.M)):
    pending = ""
    for line in body.splitlines():
        pending = pending + "\n" + line if pending else line
        if pending.count('"') % 2 == 1 or pending.endswith("\\"):
            continue
        if wanted.match(pending):
            sys.stdout.write("%d\t%s\0" % (block, pending))
        pending = ""
PY
}

start_master
launch
wait_service /placement_server/sample_placements "$launch_pid"
count=0
hand_blocks=$(commands | tr '\0' '\n' | grep -P '^\d+\trosrun placement_samplers placement_server' | cut -f1 || true)
[ -n "$hand_blocks" ] || fail "the README starts no node by hand"
block_seen=""
while IFS=$'\t' read -r -d '' block cmd; do
  count=$((count + 1))
  if [ "$block" != "$block_seen" ]; then
    block_seen=$block
    # The README says: with no server running.
    if echo "$hand_blocks" | grep -qx "$block"; then
      stop_launch
    fi
  fi
  echo "running: $cmd"
  case "$cmd" in
    "rosrun placement_samplers placement_server"*)
      bash -c "$cmd" >"$log/hand.log" 2>&1 &
      hand=$!
      extra_pids+=("$hand")
      wait_service /placement_server/sample_placements "$hand"
      out=$(rosservice call /placement_server/sample_placements "{dry_run: true}" 2>&1) || true
      echo "$out" | grep -q "success: True" || fail "the node started by hand: $out"
      names=$(echo "$out" | sed -n 's/^ *name: "\{0,1\}\([A-Za-z0-9_]*\)"\{0,1\}$/\1/p' | tr '\n' ' ')
      [ "$names" = "cube " ] || fail "the node started by hand should serve lift.yaml's cube alone, got: $names"
      kill -INT "$hand"
      wait "$hand" || fail "the node started by hand did not stop cleanly"
      # Back to what the rest of the README assumes, through the launch file.
      launch
      wait_service /placement_server/sample_placements "$launch_pid"
      ;;
    "rosrun tf2_tools"*)
      out=$(timeout 30 bash -c "$cmd" 2>&1) || fail "$cmd: $out"
      echo "$out" | grep -q -- "- Translation: \[" || fail "$cmd printed no frame: $out"
      ;;
    rostopic*)
      out=$(timeout 30 bash -c "$cmd" 2>&1) || fail "$cmd: $out"
      [ -n "$out" ] || fail "$cmd printed nothing"
      ;;
    *validate_placements*)
      out=$(bash -c "$cmd" 2>&1) || fail "$cmd: $out"
      echo "$out" | grep -q "^valid: True" || fail "$cmd: $out"
      if echo "$out" | grep -q "valid: False"; then fail "$cmd: an object is not valid: $out"; fi
      ;;
    rosservice*)
      out=$(bash -c "$cmd" 2>&1) || fail "$cmd: $out"
      echo "$out" | grep -q "^success: True" || fail "$cmd: $out"
      ;;
    *)
      out=$(bash -c "$cmd" 2>&1) || fail "$cmd: $out"
      ;;
  esac
done < <(commands)
[ "$count" -ge 10 ] || fail "expected at least 10 node commands in the README, found $count"
echo "README node commands: $count ran as written, in order"

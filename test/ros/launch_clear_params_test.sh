#!/usr/bin/env bash
# The launch file runs exactly its configuration on a master that an earlier configuration
# left its parameters on (clear_params): config/default.yaml, then pick_place_mjcf.yaml, whose
# configuration has neither default's sampler maps nor its table fixture nor its hidden pill.
# Needs the devel space's environment (ctest gives it through env.sh).
# usage: launch_clear_params_test.sh SOURCE_DIR
set -euo pipefail
root=$1
source "$root/test/ros/shell_test_helpers.sh"
start_master

launch
wait_service /placement_server/sample_placements "$launch_pid"
out=$(rosservice call /placement_server/sample_placements "{dry_run: true}")
echo "$out" | grep -q "success: True" || fail "default.yaml: $out"
stop_launch
rosparam get /placement_server/CupSampler >/dev/null 2>&1 ||
  fail "precondition: default.yaml's sampler maps should stay on the master after the launch"

launch config:="$root/config/pick_place_mjcf.yaml"
wait_service /placement_server/sample_placements "$launch_pid"
out=$(rosservice call /placement_server/sample_placements "{seed: 3, dry_run: true}")
echo "$out" | grep -q "success: True" || fail "pick_place_mjcf.yaml after default.yaml: $out"
names=$(echo "$out" | sed -n 's/^ *name: "\{0,1\}\([A-Za-z0-9_]*\)"\{0,1\}$/\1/p' | sort | tr '\n' ' ')
[ "$names" = "Bread Can Milk Nut " ] || fail "expected the placements Bread Can Milk Nut, got: $names"
for stale in CupSampler PlateSampler TableSampler fixtures hide; do
  if rosparam get "/placement_server/$stale" >/dev/null 2>&1; then
    fail "default.yaml's parameter /placement_server/$stale is still there"
  fi
done
out=$(rosservice call /placement_server/reload "{}")
echo "$out" | grep -qF 'message: "configuration reloaded: 4 objects, 0 fixtures"' ||
  fail "the node should hold 4 objects and no fixture: $out"
echo "launch clear_params: 2 configurations in turn on one master, each exactly its own"

#!/usr/bin/env bash
# launch/two_hosts.launch: as roslaunch reads it, each placement server runs on its <machine>
# (host_a, host_b) in its own namespace with its host's address as ROS_HOSTNAME, and a host that
# is not this one is started over ssh through scripts/env_loader; launched with both hosts
# localhost, both services answer on one master (also to the README's loop), each with its own
# configuration and tf prefix.
# scripts/env_loader sets up the workspace and takes ssh's server address as ROS_HOSTNAME.
# Needs the devel space's environment (ctest gives it through env.sh).
# usage: two_hosts_launch_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
root=$1
export PLACEMENT_SAMPLERS_BUILD=$2
source "$root/test/ros/shell_test_helpers.sh"
launch_file=$root/launch/two_hosts.launch

# The launch file as roslaunch assigns it: machines, namespaces, ROS_HOSTNAME, local or ssh.
# 192.0.2.1 (TEST-NET-1) is no address of this host: a remote machine.
/usr/bin/python3 - "$launch_file" "$root/scripts/env_loader" <<'PY' || fail "the launch file's machines"
import sys
import roslaunch.config
import roslaunch.core

launch_file, env_loader = sys.argv[1:3]
for host_b, b_local in (("localhost", True), ("192.0.2.1", False)):
    config = roslaunch.config.load_config_default([(launch_file, ["host_b:=" + host_b])], None)
    nodes = {n.namespace: n for n in config.nodes}
    assert sorted(nodes) == ["/cell_a/", "/cell_b/"], sorted(nodes)
    for ns, name, address, local in (("/cell_a/", "host_a", "localhost", True),
                                     ("/cell_b/", "host_b", host_b, b_local)):
        n = nodes[ns]
        assert (n.type, n.name, n.machine_name) == ("placement_server", "placement_server", name), \
            (n.type, n.name, n.machine_name)
        assert ("ROS_HOSTNAME", address) in n.env_args, (ns, n.env_args)
        assert n.machine.address == address and n.machine.env_loader == env_loader, n.machine
        assert roslaunch.core.is_machine_local(n.machine) == local, (ns, n.machine)
print("two_hosts.launch: cell_a on host_a, cell_b on host_b (local, and remote over ssh at 192.0.2.1)")
PY

# scripts/env_loader: the workspace (rospack finds the package), and ROS_HOSTNAME from ssh.
out=$(env -u ROS_HOSTNAME -u ROS_IP -u ROS_PACKAGE_PATH SSH_CONNECTION="198.51.100.4 50000 192.0.2.7 22" \
  "$root/scripts/env_loader" bash -c 'echo "$ROS_HOSTNAME $(rospack find placement_samplers)"')
[ "$out" = "192.0.2.7 $root" ] || fail "env_loader: expected '192.0.2.7 $root', got '$out'"
status=0
msg=$(PLACEMENT_SAMPLERS_BUILD=$log/none "$root/scripts/env_loader" true 2>&1) || status=$?
[ "$status" -eq 1 ] && [ "$msg" = "env_loader on $(hostname): no workspace at $log/none (build it there, or set PLACEMENT_SAMPLERS_BUILD)" ] ||
  fail "env_loader without a workspace: status $status, '$msg'"

start_master
roslaunch placement_samplers two_hosts.launch >"$log/launch.log" 2>&1 &
launch_pid=$!
for ns in cell_a cell_b; do
  wait_service "/$ns/placement_server/sample_placements" "$launch_pid"
done
# Each instance its own configuration: default.yaml's six objects, lift.yaml's cube.
out=$(rosservice call /cell_a/placement_server/sample_placements "{seed: 5}" 2>&1) || fail "cell_a: $out"
echo "$out" | grep -q "success: True" || fail "cell_a: $out"
names=$(echo "$out" | sed -n 's/^ *name: "\{0,1\}\([A-Za-z0-9_]*\)"\{0,1\}$/\1/p' | sort | tr '\n' ' ')
[ "$names" = "ball can cube cup pill plate " ] ||
  fail "cell_a should place default.yaml's objects, got: $names"
out=$(rosservice call /cell_b/placement_server/sample_placements "{seed: 5}" 2>&1) || fail "cell_b: $out"
echo "$out" | grep -q "success: True" || fail "cell_b: $out"
names=$(echo "$out" | sed -n 's/^ *name: "\{0,1\}\([A-Za-z0-9_]*\)"\{0,1\}$/\1/p' | tr '\n' ' ')
[ "$names" = "cube " ] || fail "cell_b should place lift.yaml's cube, got: $names"
# The README's loop over both instances, as written.
readme_loop=$(grep -m 1 '^for ns in cell_a cell_b; do rosservice call' "$root/README.md") ||
  fail "README.md has no loop calling both instances"
out=$(bash -c "$readme_loop" 2>&1) || fail "$readme_loop: $out"
[ "$(echo "$out" | grep -c '^success: True')" -eq 2 ] || fail "$readme_loop: $out"
# Frames apart: each scene names its instance's tf prefix.
for ns in cell_a cell_b; do
  prefix=$(rostopic echo -n 1 "/$ns/placement_server/scene/tf_prefix" 2>/dev/null | head -n 1)
  [ "$prefix" = "\"$ns/placement_server/\"" ] || [ "$prefix" = "$ns/placement_server/" ] ||
    fail "$ns: tf_prefix $prefix, expected $ns/placement_server/"
done
echo "two_hosts.launch: /cell_a and /cell_b answer on one master, each with its configuration and frames"

#!/usr/bin/env bash
# Shared set-up for scripts/test and scripts/run: Debian packages, environment, build.
# Source it; it defines ps_install, ps_env, ps_build, ps_source, and ps_launch, ps_call and
# ps_stop_launch for the scripts that start the server.

PS_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# The build lives next to the checkout, not inside it: rosrun ignores every program under the
# package's own build/, and a build folder of any other name inside the package, or whose path
# starts with the package's (checkout_build/), gives it two copies of each Python script to
# choose from. PLACEMENT_SAMPLERS_BUILD chooses another place.
PS_BUILD="${PLACEMENT_SAMPLERS_BUILD:-$(dirname "$PS_ROOT")/build_$(basename "$PS_ROOT")}"

PS_PACKAGES=(
  cmake g++ make catkin ros-core ros-core-dev rosbash
  libroscpp-dev libroslib-dev ros-message-generation ros-message-runtime python3-genpy python3-gencpp python3-genmsg
  libstd-msgs-dev ros-std-msgs libgeometry-msgs-dev ros-geometry-msgs
  libvisualization-msgs-dev ros-visualization-msgs python3-visualization-msgs
  libshape-msgs-dev ros-shape-msgs libstd-srvs-dev ros-std-srvs
  libtf2-dev libtf2-ros-dev python3-tf2-ros tf2-tools
  liburdfdom-dev libconsole-bridge-dev libfcl-dev libeigen3-dev libassimp-dev
  librostest-dev python3-rostest python3-rospy python3-nose python3-numpy libgtest-dev
  libyaml-cpp-dev catkin-lint
  # The node's ~get_loggers reads log4cxx (rosconsole's backend) itself: its headers.
  liblog4cxx-dev
  # ctest clang_format checks the layout of every C++ file with Debian 12's clang-format (14).
  clang-format
  # assimp's CMake targets link libz.so: a fresh Debian 12 failed at link time without it;
  # the .npz writer's CRC-32 is zlib's too.
  zlib1g-dev
  # test/robosuite_reference.py reads each configuration's primitive sizes.
  python3-yaml
  # /usr/bin/time: test/npz_memory.sh measures the peak memory of a large --output run.
  time
  # MuJoCo reads MJCF objects; its CMake config needs OpenGL's and qhull's development files
  # without depending on them (a fresh Debian 12 failed at configure).
  libmujoco-dev libqhull-dev libgl-dev libopengl-dev libglx-dev
  # MJCF objects are read and bounded before MuJoCo compiles them (the XML parser MuJoCo uses).
  libtinyxml2-dev
  # Boost.Geometry (header-only) merges and cuts the polygons of support surfaces.
  libboost-dev
  # The node's ~sample action (actionlib; rospy's client in sample_client.py --action), its
  # health on /diagnostics, its live knobs (dynamic_reconfigure: the .cfg generator, the C++
  # server, dynparam) and the region handles in rviz (interactive_markers).
  libactionlib-dev python3-actionlib ros-actionlib-msgs libactionlib-msgs-dev python3-actionlib-msgs
  libdiagnostic-updater-dev ros-diagnostic-msgs libdiagnostic-msgs-dev python3-diagnostic-msgs
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libinteractive-markers-dev python3-interactive-markers
  # sample_client.py --action draws its progress bar with tqdm.
  python3-tqdm
  # placement_samplers.robosuite, the Python module: pybind11 over the core, with Python's and
  # numpy's C headers (python3-numpy above).
  pybind11-dev python3-dev
  # ctest slurm_array runs the array-job scripts (scripts/slurm) on a real Slurm cluster of this
  # host: slurmctld, slurmd and their munge authentication.
  slurm-wlm munge
)

ps_sudo() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

# Installs the Debian packages that are missing (nothing to do on a second run).
ps_install() {
  local missing=()
  local p
  for p in "${PS_PACKAGES[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "==> installing ${#missing[@]} Debian packages: ${missing[*]}"
    ps_sudo apt-get update -qq
    ps_sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
      "${missing[@]}" >/dev/null
  fi
  # rostest and roslaunch resolve "localhost" through /etc/hosts.
  if ! getent hosts localhost >/dev/null; then
    echo "127.0.0.1 localhost" | ps_sudo tee -a /etc/hosts >/dev/null
  fi
}

# Debian's python first (a pyenv python lacks catkin_pkg); ROS traffic on loopback.
ps_env() {
  export PATH="/usr/bin:$PATH"
  # package://placement_samplers resolves to this checkout even before devel/setup.bash.
  export ROS_PACKAGE_PATH="$PS_ROOT${ROS_PACKAGE_PATH:+:$ROS_PACKAGE_PATH}"
  export ROS_HOSTNAME=localhost
  unset ROS_IP
}

# Configures and builds into $PS_BUILD. The second configure stores the PYTHONPATH that python
# rostests need (the first one caches it empty). Returns non-zero at the first failing step,
# also when called where bash ignores `set -e` (in an `if`, or left of `||`).
ps_build() {
  local fresh=0
  [ -f "$PS_BUILD/CMakeCache.txt" ] || fresh=1
  cmake -S "$PS_ROOT" -B "$PS_BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null || return 1
  make -C "$PS_BUILD" -j"$(nproc)" all tests || return 1
  if [ "$fresh" -eq 1 ]; then
    cmake "$PS_BUILD" >/dev/null || return 1
  fi
}

# The sample_placements service that `roslaunch placement_samplers placement_server.launch ARGS`
# serves: its name follows the ns:= and name:= arguments, as in the launch file.
ps_service_name() {
  local ns="" name=placement_server a
  for a in "$@"; do
    case "$a" in
      ns:=*) ns=${a#ns:=} ;;
      name:=*) name=${a#name:=} ;;
    esac
  done
  echo "${ns:+/${ns#/}}/$name/sample_placements"
}

# Starts `roslaunch placement_samplers placement_server.launch ARGS...` in the background, its
# output (unbuffered) in the file $PS_LAUNCH_LOG; $PS_LAUNCH_PID is roslaunch's pid. The launch
# file's node is required: roslaunch ends when the node exits, which ps_call watches for.
ps_launch() {
  PS_LAUNCH_LOG=$(mktemp "${TMPDIR:-/tmp}/placement_server_launch.XXXXXX")
  PYTHONUNBUFFERED=1 roslaunch placement_samplers placement_server.launch "$@" \
    >"$PS_LAUNCH_LOG" 2>&1 &
  PS_LAUNCH_PID=$!
}

# Stops what ps_launch started (roslaunch stops its nodes, and the master when it started one)
# and removes the log. Safe to call twice and from an exit trap under `set -e`.
ps_stop_launch() {
  if [ -n "${PS_CLIENT_PID:-}" ]; then
    kill "$PS_CLIENT_PID" 2>/dev/null || true
    wait "$PS_CLIENT_PID" 2>/dev/null || true
    PS_CLIENT_PID=""
  fi
  if [ -n "${PS_LAUNCH_PID:-}" ]; then
    kill -INT "$PS_LAUNCH_PID" 2>/dev/null || true
    wait "$PS_LAUNCH_PID" 2>/dev/null || true
    PS_LAUNCH_PID=""
  fi
  if [ -n "${PS_LAUNCH_LOG:-}" ]; then
    rm -f "$PS_LAUNCH_LOG"
    PS_LAUNCH_LOG=""
  fi
}

# Runs `sample_client.py --service SERVICE CLIENT_ARGS...` against the server ps_launch started
# and returns the client's status (0 = placed, 1 = not placed). When roslaunch ends first (the
# node exited at start-up, e.g. an invalid configuration), it stops the client at once, prints
# the node's FATAL line (or the end of roslaunch's output) on stderr and returns 2.
ps_call() {
  local service=$1 done_pid="" status=0
  shift
  rosrun placement_samplers sample_client.py --service "$service" "$@" &
  PS_CLIENT_PID=$!
  wait -n -p done_pid "$PS_CLIENT_PID" "$PS_LAUNCH_PID" || status=$?
  if [ "$done_pid" = "$PS_CLIENT_PID" ]; then
    PS_CLIENT_PID=""
    return "$status"
  fi
  PS_LAUNCH_PID=""  # reaped
  # SIGKILL: a client told to stop would still say "not available", which is not the reason.
  kill -KILL "$PS_CLIENT_PID" 2>/dev/null || true
  wait "$PS_CLIENT_PID" 2>/dev/null || true
  PS_CLIENT_PID=""
  local fatal
  # rosconsole colours the line: the escapes go.
  fatal=$(sed 's/\x1b\[[0-9;]*m//g' "$PS_LAUNCH_LOG" | grep -m 5 -E '^\[FATAL\]' || true)
  {
    echo "the placement server exited before serving $service:"
    if [ -n "$fatal" ]; then
      echo "$fatal"
    else
      tail -n 15 "$PS_LAUNCH_LOG"
    fi
  } >&2
  return 2
}

# Sources the build's devel/setup.bash (it fails under set -u).
ps_source() {
  set +u
  # shellcheck disable=SC1091
  source "$PS_BUILD/devel/setup.bash"
  set -u
}

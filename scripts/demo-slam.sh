#!/usr/bin/env bash
# Demonstration 1 of docs/demos.md: SLAM in an office, end to end over ROS 1.
# Run scripts/demo-slam.sh --help for what it does.
set -euo pipefail

usage() {
  cat <<'EOF'
Usage: scripts/demo-slam.sh [--out DIR] [--duration S] [--rate R]

SLAM in an office over ROS 1, as in the seed paper's Fig. 4. The script starts, each in its
own process group and all on a private ROS master (a free port, its own ROS_HOME):

  roscore             on a free port (never 11311), /use_sim_time true
  rescuesim run       worlds/office.yaml --ros1 --use-sim-time: the simulator, paced to the
                      wall clock x R; publishes /scan, /odom, /tf, /clock, /ground_truth/pose
  slam_node           ICP scan-matching SLAM (MRPT): /scan + /odom -> /map, map -> odom on /tf
  route_node          scripted tele-operation: drives examples/ros1/slam/office_route.txt
                      (a loop round the open-plan area, the four offices, the meeting room)
  slam_recorder       at sim time S saves the map and the true, odometry and SLAM trajectories

then stops them all and scores the run against the world's ground truth (slam_eval).

Options:
  --out DIR        output folder (default runs/demo-slam)
  --duration S     sim seconds to map for (default 240; the whole route takes about 225)
  --rate R         sim seconds per wall second (default 1: realtime; 2 maps twice as fast)
  -h, --help       this text

Outputs in DIR:
  map.pgm, map.yaml    the SLAM map in map_server's format (rosrun map_server map_server map.yaml)
  map.png              the same map as a picture
  slam.png             ground-truth floor plan | SLAM map | trajectories (truth, SLAM, odometry)
  slam_metrics.json    occupied-cell precision and recall against the true floor plan (one cell
                       tolerance), ATE RMSE of map -> base_link against /ground_truth/pose, the
                       alignment used, sim and wall time
  trajectory.csv       the paired trajectories; sim/ (the simulator's outputs); logs/ (each process)

Binaries come from $BUILD/bin (default: build/bin of this repository; build with 'make').
Ctrl-C stops everything; no process is left behind. Exit code 0 on success, 1 when a part
fails, 2 on bad arguments.

Example:
  scripts/demo-slam.sh --duration 60 --rate 2 --out /tmp/slam
EOF
}

die_usage() { echo "demo-slam: $1 (see --help)" >&2; exit 2; }

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=runs/demo-slam
duration=240
rate=1
is_number() { [[ $1 =~ ^[0-9]+([.][0-9]+)?$ ]] && awk -v v="$1" 'BEGIN { exit !(v > 0) }'; }
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --out) [ $# -ge 2 ] && [ -n "$2" ] || die_usage "--out needs a folder"; out=$2; shift 2 ;;
    --out=*) out=${1#*=}; [ -n "$out" ] || die_usage "--out needs a folder"; shift ;;
    --duration|--rate)
      [ $# -ge 2 ] || die_usage "$1 needs a number"
      is_number "$2" || die_usage "$1 must be a positive number, got '$2'"
      if [ "$1" = --duration ]; then duration=$2; else rate=$2; fi
      shift 2 ;;
    --duration=*|--rate=*)
      v=${1#*=}; is_number "$v" || die_usage "${1%%=*} must be a positive number, got '$v'"
      if [[ $1 == --duration=* ]]; then duration=$v; else rate=$v; fi
      shift ;;
    *) die_usage "unknown argument '$1'" ;;
  esac
done

# the parts: our binaries, ROS's tools
bin=${BUILD:-$repo/build}/bin
for b in rescuesim slam_node route_node slam_recorder slam_eval; do
  if [ ! -x "$bin/$b" ]; then
    echo "demo-slam: $bin/$b not found: build first ('make', or set BUILD to your build folder);" >&2
    echo "  slam_node needs MRPT and roscpp (scripts/install-deps.sh installs them)" >&2
    exit 1
  fi
done
for t in roscore rosparam python3; do
  command -v "$t" >/dev/null || { echo "demo-slam: '$t' not found (scripts/install-deps.sh installs ROS 1)" >&2; exit 1; }
done

mkdir -p "$out/logs"
out=$(cd "$out" && pwd)
rm -f "$out"/{map.pgm,map.yaml,map.png,slam.png,slam_metrics.json,trajectory.csv}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/demo-slam.XXXXXX")

# every child runs in its own process group (job control), so stopping a group stops
# everything that child started; on any exit, Ctrl-C or kill, every group is stopped, newest
# first, so that the master outlives the nodes that talk to it
pids=()
stop_group() {  # stop_group PID SECONDS: SIGINT to the group, SIGKILL when it lingers
  local pid=$1 i
  kill -INT -- "-$pid" 2>/dev/null || return 0
  for ((i = 0; i < $2 * 10; i++)); do
    kill -0 -- "-$pid" 2>/dev/null || return 0
    sleep 0.1
  done
  kill -KILL -- "-$pid" 2>/dev/null || true
}
cleanup() {
  local rc=$? i
  trap - EXIT INT TERM
  set +e
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do stop_group "${pids[i]}" 10; done
  wait 2>/dev/null
  rm -rf "$tmp"
  exit "$rc"
}
trap cleanup EXIT
trap 'echo "demo-slam: interrupted" >&2; exit 130' INT TERM

start() {  # start NAME CMD...: runs CMD in the background in its own process group, output to logs/NAME.log
  local name=$1; shift
  set -m
  "$@" >"$out/logs/$name.log" 2>&1 &
  set +m
  pids+=($!)
  eval "pid_$name=$!"
}
alive() { kill -0 "$1" 2>/dev/null; }
log_tail() { echo "---- last lines of logs/$1.log:" >&2; tail -n 15 "$out/logs/$1.log" >&2 || true; }

# a private ROS master: a free port, its own ROS_HOME and log folder
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI=http://localhost:$port ROS_HOSTNAME=localhost ROS_HOME=$tmp/ros ROS_LOG_DIR=$tmp/ros/log
export ROSCONSOLE_STDOUT_LINE_BUFFERED=1  # the logs, and so the progress lines, as they happen
unset ROS_IP ROS_NAMESPACE
echo "demo-slam: roscore on port $port; outputs in $out"
t0=$(date +%s.%N)
start roscore roscore -p "$port"
for i in $(seq 100); do
  rosparam set /use_sim_time true >/dev/null 2>&1 && break
  alive "$pid_roscore" || { log_tail roscore; echo "demo-slam: roscore failed" >&2; exit 1; }
  [ "$i" -eq 100 ] && { log_tail roscore; echo "demo-slam: roscore did not answer in 20 s" >&2; exit 1; }
  sleep 0.2
done

# the ROS nodes wait for /clock; then the simulator (a little longer than the recording)
start slam_recorder "$bin/slam_recorder" "_out:=$out" "_duration:=$duration"
start slam_node "$bin/slam_node"
start route_node "$bin/route_node" "_route:=$repo/examples/ros1/slam/office_route.txt"
sleep 1
sim_duration=$(awk -v d="$duration" 'BEGIN { print d + 3 }')
start rescuesim "$bin/rescuesim" run "$repo/worlds/office.yaml" --ros1 --use-sim-time --rate "$rate" \
  --duration "$sim_duration" --no-cameras -q --out "$out/sim"
echo "demo-slam: mapping for $duration s of sim time at ${rate}x realtime (logs in $out/logs)"

# progress until the recorder has written the map and trajectories
last=""
while alive "$pid_slam_recorder"; do
  for p in rescuesim slam_node; do
    pv=pid_$p
    if ! alive "${!pv}"; then log_tail "$p"; echo "demo-slam: $p stopped early" >&2; exit 1; fi
  done
  line=$(grep -a -o 'slam_recorder: t = .*' "$out/logs/slam_recorder.log" | tail -n 1 || true)
  line=${line%%$'\e'*}  # without rosconsole's colour codes
  if [ -n "$line" ] && [ "$line" != "$last" ]; then
    echo "demo-slam: ${line#slam_recorder: }"
    last=$line
  fi
  sleep 1
done
if ! wait "$pid_slam_recorder"; then log_tail slam_recorder; echo "demo-slam: slam_recorder failed" >&2; exit 1; fi
t1=$(date +%s.%N)
wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')
grep -a -h 'route done\|skipped' "$out/logs/route_node.log" | sed -e 's/^.*route_node: /demo-slam: route: /' -e 's/\x1b\[[0-9;]*m//g' || true
echo "demo-slam: recorded $duration s of sim time in $wall s wall time; scoring"

"$bin/slam_eval" --scenario "$repo/worlds/office.yaml" --run "$out" --out "$out" --wall-time "$wall" --rate "$rate"
echo "demo-slam: done: $out/slam.png, $out/slam_metrics.json, $out/map.pgm + map.yaml"

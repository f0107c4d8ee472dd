#!/usr/bin/env bash
# Demonstration 2 (docs/demos.md): autonomous navigation through a seeded random maze over ROS 1.
# The simulator and the navigation node (examples/ros1/nav) are separate processes that talk only
# through a private roscore; the simulator judges when victims are seen and ends the run.
set -euo pipefail

usage() {
  cat <<'EOF'
demo-nav.sh: autonomous navigation in a maze over ROS 1 (the seed's Demonstration 2)

Usage: scripts/demo-nav.sh [--seed N] [--trials N] [--out DIR] [--duration S] [--rate R | --sync]
                           [--size N] [--victims N] [--loops F]

What it does, per trial (maze seed N, N+1, ...):
  1. a private roscore on a free port (never 11311), with its own ROS_HOME and ROS_LOG_DIR;
  2. the navigation node rescuesim_nav: the simulator's built-in explorer (wall following, and A*
     to the nearest frontier when stuck) as a ROS node: /scan, /odom, /tf_static in; /cmd_vel,
     /nav/path, /nav/map out;
  3. the simulator: 'rescuesim run --ros1 --use-sim-time --rate R' on a generated maze with
     rubble and raised areas as in the default scenario, and victims in dead ends first; the
     built-in controllers are off (ROS drives the robot). It judges victims itself (seen when in
     the thermal camera's field of view, within its range, with nothing in between) and
     stops when every victim has been seen or after S seconds of sim time;
  4. DIR/nav_metrics.json (success, time each victim was first seen, distance, collisions) and
     DIR/path.png (true path, every A* route, the last one bold), like the seed's Fig. 5.
With --trials N > 1, trial i goes to DIR/seed-<N+i>/ and a table of all of them to the terminal,
DIR/nav_trials.json and DIR/nav_trials.md (success rate, median time to find every victim).

Options:
  --seed N      maze and run seed of the first trial (default 1)
  --trials N    number of seeded mazes (default 1)
  --out DIR     output folder (default runs/demo-nav)
  --duration S  time limit per trial, s of sim time (default 300)
  --sync        lockstep, synchronous with the node: after each scan the simulator waits for the
                node's cmd_vel (rescuesim run --sync), so a trial runs as fast as the node answers
                (a 300 s trial in about 6 s) and repeats exactly; the default with --trials > 1
  --rate R      sim seconds per wall second (default 5; lower it if the node cannot keep up:
                nav_metrics.json says what share of the scans the node used)
  --size N      maze of N x N cells of 1.5 m (default 6; the default scenario's is 8; 2 .. 30)
  --victims N   victims in the maze (default 3)
  --loops F     fraction of inner walls opened beyond a perfect maze, 0 .. 1 (default 0.15, as the
                default scenario; 0: a perfect maze, with no island a wall follower could circle)

  -h, --help    this text

Binaries are taken from $BUILD/bin (default build/bin): run 'make' first.
Ctrl-C stops everything (every process it started is ended) and keeps what was written.
Exit codes: 0 every trial ran (whether or not the robot succeeded), 1 a process failed,
2 bad arguments.

Examples:
  scripts/demo-nav.sh                            one maze, outputs in runs/demo-nav/
  scripts/demo-nav.sh --seed 5 --rate 2          another maze, slower
  scripts/demo-nav.sh --trials 20 --out runs/nav20
EOF
}

die_usage() {
  echo "demo-nav: $1 (see --help)" >&2
  exit 2
}

seed=1 trials=1 out=runs/demo-nav duration=300 rate=5 size=6 victims=3 loops=0.15 sync=0 rate_given=0
is_uint() { [[ "$1" =~ ^[0-9]+$ ]]; }
is_pos_number() { [[ "$1" =~ ^([0-9]+\.?[0-9]*|\.[0-9]+)$ ]] && awk -v x="$1" 'BEGIN { exit !(x > 0) }'; }
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --sync) sync=1; shift ;;
    --seed|--trials|--out|--duration|--rate|--size|--victims|--loops)
      [ $# -ge 2 ] || die_usage "$1 needs a value"
      opt="$1" val="$2"; shift 2
      case "$opt" in
        --seed) is_uint "$val" || die_usage "--seed wants a whole number >= 0, not '$val'"; seed=$val ;;
        --trials) { is_uint "$val" && [ "$val" -ge 1 ] && [ "$val" -le 1000 ]; } || die_usage "--trials wants 1 .. 1000, not '$val'"; trials=$val ;;
        --out) [ -n "$val" ] || die_usage "--out wants a folder"; out=$val ;;
        --duration) is_pos_number "$val" || die_usage "--duration wants seconds > 0, not '$val'"; duration=$val ;;
        --rate) { is_pos_number "$val" && awk -v x="$val" 'BEGIN { exit !(x <= 100) }'; } || die_usage "--rate wants a number in (0, 100], not '$val'"; rate=$val rate_given=1 ;;
        --size) { is_uint "$val" && [ "$val" -ge 2 ] && [ "$val" -le 30 ]; } || die_usage "--size wants 2 .. 30 cells, not '$val'"; size=$val ;;
        --loops) { [[ "$val" =~ ^([0-9]+\.?[0-9]*|\.[0-9]+)$ ]] && awk -v x="$val" 'BEGIN { exit !(x <= 1) }'; } || die_usage "--loops wants a fraction 0 .. 1, not '$val'"; loops=$val ;;
        --victims) { is_uint "$val" && [ "$val" -ge 1 ] && [ "$val" -le 50 ]; } || die_usage "--victims wants 1 .. 50, not '$val'"; victims=$val ;;
      esac ;;
    *) die_usage "unknown argument '$1'" ;;
  esac
done
# several trials run synchronously (lockstep with the node, repeatable) unless a pace is asked for
if [ "$trials" -gt 1 ] && [ "$rate_given" = 0 ]; then sync=1; fi
if [ "$sync" = 1 ] && [ "$rate_given" = 1 ]; then die_usage "--sync and --rate exclude each other"; fi
# rate 0 in the records means synchronous
pace_text="rate ${rate}x"
if [ "$sync" = 1 ]; then rate=0 pace_text="synchronous (lockstep with the node)"; fi

# the binaries: $BUILD/bin, else build/bin of this checkout
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="${BUILD:-$root/build}/bin"
for b in rescuesim rescuesim_nav rescuesim_nav_plot; do
  if [ ! -x "$bin/$b" ]; then
    echo "demo-nav: $bin/$b is missing: run 'make' first (or set BUILD to your build folder)" >&2
    exit 1
  fi
done
for c in roscore python3; do
  command -v "$c" >/dev/null 2>&1 || { echo "demo-nav: '$c' is missing: run scripts/install-deps.sh" >&2; exit 1; }
done
mkdir -p "$out"
out="$(cd "$out" && pwd)"

# every child runs in a process group of its own; all of them end with this script
groups=()
stop_group() {
  local g=$1
  kill -TERM -- "-$g" 2>/dev/null || return 0
  for _ in $(seq 50); do
    kill -0 -- "-$g" 2>/dev/null || return 0
    sleep 0.1
  done
  kill -KILL -- "-$g" 2>/dev/null || true
}
cleanup() {
  local g
  for ((i = ${#groups[@]} - 1; i >= 0; i--)); do
    g=${groups[$i]}
    [ -n "$g" ] && stop_group "$g"
  done
  groups=()
  [ -n "${ros_dir:-}" ] && rm -rf "$ros_dir"
  return 0
}
interrupted() {
  echo >&2
  echo "demo-nav: interrupted; stopping every process it started" >&2
  cleanup
  exit 130
}
trap cleanup EXIT
trap interrupted INT TERM
# starts "$@" in a new process group (its id is the child's pid) and sets $started
start_group() {
  setsid "$@" &
  started=$!
  groups+=("$started")
}
forget_group() {
  local keep=() g
  for g in "${groups[@]}"; do [ "$g" != "$1" ] && keep+=("$g"); done
  groups=("${keep[@]+"${keep[@]}"}")
}

# a private ROS master on a free port, with its own home and log folder
ros_dir="$(mktemp -d "${TMPDIR:-/tmp}/demo-nav-ros.XXXXXX")"
export ROS_HOME="$ros_dir/home" ROS_LOG_DIR="$ros_dir/log" ROS_HOSTNAME=localhost
mkdir -p "$ROS_HOME" "$ROS_LOG_DIR"
port_is_open() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
master_up=0
for attempt in 1 2 3 4 5; do
  port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  [ "$port" = 11311 ] && continue
  export ROS_MASTER_URI="http://localhost:$port"
  start_group roscore -p "$port" >"$out/roscore.log" 2>&1
  roscore_group=$started
  for _ in $(seq 150); do
    if port_is_open "$port"; then master_up=1; break; fi
    kill -0 "$roscore_group" 2>/dev/null || break
    sleep 0.1
  done >"$ros_dir/roscore-wait.log" 2>&1
  [ $master_up = 1 ] && break
  stop_group "$roscore_group"; forget_group "$roscore_group"
done
if [ $master_up != 1 ]; then
  echo "demo-nav: roscore did not start (see $out/roscore.log)" >&2
  exit 1
fi
echo "demo-nav: roscore at $ROS_MASTER_URI; $trials trial(s) of a ${size}x${size} maze (loops $loops) with $victims victim(s), limit ${duration} s, $pace_text"

# one trial: maze seed $1 into folder $2
run_trial() {
  local s=$1 dir=$2 label=$3
  mkdir -p "$dir"
  rm -f "$dir/nav_metrics.json" "$dir/path.png" "$dir/nav_node.json"
  local rubble raised
  rubble=$(( (12 * size * size + 32) / 64 ))
  cat >"$dir/scenario.yaml" <<EOF
# Demonstration 2 (scripts/demo-nav.sh): the default scenario's kind of maze, seeded; the run
# stops when every victim has been seen.
name: demo-nav
seed: $s
duration: $duration
stop_when_all_found: true
world:
  maze:
    cols: $size
    rows: $size
    cell_size: 1.5
    loop_fraction: $loops
    rubble: $rubble
    raised_fraction: 0.08
    victims: $victims
    start_cell: [0, 0]
robots:
  - name: robot
    model: rescue_robot
    controller: explorer
EOF
  # the node first, so that it is listening when the simulator starts
  start_group "$bin/rescuesim_nav" --out "$dir/nav_node.json" >"$dir/nav_node.log" 2>&1
  local node=$started
  # paced (--rate), or lockstep and synchronous with the node (--sync: each scan waits for its cmd_vel)
  local pace=(--rate "$rate")
  [ "$sync" = 1 ] && pace=(--sync)
  start_group "$bin/rescuesim" run "$dir/scenario.yaml" --seed "$s" --ros1 --use-sim-time "${pace[@]}" \
    --duration "$duration" --no-cameras --out "$dir/sim" >"$dir/sim.log" 2>&1
  local sim=$started
  local t0=$SECONDS next=$((SECONDS + 5)) line last=""
  while kill -0 "$sim" 2>/dev/null; do
    if ! kill -0 "$node" 2>/dev/null; then
      echo "demo-nav: $label: the navigation node stopped early (see $dir/nav_node.log)" >&2
      break
    fi
    if [ $SECONDS -ge $next ]; then
      line=$(tr '\r' '\n' <"$dir/sim.log" | grep -E 'victims [0-9]+/' | tail -n 1 | sed -E 's/^\[[-#]*\] *//')
      if [ -n "$line" ] && [ "$line" != "$last" ]; then
        echo "  $label: ${line}  ($((SECONDS - t0)) s wall)"
        last=$line
      fi
      next=$((SECONDS + 5))
    fi
    sleep 0.2
  done
  local sim_rc=0
  wait "$sim" || sim_rc=$?
  forget_group "$sim"
  # the node writes its record when it is told to stop
  stop_group "$node"; wait "$node" 2>/dev/null || true
  forget_group "$node"
  if [ $sim_rc -ne 0 ] || [ ! -f "$dir/sim/summary.json" ]; then
    echo "demo-nav: $label: the simulator failed (exit $sim_rc); see $dir/sim.log" >&2
    return 1
  fi
  if [ ! -f "$dir/nav_node.json" ]; then
    echo "demo-nav: $label: the navigation node left no record; see $dir/nav_node.log" >&2
    return 1
  fi
  python3 - "$dir" "$rate" <<'PY'
import json, os, sys
d, rate = sys.argv[1], float(sys.argv[2])
s = json.load(open(os.path.join(d, "sim", "summary.json")))
n = json.load(open(os.path.join(d, "nav_node.json")))
victims = s.get("victims", [])
found = [v for v in victims if v.get("found")]
success = len(victims) > 0 and len(found) == len(victims)
times = [v.get("time_s") for v in found]
m = {
    "success": success,
    "time_to_finish_s": max(times) if success else None,
    "victims_total": len(victims),
    "victims_found": len(found),
    "victims": [{"name": v.get("name"), "found": bool(v.get("found")), "time_s": v.get("time_s") if v.get("found") else None} for v in victims],
    "victim_judge": "the simulator (summary.json): " + str(s.get("victim_detection", "?")),
    "stop_reason": s.get("stop_reason"),
    "sim_time_s": s.get("sim_time_s"),
    "wall_time_s": s.get("wall_time_s"),
    "rate": rate,
    "distance_m": s.get("distance_m"),
    "collisions": s.get("collisions"),
    "coverage": s.get("coverage"),
    "seed": s.get("seed"),
    "node": {k: n.get(k) for k in ("controller", "scans", "commands", "step_ms_mean", "step_ms_max", "mode", "exploration_complete", "stats")},
    "planned_paths": len(n.get("paths", [])),
}
# did the node keep up? every scan the simulator published should have reached it
scans_out = (s.get("message_counts") or {}).get("/scan")
if scans_out:
    m["scans_published"] = scans_out
    m["scans_used_fraction"] = round((n.get("scans") or 0) / scans_out, 3)
tmp = os.path.join(d, ".nav_metrics.json.tmp")
with open(tmp, "w") as f:
    json.dump(m, f, indent=1)
    f.write("\n")
os.replace(tmp, os.path.join(d, "nav_metrics.json"))
PY
  local title
  title=$(python3 -c 'import json,sys; m=json.load(open(sys.argv[1])); print("seed %s: %d/%d victims in %.0f s, %.1f m, %d collisions" % (m["seed"], m["victims_found"], m["victims_total"], m["sim_time_s"], m["distance_m"], m["collisions"]))' "$dir/nav_metrics.json")
  "$bin/rescuesim_nav_plot" --run "$dir/sim" --nav "$dir/nav_node.json" --out "$dir/path.png" --title "$title" >/dev/null
  echo "  $title -> $dir/{nav_metrics.json,path.png}"
}

failed=0
for ((i = 0; i < trials; i++)); do
  s=$((seed + i))
  if [ "$trials" -eq 1 ]; then dir="$out"; else dir="$out/seed-$s"; fi
  echo "trial $((i + 1))/$trials: seed $s"
  run_trial "$s" "$dir" "seed $s" || failed=$((failed + 1))
done

if [ "$trials" -gt 1 ]; then
  python3 - "$out" "$seed" "$trials" "$duration" "$rate" "$size" "$victims" <<'PY'
import json, os, statistics, sys
out, seed, trials, duration, rate, size, victims = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5]), int(sys.argv[6]), int(sys.argv[7])
rows = []
for i in range(trials):
    p = os.path.join(out, "seed-%d" % (seed + i), "nav_metrics.json")
    m = json.load(open(p)) if os.path.exists(p) else None
    rows.append((seed + i, m))
ran = [m for _, m in rows if m]
ok = [m for m in ran if m["success"]]
times = [m["time_to_finish_s"] for m in ok]
summary = {
    "trials": trials, "ran": len(ran), "successes": len(ok),
    "success_rate": len(ok) / trials,
    "median_time_to_finish_s": statistics.median(times) if times else None,
    "median_victims_found": statistics.median([m["victims_found"] for m in ran]) if ran else None,
    "median_distance_m": statistics.median([m["distance_m"] for m in ran]) if ran else None,
    "mean_collisions": statistics.mean([m["collisions"] for m in ran]) if ran else None,
    "settings": {"first_seed": seed, "duration_s": duration, "rate": rate, "maze": "%dx%d" % (size, size), "victims": victims},
    "victim_judge": ran[0]["victim_judge"] if ran else None,
    "per_trial": [{"seed": s, **({k: m[k] for k in ("success", "time_to_finish_s", "victims_found", "victims_total", "sim_time_s", "distance_m", "collisions")} if m else {"success": False, "error": "did not run"})} for s, m in rows],
}
lines = ["| seed | success | victims | time to finish (s) | distance (m) | collisions |", "|---:|:---:|:---:|---:|---:|---:|"]
for s, m in rows:
    if m is None:
        lines.append("| %d | error | - | - | - | - |" % s)
        continue
    t = "%.1f" % m["time_to_finish_s"] if m["success"] else "- (limit %.0f)" % m["sim_time_s"]
    lines.append("| %d | %s | %d/%d | %s | %.1f | %d |" % (s, "yes" if m["success"] else "no", m["victims_found"], m["victims_total"], t, m["distance_m"], m["collisions"]))
med = summary["median_time_to_finish_s"]
lines.append("")
lines.append("Success: %d/%d (%.0f%%); median time to find every victim (successful trials): %s; %dx%d mazes, %d victims, limit %.0f s, %s." % (
    len(ok), trials, 100.0 * len(ok) / trials, "%.1f s" % med if med is not None else "-", size, size, victims, duration,
    "synchronous" if rate == 0 else "rate %gx" % rate))
md = "\n".join(lines) + "\n"
for name, text in (("nav_trials.json", json.dumps(summary, indent=1) + "\n"), ("nav_trials.md", md)):
    tmp = os.path.join(out, "." + name + ".tmp")
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, os.path.join(out, name))
print()
print(md, end="")
print("wrote %s/{nav_trials.json,nav_trials.md}" % out)
PY
fi
[ $failed -eq 0 ] || { echo "demo-nav: $failed trial(s) failed to run" >&2; exit 1; }

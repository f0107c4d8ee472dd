#!/usr/bin/env bash
# The short Demonstration 2: three seeded 4x4 perfect mazes (rubble and raised areas as usual)
# with two victims each, through scripts/demo-nav.sh exactly as a user runs it.
# Usage: nav_demo_test.sh SOURCE_DIR BUILD_DIR OUT_DIR
#
# Why these numbers: with the same explorer in-process ('rescuesim batch', lockstep), such mazes
# were searched fully within 150 s in 19 of seeds 1..20 (median 63 s) when it followed walls
# first; over ROS the run is not bit-for-bit repeatable (message timing), so the test asks for
# 2 of 3. Mazes 3-5: since the explorer drives to frontiers first, maze 2's two victims come into
# view as it turns at the start (both found at 1.2 s, 0.1 m driven), too short a trial to check
# the driving and the node's share of the scans.
set -euo pipefail
src=$1 build=$2 out=$3
rm -rf "$out"
seed=3        # mazes 3, 4, 5
duration=150  # s of sim time per maze
# synchronous (the default with --trials): lockstep with the node, so a trial repeats exactly
BUILD="$build" "$src/scripts/demo-nav.sh" --seed $seed --trials 3 --size 4 --victims 2 --loops 0 \
  --duration $duration --out "$out"
# determinism over ROS: the first maze again, synchronous, drives exactly the same path
BUILD="$build" "$src/scripts/demo-nav.sh" --seed $seed --sync --size 4 --victims 2 --loops 0 \
  --duration $duration --out "$out/again"
cmp "$out/seed-$seed/sim/trajectory.csv" "$out/again/sim/trajectory.csv" || {
  echo "FAILED: a synchronous run of seed $seed did not repeat its trajectory exactly"; exit 1; }

python3 - "$out" $duration <<'PY'
import json, os, sys
out, duration = sys.argv[1], float(sys.argv[2])
t = json.load(open(os.path.join(out, "nav_trials.json")))
problems = []
def check(cond, what):
    if not cond:
        problems.append(what)
check(t["trials"] == 3 and t["ran"] == 3, "all three trials ran: %s" % t)
check(t["successes"] >= 2, "at least 2 of 3 mazes fully searched, got %d" % t["successes"])
check(os.path.exists(os.path.join(out, "nav_trials.md")), "nav_trials.md written")
for seed in (3, 4, 5):
    d = os.path.join(out, "seed-%d" % seed)
    m = json.load(open(os.path.join(d, "nav_metrics.json")))
    tag = "seed %d: " % seed
    check(m["victims_total"] == 2, tag + "2 victims in the maze, got %s" % m["victims_total"])
    found_times = [v["time_s"] for v in m["victims"] if v["found"]]
    check(len(found_times) == m["victims_found"], tag + "a time for every victim found")
    check(all(0 <= x <= m["sim_time_s"] + 1e-6 for x in found_times), tag + "victims found within the run: %s" % found_times)
    if m["success"]:
        # the simulator's own stop rule ended the run when the last victim was seen
        check(m["stop_reason"] == "all victims found", tag + "stopped by the simulator's rule, got %r" % m["stop_reason"])
        check(abs(m["time_to_finish_s"] - max(found_times)) < 1e-6, tag + "time to finish = last victim's time")
        check(m["sim_time_s"] <= duration, tag + "finished within the limit")
    else:
        check(abs(m["sim_time_s"] - duration) < 0.1, tag + "a failed run lasts the whole limit, got %s" % m["sim_time_s"])
    # the robot drove, and no faster than its 1.0 m/s limit allows
    check(1.0 < m["distance_m"] <= 1.0 * m["sim_time_s"], tag + "distance %.1f m in %.1f s" % (m["distance_m"], m["sim_time_s"]))
    check(0 <= m["collisions"] <= 30, tag + "collisions %s (0 .. 30)" % m["collisions"])
    # the node answered the scans: one command per scan, and it saw nearly all of them
    n = m["node"]
    check(n["commands"] == n["scans"] and n["scans"] > 0, tag + "one command per scan: %s" % n)
    # (synchronous: the simulator waits for the node's answer to each scan; only scans before
    # the node connected go unanswered)
    check(m.get("scans_used_fraction", 0) >= 0.95, tag + "the node used >= 95%% of the scans, got %s" % m.get("scans_used_fraction"))
    with open(os.path.join(d, "path.png"), "rb") as f:
        check(f.read(8) == b"\x89PNG\r\n\x1a\n", tag + "path.png is a PNG")
if problems:
    print("FAILED:\n  " + "\n  ".join(problems))
    sys.exit(1)
print("demo-nav: %d/3 mazes searched fully; median %.1f s; every metric sane" % (t["successes"], t["median_time_to_finish_s"] or -1))
PY

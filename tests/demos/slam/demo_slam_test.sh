#!/usr/bin/env bash
# ctest demo_slam: runs scripts/demo-slam.sh for 60 s of sim time at 2x realtime and checks
# that the map and the trajectory meet thresholds a working SLAM meets and a broken one does
# not: occupied-cell precision and recall >= 0.8 (one cell tolerance), start-aligned ATE
# below 0.15 m (measured runs: see docs/demos.md). Outputs stay in $1 for inspection.
set -euo pipefail
out=${1:?usage: demo_slam_test.sh OUT_DIR}
src=${RESCUESIM_SOURCE_DIR:-$(cd "$(dirname "$0")/../../.." && pwd)}
rm -rf "$out"
"$src/scripts/demo-slam.sh" --duration 60 --rate 2 --out "$out"
python3 - "$out/slam_metrics.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
p, r, ate = m["occupancy"]["precision"], m["occupancy"]["recall"], m["ate"]["rmse_m"]
checks = [("precision", p, p >= 0.8, ">= 0.8"), ("recall", r, r >= 0.8, ">= 0.8"),
          ("ATE RMSE (m)", ate, ate < 0.15, "< 0.15"),
          ("sim time (s)", m["sim_time_s"], m["sim_time_s"] >= 55, ">= 55")]
bad = 0
for name, value, ok, want in checks:
    print(f"demo_slam: {name} = {value:.3f} (want {want}) {'ok' if ok else 'FAILED'}")
    bad += not ok
sys.exit(1 if bad else 0)
PY

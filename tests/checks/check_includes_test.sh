#!/usr/bin/env bash
# The include check (scripts/check-includes.sh) against planted trees and a fixture table in
# the format of docs/architecture.md §3 (so that row changes there do not move this test): a
# clean tree passes, and each planted bad include is reported with its file:line, so the check
# cannot pass by seeing nothing.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
check=$repo/scripts/check-includes.sh
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
table=$tmp/architecture.md
cat > "$table" <<'TABLE'
## 3. Modules

| folder | responsibility | may use |
|---|---|---|
| `src/core` | basics | std, Eigen (no module of ours) |
| `src/world` | worlds | `core`; yaml-cpp; LinearMath (Bullet's hulls) privately: only in `world/mesh`, .cpp only |
| `src/physics` | Bullet adapter | `core`, `world`; Bullet |
| `src/raycast` | rays | `core`, `world`; Embree, TBB |
| `src/msgs` | messages | `core` |
| `src/sim` | simulation | everything above |
| `src/autonomy` | controllers | `core`, `msgs` |
| `src/bridges/{ros1,mcap}` | transports | `sim`, `msgs`; roscpp only in `bridges/ros1` |
| `src/app` | the CLI | all modules |

## 4. Next section

| `src/elsewhere` | not a module row: outside section 3 | `core` |
TABLE
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# a small tree that follows the table
plant() { mkdir -p "$(dirname "$tmp/$1")"; printf '%s\n' "${@:2}" > "$tmp/$1"; }
plant src/core/pose.h '#pragma once' '#include <Eigen/Core>'
plant src/world/world.h '#pragma once' '#include "core/pose.h"'
plant src/world/mesh/mesh_hull.cpp '#include <LinearMath/btConvexHullComputer.h>' '#include "world/world.h"'
plant src/physics/physics.cpp '#include <btBulletDynamicsCommon.h>' '#include "world/world.h"'
plant src/sim/simulation.h '#pragma once' '#include "physics/physics.h"' '#include "core/pose.h"'
plant src/physics/physics.h '#pragma once'
plant src/bridges/ros1/ros1_bridge.cpp '#include <ros/node_handle.h>' '#include "sim/simulation.h"'
plant src/bridges/mcap/mcap_bridge.cpp '#include "sim/simulation.h"' '#include "world/world.h"'
plant src/raycast/ray_scene.cpp '#include <embree3/rtcore.h>' '#include <tbb/parallel_for.h>'
out=$("$check" --table "$table" "$tmp" 2>&1) || fail "clean tree rejected: $out"

# planted violations, one per rule
plant src/core/rng.cpp '#include "core/pose.h"' '#include "sim/simulation.h"'
plant src/world/mesh/mesh.h '#pragma once' '#include <LinearMath/btVector3.h>'
plant src/raycast/bad.cpp '#include <btBulletDynamicsCommon.h>'
plant src/bridges/mcap/mcap_ros1.cpp '#include "bridges/ros1/ros1_bridge.h"'
plant src/bridges/ros1/ros1_bridge.h '#pragma once'
plant src/autonomy/explorer.cpp '#include "msgs/messages.h"' '#include <epoxy/gl.h>' '#include "world/world.h"'
plant src/msgs/messages.h '#pragma once'
plant src/autonomy/astar.cpp '#include <yaml-cpp/yaml.h>  // check-includes: allow'
plant src/app/main.cpp '#include "bridges/ros1/ros1_bridge.h"' '#include "autonomy/astar.h"' '#include "sim/simulation.h"'
plant src/autonomy/astar.h '#pragma once' '#include "msgs/messages.h"'
set +e
out=$("$check" --table "$table" "$tmp" 2>&1)
rc=$?
set -e
[ "$rc" = 1 ] || fail "exit code $rc for a tree with bad includes, expected 1"
expect() { grep -qF -- "$1" <<<"$out" || fail "missing: $1"; }
expect 'src/core/rng.cpp:2: includes "sim/simulation.h" but core may only use'
expect 'src/world/mesh/mesh.h:2: includes <LinearMath/btVector3.h>'
expect 'src/raycast/bad.cpp:1: includes <btBulletDynamicsCommon.h> (bullet) but raycast may only use'
expect 'src/bridges/mcap/mcap_ros1.cpp:1: includes "bridges/ros1/ros1_bridge.h" but bridges/mcap may only use'
expect 'src/autonomy/explorer.cpp:2: includes <epoxy/gl.h> (epoxy) but autonomy may only use'
expect 'src/autonomy/explorer.cpp:3: includes "world/world.h" but autonomy may only use'
expect "src/autonomy/astar.cpp:1: 'check-includes: allow' needs a reason"
n=$(grep -c ': includes \|needs a reason' <<<"$out" || true)
[ "$n" = 7 ] || fail "expected 7 reports, got $n: $out"

# a whitelisted include with a reason passes; a folder with no row is reported
plant src/autonomy/astar.cpp '#include <yaml-cpp/yaml.h>  // check-includes: allow fixture'
rm "$tmp/src/core/rng.cpp" "$tmp/src/world/mesh/mesh.h" "$tmp/src/raycast/bad.cpp" \
   "$tmp/src/bridges/mcap/mcap_ros1.cpp" "$tmp/src/autonomy/explorer.cpp"
out=$("$check" --table "$table" "$tmp" 2>&1) || fail "whitelisted include rejected: $out"
plant src/nowhere/x.cpp '#include "core/pose.h"'
set +e
out=$("$check" --table "$table" "$tmp" 2>&1); rc=$?
set -e
[ "$rc" = 1 ] && grep -qF 'src/nowhere/ is in no module row' <<<"$out" || fail "folder without a row not reported: $out"
plant src/elsewhere/y.cpp '#include "core/pose.h"'
out=$("$check" --table "$table" "$tmp" 2>&1) || true
grep -qF 'src/elsewhere/ is in no module row' <<<"$out" || fail "a table row outside section 3 was read: $out"

# a table that names an unknown module is an error of the table (exit 2)
sed 's/| controllers | `core`, `msgs` |/| controllers | `core`, `messages` |/' "$table" > "$tmp/bad.md"
set +e
out=$("$check" --table "$tmp/bad.md" "$tmp" 2>&1); rc=$?
set -e
[ "$rc" = 2 ] && grep -qF 'may use `messages`, which is not a module row' <<<"$out" || fail "bad table: rc=$rc $out"

[ "$failures" = 0 ] && echo "check_includes_test: all passed"
exit "$failures"

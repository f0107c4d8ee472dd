#!/usr/bin/env bash
# Builds the libFuzzer targets with clang in build-fuzz/ and runs them.
#   scripts/fuzz.sh [seconds] [extra libFuzzer flags...]   one target (FUZZ_TARGET), default 60 s
#   scripts/fuzz.sh --smoke [seconds]                       every target in turn, default 20 s
#                                                           each; exit 1 when any crashed
#   scripts/fuzz.sh --list                                  the targets
# Targets (fuzz/<target>_fuzz.cpp, seeds in fuzz/corpus/<target>):
#   svg_path         the SVG attribute parsers (path, transform, paint, length)
#   svg_world        whole SVG world documents (load_svg_world_from_string)
#   urdf             the URDF importer
#   sdf_world        the SDF importer (whole worlds and models, through sdformat)
#   scenario         scenario YAML (parse_scenario)
#   cdr              the CDR (ROS 2) message decoder, with a round trip
#   ros1             the ROS 1 message decoder, with a round trip
#   mcap_reader      the MCAP reader (open, check, read every message)
#   foxglove_client  Foxglove WebSocket client frames (JSON requests, binary messages)
#   batch_record     one line of a batch's results.jsonl (parse_trial_line), with a round trip
#   datagram_request a comms/send request (parse_send_request), with a round trip
#   control_cdr      the control services' CDR bodies (Simulation Interfaces, SimulateSteps,
#                    parameters), with a round trip
# New inputs go to build-fuzz/corpus/<target>; crashes to build-fuzz/crashes/<target>/. The seed
# corpus in fuzz/corpus/<target> is only read. Inputs that once crashed a target are kept in
# fuzz/crashes/<target>/ and replayed before it runs. Exit code 2 for bad arguments.
set -euo pipefail

targets=(svg_path svg_world urdf sdf_world scenario cdr ros1 mcap_reader foxglove_client batch_record datagram_request control_cdr)
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$root/build-fuzz
jobs=${FUZZ_BUILD_JOBS:-$(nproc 2>/dev/null || echo 2)}

mode=one
case "${1:-}" in
  --smoke) mode=smoke; shift ;;
  --list) printf '%s\n' "${targets[@]}"; exit 0 ;;
  -h | --help) sed -n '2,22p' "$0"; exit 0 ;;
esac
seconds=${1:-$([ "$mode" = smoke ] && echo 20 || echo 60)}
shift || true
if ! [[ "$seconds" =~ ^[0-9]+$ ]]; then
  echo "fuzz.sh: seconds must be a whole number, got '$seconds'" >&2; exit 2
fi
if [ "$mode" = smoke ]; then
  run=("${targets[@]}")
else
  target=${FUZZ_TARGET:-svg_path}
  if ! printf '%s\n' "${targets[@]}" | grep -qx -- "$target"; then
    echo "fuzz.sh: unknown FUZZ_TARGET '$target' (known: ${targets[*]})" >&2; exit 2
  fi
  run=("$target")
fi

# configure (clang, no tests, benchmarks or optional bridges) and build only the fuzz targets
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DRESCUESIM_FUZZ=ON -DRESCUESIM_TESTS=OFF -DRESCUESIM_BENCH=OFF \
  -DRESCUESIM_ROS1=OFF -DRESCUESIM_ROS2=OFF -DRESCUESIM_PYTHON=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target "${run[@]/%/_fuzz}"

# run: the working corpus first (libFuzzer writes there), the seeds after it
crashed=()
for target in "${run[@]}"; do
  corpus=$build/corpus/$target
  crashes=$build/crashes/$target
  mkdir -p "$corpus" "$crashes"
  # known crashing inputs (fuzz/crashes/<target>/) first: each must now run clean
  known=()
  if [ -d "$root/fuzz/crashes/$target" ]; then
    mapfile -t known < <(find "$root/fuzz/crashes/$target" -type f | sort)
  fi
  if [ "${#known[@]}" -gt 0 ]; then
    echo "== $target: ${#known[@]} known crash input(s) from fuzz/crashes/$target"
    if ! "$build/bin/${target}_fuzz" -runs=1 "${known[@]}"; then
      crashed+=("$target")
      continue
    fi
  fi
  echo "== $target: ${seconds}s"
  if ! "$build/bin/${target}_fuzz" -max_total_time="$seconds" -max_len=65536 -timeout=10 \
      -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$crashes/" "$@" \
      "$corpus" "$root/fuzz/corpus/$target"; then
    crashed+=("$target")
  fi
done
if [ "${#crashed[@]}" -gt 0 ]; then
  echo "fuzz.sh: crashes in: ${crashed[*]} (inputs in $build/crashes/<target>/)" >&2
  exit 1
fi

#!/usr/bin/env bash
# Builds a libFuzzer target with clang in build-fuzz/ and runs it for N seconds (default 60):
# scripts/fuzz.sh [seconds] [extra libFuzzer flags...]
# FUZZ_TARGET picks the target (default svg_path):
#   svg_path  the SVG attribute parsers (fuzz/svg_path_fuzz.cpp)
#   urdf      the URDF importer (fuzz/urdf_fuzz.cpp)
# New inputs go to build-fuzz/corpus/<target>; crashes to build-fuzz/crash-*. The seed corpus
# in fuzz/corpus/<target> is only read.
set -euo pipefail

seconds=${1:-60}
shift || true
target=${FUZZ_TARGET:-svg_path}
case "$target" in
  svg_path | urdf) ;;
  *) echo "fuzz.sh: unknown FUZZ_TARGET '$target' (known: svg_path, urdf)" >&2; exit 2 ;;
esac
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$root/build-fuzz

# configure and build only the fuzz target
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DRESCUESIM_FUZZ=ON -DRESCUESIM_TESTS=OFF -DRESCUESIM_BENCH=OFF
cmake --build "$build" --target "${target}_fuzz"

# run: the working corpus first (libFuzzer writes there), the seeds after it
corpus=$build/corpus/$target
mkdir -p "$corpus"
"$build/bin/${target}_fuzz" -max_total_time="$seconds" -max_len=4096 -timeout=10 -print_final_stats=1 \
  -artifact_prefix="$build/" "$@" "$corpus" "$root/fuzz/corpus/$target"

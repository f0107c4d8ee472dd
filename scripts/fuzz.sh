#!/usr/bin/env bash
# Builds the libFuzzer target for the SVG attribute parsers with clang in build-fuzz/ and runs
# it for N seconds (default 60): scripts/fuzz.sh [seconds] [extra libFuzzer flags...]
# New inputs go to build-fuzz/corpus/svg_path; crashes to build-fuzz/crash-*. The seed corpus
# in fuzz/corpus/svg_path is only read.
set -euo pipefail

seconds=${1:-60}
shift || true
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$root/build-fuzz

# configure and build only the fuzz target
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DRESCUESIM_FUZZ=ON -DRESCUESIM_TESTS=OFF -DRESCUESIM_BENCH=OFF
cmake --build "$build" --target svg_path_fuzz

# run: the working corpus first (libFuzzer writes there), the seeds after it
corpus=$build/corpus/svg_path
mkdir -p "$corpus"
"$build/bin/svg_path_fuzz" -max_total_time="$seconds" -max_len=4096 -timeout=10 -print_final_stats=1 \
  -artifact_prefix="$build/" "$@" "$corpus" "$root/fuzz/corpus/svg_path"

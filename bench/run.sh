#!/usr/bin/env bash
# Runs every benchmark of a Release build and writes the results to
# bench/results/<name>.json (Google Benchmark's JSON) with the machine's
# description. Usage: bench/run.sh [build-folder]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build/release}
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_BENCH=ON >/dev/null
cmake --build "$BUILD" -j"$(nproc)"
mkdir -p bench/results
for exe in "$BUILD"/bench/bench_*; do
  name=$(basename "$exe")
  echo "== $name"
  "$exe" --benchmark_out="bench/results/$name.json" --benchmark_out_format=json \
    --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
done

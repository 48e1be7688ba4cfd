#!/usr/bin/env bash
# The ground-truth bench of quality indices (issue #14): builds quality_bench
# in a Release tree, runs every case (bench/quality/quality_bench.cpp;
# the reconstruction cases need `colmap`), and writes
# bench/results/quality/quality.json and the markdown table
# bench/results/quality/table.md that docs/pri.md shows.
# Usage: bench/quality/run.sh [build-folder] [quality_bench arguments...]
# (about 6 minutes on 2 cores: most of it COLMAP on the three scenes).
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build/release}
shift || true
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_BENCH=ON >/dev/null
cmake --build "$BUILD" -j"$(nproc)" --target quality_bench
mkdir -p bench/results/quality
"$BUILD/bench/quality_bench" --out bench/results/quality/quality.json "$@"
/usr/bin/python3 bench/quality/table.py bench/results/quality/quality.json >bench/results/quality/table.md
echo "wrote bench/results/quality/table.md"

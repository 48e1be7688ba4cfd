#!/usr/bin/env bash
# Vector kernels (issue #19): PRI's sampling + comparison with the scalar
# and the vector kernels (MESHNBV_SIMD, meshnbv/sampling.h) at 5 and 20
# views per face on 1 and 2 threads, and the bilinear peaks, scalar and
# vectorised, in one bench_pri run (3 repetitions, random interleaving, so
# that every ratio is between figures measured together). Writes
# bench/results/simd/{bench_pri_simd.json,simd.md}.
# Usage: bench/simd/run.sh [build-folder]   (about 4 minutes)
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build/release}
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_BENCH=ON >/dev/null
cmake --build "$BUILD" -j"$(nproc)" --target bench_pri
mkdir -p bench/results/simd
"$BUILD/bench/bench_pri" --benchmark_filter='BM_Pri/threads:[12]/views:(5|20)/spp:8/|BM_BilinearPeak' \
  --benchmark_repetitions=3 --benchmark_enable_random_interleaving=true \
  --benchmark_out=bench/results/simd/bench_pri_simd.json --benchmark_out_format=json
/usr/bin/python3 bench/simd/table.py bench/results/simd/bench_pri_simd.json > bench/results/simd/simd.md
cat bench/results/simd/simd.md

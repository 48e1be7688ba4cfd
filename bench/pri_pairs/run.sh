#!/usr/bin/env bash
# PRI's pairwise means in O(m n) (issue #19): BM_Pri of bench_pri (city of
# > 200k faces, 20 views at 640x480, r = 8, 5 / 10 / 20 views per face, 1 and
# 2 threads) for this tree and for a baseline commit whose means loop over
# every pair, both built here and run alternately in one session (the
# machine is shared: the ratios come from the same run). Writes
# bench/results/pri_pairs/{bench_pri_<which>_<round>.json,summary.json,table.md}.
# Usage: bench/pri_pairs/run.sh [baseline-commit] [rounds]
set -euo pipefail
cd "$(dirname "$0")/../.."
BASE_COMMIT=${1:-a9ced38}
ROUNDS=${2:-2}
OUT=bench/results/pri_pairs
NEW_BUILD=build/release
BASE_TREE=/tmp/meshnbv_pri_pairs_base
mkdir -p "$OUT"
cmake -S . -B "$NEW_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_BENCH=ON >/dev/null
cmake --build "$NEW_BUILD" -j"$(nproc)" --target bench_pri
if [ ! -d "$BASE_TREE" ]; then git worktree add --detach "$BASE_TREE" "$BASE_COMMIT" >/dev/null; fi
git -C "$BASE_TREE" checkout -q --detach "$BASE_COMMIT"
cmake -S "$BASE_TREE" -B "$BASE_TREE/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_BENCH=ON >/dev/null
cmake --build "$BASE_TREE/build" -j"$(nproc)" --target bench_pri
FILTER='BM_Pri/threads:[12]/views:(5|10|20)/spp:8'
for round in $(seq 1 "$ROUNDS"); do
  for which in base new; do
    exe=$NEW_BUILD/bench/bench_pri
    [ "$which" = base ] && exe=$BASE_TREE/build/bench/bench_pri
    echo "== round $round: $which"
    "$exe" --benchmark_filter="$FILTER" --benchmark_out="$OUT/bench_pri_${which}_${round}.json" \
      --benchmark_out_format=json
  done
done
/usr/bin/python3 bench/pri_pairs/table.py "$OUT" "$BASE_COMMIT" "$(git rev-parse --short HEAD)"

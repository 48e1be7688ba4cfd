#!/usr/bin/env bash
# This tree against a baseline commit (issue #19), both built here and run
# alternately in one session (the machine is shared: the ratios come from
# the same run):
# - BM_Pri of bench_pri: sampling + comparison on a city of > 200k faces,
#   20 views at 640x480, r = 8, 5 / 10 / 20 views per face, 1 and 2 threads
#   (the baseline a9ced38 averages a face's errors by visiting every pair);
# - BM_CandidateEvaluations of bench_nbv: the paper energy's candidate
#   evaluations per second, 1 and 2 threads (the baseline takes acos of
#   each incidence and then its cosine).
# Writes bench/results/against_baseline/{<bench>_<which>_<round>.json,
# summary.json,table.md}.
# Usage: bench/against_baseline/run.sh [baseline-commit] [rounds]
set -euo pipefail
cd "$(dirname "$0")/../.."
BASE_COMMIT=${1:-a9ced38}
ROUNDS=${2:-2}
OUT=bench/results/against_baseline
NEW_BUILD=build/release
BASE_TREE=/tmp/meshnbv_against_baseline
mkdir -p "$OUT"
cmake -S . -B "$NEW_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_BENCH=ON >/dev/null
cmake --build "$NEW_BUILD" -j"$(nproc)" --target bench_pri bench_nbv
if [ ! -d "$BASE_TREE" ]; then git worktree add --detach "$BASE_TREE" "$BASE_COMMIT" >/dev/null; fi
git -C "$BASE_TREE" checkout -q --detach "$BASE_COMMIT"
cmake -S "$BASE_TREE" -B "$BASE_TREE/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_BENCH=ON >/dev/null
cmake --build "$BASE_TREE/build" -j"$(nproc)" --target bench_pri bench_nbv
for round in $(seq 1 "$ROUNDS"); do
  for which in base new; do
    dir=$NEW_BUILD
    [ "$which" = base ] && dir=$BASE_TREE/build
    echo "== round $round: $which"
    "$dir/bench/bench_pri" --benchmark_filter='BM_Pri/threads:[12]/views:(5|10|20)/spp:8' \
      --benchmark_out="$OUT/bench_pri_${which}_${round}.json" --benchmark_out_format=json
    "$dir/bench/bench_nbv" --benchmark_filter='BM_CandidateEvaluations' \
      --benchmark_out="$OUT/bench_nbv_${which}_${round}.json" --benchmark_out_format=json
  done
done
/usr/bin/python3 bench/against_baseline/table.py "$OUT" "$BASE_COMMIT" "$(git rev-parse --short HEAD)"

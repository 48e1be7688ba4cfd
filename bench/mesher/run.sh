#!/usr/bin/env bash
# The Delaunay visibility mesher (libs/eval/src/visibility_mesher.cpp), this
# tree against a baseline commit, both built here and run alternately in one
# session (the machine is shared: ratios come from the same run). Points
# like the dense backend's fused ones (mesher_bench.cpp) on the synthetic
# building and fortress, 150,000 each (the dense backend's cap), 4 views
# per point, on 1 and 2 threads.
# Writes bench/results/mesher/{runs.jsonl, summary.json, table.md}.
# Usage: bench/mesher/run.sh [baseline-commit] [rounds]   (default f6b4564, 3)
set -euo pipefail
cd "$(dirname "$0")/../.."
BASE_COMMIT=${1:-f6b4564}
ROUNDS=${2:-3}
OUT=bench/results/mesher
NEW_BUILD=build/release
BASE_TREE=/tmp/meshnbv_mesher_baseline
mkdir -p "$OUT"
cmake -S . -B "$NEW_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_BENCH=ON >/dev/null
cmake --build "$NEW_BUILD" --target mesher_bench
if [ ! -d "$BASE_TREE" ]; then git worktree add --detach "$BASE_TREE" "$BASE_COMMIT" >/dev/null; fi
git -C "$BASE_TREE" checkout -q --force --detach "$BASE_COMMIT"
# The baseline has no mesher_bench: this tree's program, without the phase
# timings the baseline's result does not have.
mkdir -p "$BASE_TREE/bench/mesher"
cp bench/mesher/mesher_bench.cpp "$BASE_TREE/bench/mesher/"
cat >>"$BASE_TREE/bench/CMakeLists.txt" <<'CMAKE'
add_executable(mesher_bench mesher/mesher_bench.cpp)
target_link_libraries(mesher_bench PRIVATE meshnbv::core meshnbv::synth meshnbv::eval meshnbv_warnings TBB::tbb)
target_compile_definitions(mesher_bench PRIVATE MESHNBV_MESHER_BENCH_NO_PHASES)
CMAKE
cmake -S "$BASE_TREE" -B "$BASE_TREE/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_BENCH=ON >/dev/null
cmake --build "$BASE_TREE/build" --target mesher_bench
git -C "$BASE_TREE" checkout -q --force --detach "$BASE_COMMIT"  # the tree as committed again
: >"$OUT/runs.jsonl"
for round in $(seq 1 "$ROUNDS"); do
  for which in base new; do
    bin=$NEW_BUILD/bench/mesher_bench
    [ "$which" = base ] && bin=$BASE_TREE/build/bench/mesher_bench
    for scene in building fortress; do
      echo "round $round: $which $scene" >&2
      "$bin" "$scene" 150000 4 1 1 2 | sed "s/^{/{\"build\": \"$which\", \"round_of_run\": $round, /" >>"$OUT/runs.jsonl"
    done
  done
done
/usr/bin/python3 bench/mesher/table.py "$OUT" "$BASE_COMMIT" "$(git rev-parse --short HEAD)"

#!/usr/bin/env bash
# Runs the libFuzzer targets. Build them first (docs/robustness.md):
#   CXX=clang++ CC=clang cmake -S . -B build/fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
#     -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g -DNDEBUG" -DMESHNBV_SANITIZE=ON \
#     -DMESHNBV_BUILD_FUZZ=ON -DMESHNBV_BUILD_TESTS=OFF -DMESHNBV_BUILD_BENCH=OFF
#   cmake --build build/fuzz --target fuzzers
# then: fuzz/run.sh [-b BUILD] [-t SECONDS_PER_TARGET] [-j PARALLEL] [target...]
# Corpora grow in BUILD/fuzz/corpus/<target> (started from fuzz/seeds and
# kept between runs), crashers land in BUILD/fuzz/artifacts/<target>, logs
# in BUILD/fuzz/logs/<target>.log; fuzz/summary.py sums the logs up.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$ROOT/build/fuzz
SECONDS_PER_TARGET=120
JOBS=2
while getopts "b:t:j:" opt; do
  case $opt in
    b) BUILD=$(cd "$OPTARG" && pwd) ;;
    t) SECONDS_PER_TARGET=$OPTARG ;;
    j) JOBS=$OPTARG ;;
    *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(ply ply_binary obj off mlp json middlebury colmap bundler colmap_binary metashape openmvg alicevision)
OUT=$BUILD/fuzz
mkdir -p "$OUT/logs"
for t in "${TARGETS[@]}"; do
  [ -x "$BUILD/fuzz/fuzz_$t" ] || { echo "missing $BUILD/fuzz/fuzz_$t: build the 'fuzzers' target" >&2; exit 1; }
  mkdir -p "$OUT/corpus/$t" "$OUT/artifacts/$t"
  cp -n "$ROOT/fuzz/seeds/$t/"* "$OUT/corpus/$t/" 2>/dev/null || true
  [ -d "$ROOT/fuzz/regressions/$t" ] && cp -n "$ROOT/fuzz/regressions/$t/"* "$OUT/corpus/$t/" 2>/dev/null || true
done
run_one() {
  local t=$1
  local dict=()
  [ -f "$ROOT/fuzz/dict/$t.dict" ] && dict=(-dict="$ROOT/fuzz/dict/$t.dict")
  # Leaks are checked (ASan's LeakSanitizer); UB aborts (-fno-sanitize-recover).
  # -malloc_limit_mb: a single allocation past 256 MB from a <= 16 kB input is
  # a count trusted before checking it against the file size.
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=0 \
  UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    "$BUILD/fuzz/fuzz_$t" "$OUT/corpus/$t" "${dict[@]}" \
      -max_total_time="$SECONDS_PER_TARGET" -max_len=16384 -timeout=10 \
      -rss_limit_mb=2048 -malloc_limit_mb=256 -print_final_stats=1 \
      -artifact_prefix="$OUT/artifacts/$t/" >"$OUT/logs/$t.log" 2>&1
  echo "$t: exit $? ($(grep -c 'NEW ' "$OUT/logs/$t.log") new units)"
}
export -f run_one
export ROOT BUILD OUT SECONDS_PER_TARGET
printf '%s\n' "${TARGETS[@]}" | xargs -P "$JOBS" -I{} bash -c 'run_one {} || true'
python3 "$ROOT/fuzz/summary.py" "$OUT/logs" "${TARGETS[@]}"

#!/usr/bin/env bash
# The whole test suite from scratch: install dependencies, configure a fresh
# Release build with every part on, build, run ctest; then the same suite
# under AddressSanitizer + UndefinedBehaviorSanitizer (scripts/test-sanitizers.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
START=$SECONDS
step_done() { echo "== scripts/test.sh: $1 done at $((SECONDS - START)) s"; }
scripts/install-deps.sh
step_done "dependencies"
BUILD=${MESHNBV_BUILD_DIR:-build/ci}
rm -rf "$BUILD"
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DMESHNBV_BUILD_TESTS=ON -DMESHNBV_BUILD_BENCH=ON -DMESHNBV_BUILD_VTK=ON -DMESHNBV_BUILD_MESHLAB=ON -DMESHNBV_BUILD_MPI=ON -DMESHNBV_BUILD_PARAVIEW=ON
cmake --build "$BUILD" -j"$(nproc)"
step_done "Release build"
ctest --test-dir "$BUILD" --output-on-failure -j"$(nproc)"
step_done "Release tests"
# Second step: the same suite under AddressSanitizer + UndefinedBehaviorSanitizer.
scripts/test-sanitizers.sh
step_done "sanitizer build and tests"

#!/usr/bin/env bash
# The whole test suite from scratch: install dependencies, configure a fresh
# Release build with every part on, build, run ctest; then the same suite
# under AddressSanitizer + UndefinedBehaviorSanitizer (scripts/test-sanitizers.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
BUILD=${MESHNBV_BUILD_DIR:-build/ci}
rm -rf "$BUILD"
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DMESHNBV_BUILD_TESTS=ON -DMESHNBV_BUILD_BENCH=ON -DMESHNBV_BUILD_VTK=ON -DMESHNBV_BUILD_MESHLAB=ON -DMESHNBV_BUILD_MPI=ON -DMESHNBV_BUILD_PARAVIEW=ON
cmake --build "$BUILD" -j"$(nproc)"
ctest --test-dir "$BUILD" --output-on-failure -j"$(nproc)"
# Second step: the same suite under AddressSanitizer + UndefinedBehaviorSanitizer.
scripts/test-sanitizers.sh

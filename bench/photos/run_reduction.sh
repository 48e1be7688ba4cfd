#!/usr/bin/env bash
# Reduced JPEG decoding bench (issue #17): PRI on 24 photos of 20 MP of the
# synthetic building at several mesh edge lengths, photos decoded whole and
# reduced (max_image_reduction 1 and 8) in the same session
# (bench/photos/reduction.py). Writes bench/results/photos/reduction.{json,md}.
# Usage: bench/photos/run_reduction.sh [build-folder]   (scratch:
# $MESHNBV_REDUCTION_WORK, default /tmp/meshnbv_reduction, about 3 GB)
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build/release}
WORK=${MESHNBV_REDUCTION_WORK:-/tmp/meshnbv_reduction}
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_BENCH=ON >/dev/null
cmake --build "$BUILD" -j"$(nproc)" --target meshnbv
mkdir -p "$WORK"
/usr/bin/python3 bench/photos/reduction.py "$BUILD" "$WORK" bench/results/photos

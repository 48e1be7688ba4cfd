#!/usr/bin/env bash
# Photo bench (issue #17): PRI on >= 1M faces with 25, 50 and 100 photos of
# 20 MP as JPEG, against the time it takes just to decode those photos on
# 2 threads, and the whole process's peak memory (target <= 4 GB, flat in
# the photo count). The scene: the synthetic city (729k faces at edge
# 0.2 m) with every triangle split in two (1.46M faces, the same surface),
# 100 hemisphere views rendered at 2736x1824 and doubled to 5472x3648
# (bicubic, sensor-like noise, JPEG quality 92; rendering them at full size
# would take this machine half an hour). Writes
# bench/results/photos/{photos.json,photos.md}.
# Usage: bench/photos/run.sh [build-folder]   (scratch: $MESHNBV_PHOTOS_WORK,
# default /tmp/meshnbv_photos, about 1 GB)
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build/release}
WORK=${MESHNBV_PHOTOS_WORK:-/tmp/meshnbv_photos}
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_BENCH=ON >/dev/null
cmake --build "$BUILD" -j"$(nproc)" --target meshnbv photo_decode
mkdir -p "$WORK"
/usr/bin/python3 bench/photos/photos.py "$BUILD" "$WORK" bench/results/photos

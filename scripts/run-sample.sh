#!/usr/bin/env bash
# The main job on the bundled sample project: install dependencies, build,
# run, and say where the results went.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
BUILD=${MESHNBV_BUILD_DIR:-build/release}
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_TESTS=OFF \
  -DMESHNBV_BUILD_BENCH=OFF -DMESHNBV_BUILD_VTK=ON -DMESHNBV_BUILD_MESHLAB=ON >/dev/null
cmake --build "$BUILD" -j"$(nproc)" --target meshnbv
OUT=${MESHNBV_OUT:-out/sample}
mkdir -p "$OUT"
SCENE=sample_projects/building/project.mlp
"$BUILD/apps/meshnbv" info "$SCENE" --json "$OUT/info.json"
"$BUILD/apps/meshnbv" pri "$SCENE" --out "$OUT/pri.ply" --json "$OUT/pri.json" --overwrite
echo "results in $OUT/: info.json (scene summary), pri.ply (mesh coloured by PRI, face quality = PRI), pri.json (PRI summary)"

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
"$BUILD/apps/meshnbv" pri "$SCENE" --out "$OUT/pri.ply" --json "$OUT/pri.json" --overwrite --quiet
"$BUILD/apps/meshnbv" suggest "$SCENE" --pri "$OUT/pri.ply" --top 3 --out "$OUT/suggestions.json" \
  --mlp "$OUT/suggestions.mlp" --frustums "$OUT/frustums.ply" --colmap "$OUT/colmap" --overwrite --quiet
echo
echo "results in $OUT/:"
echo "  info.json          scene summary"
echo "  pri.ply, pri.json  mesh coloured by PRI (face quality = PRI) and its summary"
echo "  suggestions.json   the 3 suggested next views with every energy term"
echo "  suggestions.mlp    open in MeshLab: the scene with rasters nbv_1..nbv_3"
echo "  frustums.ply       the suggested camera frustums (red = best)"
echo "  colmap/            the suggestions as a COLMAP text model"

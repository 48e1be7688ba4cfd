#!/usr/bin/env bash
# The main job on the bundled sample project: install dependencies, build,
# run, and say where the results went.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
BUILD=${MESHNBV_BUILD_DIR:-build/release}
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_TESTS=OFF \
  -DMESHNBV_BUILD_BENCH=OFF -DMESHNBV_BUILD_VTK=ON -DMESHNBV_BUILD_MESHLAB=ON -DMESHNBV_BUILD_MPI=ON >/dev/null
cmake --build "$BUILD" -j"$(nproc)" --target meshnbv
OUT=${MESHNBV_OUT:-out/sample}
mkdir -p "$OUT"
SCENE=sample_projects/building/project.mlp
"$BUILD/apps/meshnbv" info "$SCENE" --json "$OUT/info.json"
echo
"$BUILD/apps/meshnbv" run "$SCENE" --out "$OUT" --top 3 --overwrite
echo
echo "results in $OUT/: report.html (open it in a browser), pri.ply + pri.json (mesh coloured by PRI,"
echo "face quality = PRI), suggestions.json, suggestions.mlp (open in MeshLab), frustums.ply, info.json"

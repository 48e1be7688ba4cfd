#!/usr/bin/env bash
# Scale bench (docs/scale.md, issue #22), in one session:
# 1. meshnbv-mpi on 1, 2 and 4 ranks (oversubscribed on this 2-core
#    machine) against one `meshnbv pri` process, on a >= 1M-face scene: the
#    synthetic city (729k faces at edge 0.2 m) with each triangle split in
#    two along its longest edge (1.46M faces, the same surface, so the
#    rendered photos still fit), 128 nadir photos of 512x384 from a survey
#    grid (synth --layout grid: each photo sees a small part of it). Wall time, each
#    rank's peak memory (getrusage), tiles, faces and images decoded;
#    outputs compared bit for bit.
# 2. Incremental PRI on the same scene (one process): a local edit (a dent
#    of radius 4 m), and one view added, each against a full computation
#    of the same scene (time, faces recomputed, bitwise equality).
# 3. Cost-model points: one process at several view counts and image sizes;
#    bench/scale/model.py fits the cost model (model.json).
# 4. The loop with and without incremental PRI (loop_pri.py: loop_pri.{json,md}).
# Writes bench/results/scale/{runs.json,table.md,model.json,loop_pri.json,loop_pri.md}.
# Usage: bench/scale/run.sh [build-folder]
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build/release}
OUT=bench/results/scale
WORK=${MESHNBV_SCALE_WORK:-/tmp/meshnbv_scale}
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_MPI=ON >/dev/null
cmake --build "$BUILD" -j"$(nproc)" --target meshnbv meshnbv-mpi
if [ "$(id -u)" -eq 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
mkdir -p "$OUT" "$WORK"
/usr/bin/python3 bench/scale/scale.py "$BUILD/apps" "$WORK" "$OUT"
# 4. Incremental PRI in the loop (needs colmap): bench/scale/loop_pri.py.
/usr/bin/python3 bench/scale/loop_pri.py "$BUILD/apps" "$WORK" "$OUT"

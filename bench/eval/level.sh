#!/usr/bin/env bash
# Level new poses (issue #16, option level_views, planner.h, docs/nbv.md):
# the whole-mesh energy with sampled candidates above the ground, oriented
# by the SPEC's mean image up of the existing views (run
# nbv_recon_sampled_ground) and without roll, image up towards their level
# up (run nbv_recon_sampled_level), with the baselines uniform and coverage
# for reference, every run from the same 5 starting sets and one COLMAP
# cache per dataset.
#
#   bench/eval/level.sh [BUILD_DIR]
#   ONLY="building fortress"   synthetic datasets (new poses need a truth to render)
#
# Results: bench/results/eval/level/sparse/ (as experiment.sh's), and
# below_base.md: the added views below the mesh's base.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-build}
ONLY=${ONLY:-building fortress}
OUT=$ROOT/bench/results/eval/level/sparse
RESULTS=$OUT BACKEND=sparse ONLY=$ONLY RUNS='uniform|coverage|nbv_recon_sampled_ground|nbv_recon_sampled_level' \
  "$ROOT/bench/eval/experiment.sh" "$BUILD"
# The added views below the base, per run (below_base.md).
/usr/bin/python3 "$ROOT/bench/eval/below_base.py" "$OUT"

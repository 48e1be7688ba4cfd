#!/usr/bin/env bash
# New poses kept above the ground (issue #16, option above_ground,
# candidates.h, docs/nbv.md): the whole-mesh energy with sampled candidates,
# without (run nbv_recon_sampled, the SPEC's hemisphere) and with the ground
# (run nbv_recon_sampled_ground), with the baselines uniform and coverage
# for reference, every run from the same 5 starting sets and one COLMAP
# cache per dataset (see match_angle.sh on caches and new poses' matching).
#
#   bench/eval/ground.sh [BUILD_DIR]
#   ONLY="building fortress"   synthetic datasets (new poses need a truth to render)
#
# Results: bench/results/eval/ground/sparse/ (as experiment.sh's).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-build}
ONLY=${ONLY:-building fortress}
OUT=$ROOT/bench/results/eval/ground/sparse
RESULTS=$OUT BACKEND=sparse ONLY=$ONLY RUNS='uniform|coverage|nbv_recon_sampled|nbv_recon_sampled_ground' \
  "$ROOT/bench/eval/experiment.sh" "$BUILD"

#!/usr/bin/env bash
# The whole-mesh energy with and without the matchability condition
# (issue #16, gain.h, docs/nbv.md): match_angle 180 (off, the default; run
# nbv_recon) and 45 degrees (run nbv_recon_m45), with the baselines
# uniform and coverage for reference, every run from the same 5 starting
# sets and one COLMAP cache per dataset, so that the pairs differ only by
# the strategy (a cache rebuilt elsewhere gives slightly different points:
# compare the step-0 point counts in experiment/sparse/building/nbv_recon
# and match_angle/sparse/building/nbv_recon; and new poses' photos are
# matched afresh in every run, so their runs differ even on one cache).
#
#   bench/eval/match_angle.sh [BUILD_DIR]
#   ONLY="temple building fortress"   datasets (default all three)
#   SAMPLED="building fortress"       datasets also run with new poses
#                                     (--nbv-candidates sampled; about 7
#                                     min per run on the fortress)
#
# Results: bench/results/eval/match_angle/sparse/ (as experiment.sh's).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-build}
ONLY=${ONLY:-temple building fortress}
SAMPLED=${SAMPLED:-building fortress}
OUT=$ROOT/bench/results/eval/match_angle/sparse
RING='uniform|coverage|nbv_recon|nbv_recon_m45'
for dataset in $ONLY; do
  runs=$RING
  [[ " $SAMPLED " == *" $dataset "* ]] && runs="$RING|nbv_recon_sampled|nbv_recon_sampled_m45"
  RESULTS=$OUT BACKEND=sparse ONLY=$dataset RUNS=$runs "$ROOT/bench/eval/experiment.sh" "$BUILD"
done

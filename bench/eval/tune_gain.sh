#!/usr/bin/env bash
# Tuning of the whole-mesh energy (issue #16): a grid over gain_target and
# exploration_weight, each setting run from the experiment's starting sets
# (bench/eval/experiment.sh: same bootstraps, backend and budgets) on the
# synthetic building and fortress and on templeRing only; the datasets the
# results are checked on elsewhere are never used here. The setting kept is
# the one of largest mean area under the completeness curve over the three
# datasets (bench/eval/tune_summary.py, which also writes the table).
#
#   bench/eval/tune_gain.sh [BUILD_DIR]
#   TARGETS="1 3"  WEIGHTS="1 3 10"  ONLY="building fortress temple"
#
# Results: bench/results/eval/tune_gain/<dataset>/T<t>_w<w>/
# {bootstraps.json, bootstrap_<b>/loop.json, ...} and summary.md/json (the
# run behind today's defaults, of commit 2e33787 with CGAL's hull:
# bench/results/history/tune_gain_2e33787_summary.md; its runs are in that
# commit's tree).
# shellcheck source=env.sh
source "$(dirname "$0")/env.sh"
TARGETS=${TARGETS:-1 3}
WEIGHTS=${WEIGHTS:-1 3 10}
ONLY=${ONLY:-building fortress temple}
BOOTSTRAPS=${BOOTSTRAPS:-5}
RESULTS=$ROOT/bench/results/eval/tune_gain
[ -x "$MESHNBV" ] || { echo "no $MESHNBV: build first" >&2; exit 1; }

for dataset in $ONLY; do
  case $dataset in
    temple)
      DATA=$SHARED/middlebury/templeRing
      [ -f "$DATA/templeR_par.txt" ] || { echo "SKIP temple: $DATA not found"; continue; }
      ARGS=(--view-budget 23 --cache "$WORK/cache/temple" --thresholds 0.00075,0.00125,0.00175,0.005) ;;
    building | fortress)
      DATA=$WORK/data/$dataset
      [ -f "$DATA/scene.json" ] ||
        "$MESHNBV" synth "$dataset" --out "$DATA" --views 24 --size 1024x768 --layout ring --quiet --overwrite
      ARGS=(--view-budget 12 --cache "$WORK/cache/$dataset" --facet-support edges) ;;
    *) echo "unknown dataset '$dataset'" >&2; exit 2 ;;
  esac
  for t in $TARGETS; do
    for w in $WEIGHTS; do
      out=$RESULTS/$dataset/T${t}_w${w}
      echo "== $dataset T=$t w=$w ($(date +%T))"
      "$MESHNBV" loop "$DATA" "${ARGS[@]}" --strategy nbv --energy reconstructability --gain-target "$t" \
        --exploration-weight "$w" --bootstraps "$BOOTSTRAPS" --out "$out" --overwrite --save-meshes none --quiet \
        >"$WORK/tune_console.txt"
      mv "$WORK/tune_console.txt" "$out/console.txt"
      for b in "$out"/bootstrap_*; do rm -rf "$b/meshes" "$b/images" "$b/reference.ply"; done
    done
  done
done
/usr/bin/python3 "$ROOT/bench/eval/tune_summary.py" "$RESULTS"

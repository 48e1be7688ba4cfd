#!/usr/bin/env bash
# The dense backend against the sparse one (issue #15), rerunnable:
#  - quality: the synthetic building and fortress with all 24 ring views
#    (1024x768), and templeRing with all 47 views: accuracy, completeness,
#    points and surface samples of both backends (a loop whose last step
#    holds every view: bootstrap n-1, then the last view);
#  - loop: a 23-view nbv loop on templeRing with the dense backend, its
#    time per step split into sparse, dense, mesh, PRI, choice, evaluation.
#
#   bench/eval/dense.sh [BUILD_DIR]      ONLY=quality|loop bench/eval/dense.sh
#
# Results: bench/results/eval/dense/{quality.json,summary.md,loop_temple/}
# (bench/eval/dense_summary.py). Caches and datasets go to
# $MESHNBV_EVAL_WORK (default ../eval-work beside the repository).
# shellcheck source=env.sh
source "$(dirname "$0")/env.sh"
RESULTS=$ROOT/bench/results/eval/dense
ONLY=${ONLY:-all}
TEMPLE=$SHARED/middlebury/templeRing
mkdir -p "$WORK" "$RESULTS"
[ -x "$MESHNBV" ] || { echo "no $MESHNBV: build first" >&2; exit 1; }

if [ "$ONLY" = all ] || [ "$ONLY" = quality ]; then
  for scene in building fortress; do
    DATA=$WORK/data/$scene
    [ -f "$DATA/scene.json" ] ||
      "$MESHNBV" synth "$scene" --out "$DATA" --views 24 --size 1024x768 --layout ring --quiet --overwrite
    for backend in sparse dense; do
      echo "== $scene / $backend"
      "$MESHNBV" loop "$DATA" --strategy uniform --bootstrap 23 --view-budget 24 --backend "$backend" \
        --facet-support edges --cache "$WORK/cache/$scene" --out "$WORK/dense_bench/$scene/$backend" \
        --overwrite --quiet --save-meshes last --snapshots | tail -3
    done
  done
  if [ -f "$TEMPLE/templeR_par.txt" ]; then
    for backend in sparse dense; do
      echo "== temple / $backend"
      "$MESHNBV" loop "$TEMPLE" --strategy uniform --bootstrap 46 --view-budget 47 --backend "$backend" \
        --cache "$WORK/cache/temple" --out "$WORK/dense_bench/temple/$backend" \
        --thresholds 0.00075,0.00125,0.00175,0.005 --overwrite --quiet --save-meshes last --snapshots | tail -3
    done
  else
    echo "SKIP temple: $TEMPLE not found (set MESHNBV_SHARED_DATA)"
  fi
fi

if [ "$ONLY" = all ] || [ "$ONLY" = loop ]; then
  if [ -f "$TEMPLE/templeR_par.txt" ]; then
    echo "== temple / nbv loop, dense"
    "$MESHNBV" loop "$TEMPLE" --strategy nbv --view-budget 23 --backend dense --cache "$WORK/cache/temple" \
      --out "$RESULTS/loop_temple" --save-meshes none --thresholds 0.00075,0.00125,0.00175,0.005 --overwrite --quiet \
      | tee "$WORK/console.txt"
    mv "$WORK/console.txt" "$RESULTS/loop_temple/console.txt"
    # The meshes and the reference (MBs) stay out of the repository.
    rm -rf "$RESULTS/loop_temple/meshes" "$RESULTS/loop_temple/reference.ply" "$RESULTS/loop_temple/cache"
  fi
fi
/usr/bin/python3 "$ROOT/bench/eval/dense_summary.py" "$WORK/dense_bench" "$RESULTS"

#!/usr/bin/env bash
# The paper's experiment, rerunnable: `meshnbv loop` with every strategy on
# Middlebury templeRing and on synthetic scenes, then curves and tables.
#
#   bench/eval/run.sh [BUILD_DIR]        (default: build)
#   ONLY=temple|building|fortress bench/eval/run.sh   one dataset
#   RUNS='nbv.*' bench/eval/run.sh       only the runs whose name matches (bash regex)
#
# Results (committed): bench/results/eval/<dataset>/<run>/{loop.json,
# steps.csv, console.txt, meshes/ (last step, PLY + two pictures)},
# <dataset>/{reference.ply, reference_[ab].png, curves.png, table.md},
# results.md, summary.json (bench/eval/summary.py). COLMAP caches and the synthetic datasets
# go to $MESHNBV_EVAL_WORK (default ../eval-work beside the repository:
# large, never committed). Needs colmap and python3-matplotlib.
# About 26 minutes on 2 cores from scratch (COLMAP's matching, once per dataset, 7 of them).
# shellcheck source=env.sh
source "$(dirname "$0")/env.sh"
RESULTS=$ROOT/bench/results/eval
ONLY=${ONLY:-all}
RUNS=${RUNS:-.*}
SEEDS="1 2 3"
mkdir -p "$WORK" "$RESULTS"
[ -x "$MESHNBV" ] || { echo "no $MESHNBV: build first" >&2; exit 1; }

# run DATASET NAME ARGS...: one loop, its console output kept beside its results.
run() {
  local dataset=$1 name=$2; shift 2
  local out=$RESULTS/$dataset/$name
  [[ $name =~ ^($RUNS)$ ]] || return 0
  echo "== $dataset / $name"
  mkdir -p "$RESULTS/$dataset"
  "$MESHNBV" loop "$@" --out "$out" --overwrite --save-meshes last --snapshots --quiet | tee "$WORK/console.txt"
  mv "$WORK/console.txt" "$out/console.txt"
  # The pictures taken at new poses stay out of the repository (a few MB).
  rm -rf "$out/images"
  # The reference is the same for every run of a dataset: keep one copy.
  mv -f "$out"/reference.ply "$out"/reference_a.png "$out"/reference_b.png "$RESULTS/$dataset/"
}

# strategies DATASET ARGS...: uniform, random (3 seeds), coverage, nbv among the dataset's views.
strategies() {
  local dataset=$1; shift
  run "$dataset" uniform "$@" --strategy uniform
  for s in $SEEDS; do run "$dataset" "random_seed$s" "$@" --strategy random --seed "$s"; done
  run "$dataset" coverage "$@" --strategy coverage
  run "$dataset" nbv "$@" --strategy nbv
}

if [ "$ONLY" = all ] || [ "$ONLY" = temple ]; then
  TEMPLE=$SHARED/middlebury/templeRing
  if [ -f "$TEMPLE/templeR_par.txt" ]; then
    # 47 views on a ring; bootstrap: view 0 and its two neighbours; up to 23
    # views as in the paper. Reference: the reconstruction from all 47.
    # Thresholds: Middlebury's 0.75, 1.25, 1.75 mm, and 5 mm (sparse meshes).
    strategies temple "$TEMPLE" --view-budget 23 --cache "$WORK/cache/temple" \
      --thresholds 0.00075,0.00125,0.00175,0.005
  else
    echo "SKIP temple: $TEMPLE not found (set MESHNBV_SHARED_DATA)"
  fi
fi

for scene in building fortress; do
  if [ "$ONLY" != all ] && [ "$ONLY" != "$scene" ]; then continue; fi
  DATA=$WORK/data/$scene
  if [ ! -f "$DATA/scene.json" ]; then
    # A ring of 24 views (15 degrees apart) at 1024x768: the candidates.
    "$MESHNBV" synth "$scene" --out "$DATA" --views 24 --size 1024x768 --layout ring --quiet --overwrite
  fi
  # Facades seen from different sides must not be joined through the
  # inside (docs/evaluation.md): --facet-support edges.
  COMMON=(--view-budget 12 --cache "$WORK/cache/$scene" --facet-support edges)
  strategies "$scene" "$DATA" "${COMMON[@]}"
  # Continuous: new poses anywhere, the renderer takes the picture.
  run "$scene" nbv_sampled "$DATA" --strategy nbv --nbv-candidates sampled "${COMMON[@]}"
  run "$scene" nbv_refined "$DATA" --strategy nbv --nbv-candidates refined --refine-iterations 60 "${COMMON[@]}"
done

/usr/bin/python3 "$ROOT/bench/eval/report.py" "$RESULTS"
/usr/bin/python3 "$ROOT/bench/eval/summary.py" "$RESULTS"

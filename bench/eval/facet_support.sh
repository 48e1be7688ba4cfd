#!/usr/bin/env bash
# docs/evaluation.md's `--facet-support` figure: the synthetic building's
# `nbv` loop of bench/eval/run.sh (same dataset, cache and options) up to 7
# views, once with `--facet-support any` and once with `edges`, in the same
# run; accuracy and completeness at every step of both.
#
#   bench/eval/facet_support.sh [BUILD_DIR]      (default: build)
#
# Results (committed): bench/results/facet_support/{any,edges}/{loop.json,
# steps.csv,console.txt} and bench/results/facet_support/summary.json (the
# metrics at 7 views side by side). The dataset and COLMAP's cache go to
# $MESHNBV_EVAL_WORK (default ../eval-work beside the repository), shared
# with bench/eval/run.sh. Needs colmap. About 2 minutes on 2 cores with an
# empty cache (rendering the dataset, COLMAP's features and matches;
# `wall_seconds` in summary.json).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
MESHNBV=$BUILD/apps/meshnbv
WORK=${MESHNBV_EVAL_WORK:-$ROOT/../eval-work}
RESULTS=$ROOT/bench/results/facet_support
VIEWS=7
[ -x "$MESHNBV" ] || { echo "no $MESHNBV: build first" >&2; exit 1; }
mkdir -p "$WORK" "$RESULTS"
start=$SECONDS

DATA=$WORK/data/building
if [ ! -f "$DATA/scene.json" ]; then
  # As bench/eval/run.sh: a ring of 24 views (15 degrees apart) at 1024x768.
  "$MESHNBV" synth building --out "$DATA" --views 24 --size 1024x768 --layout ring --quiet --overwrite
fi
for support in any edges; do
  echo "== building / nbv, --facet-support $support, up to $VIEWS views"
  out=$RESULTS/$support
  "$MESHNBV" loop "$DATA" --strategy nbv --view-budget "$VIEWS" --cache "$WORK/cache/building" \
    --facet-support "$support" --out "$out" --overwrite --save-meshes none --quiet | tee "$WORK/console.txt"
  mv "$WORK/console.txt" "$out/console.txt"
  # The reference (the truth seen by the dataset's views) is in bench/results/eval/building/.
  rm -f "$out"/reference.ply "$out"/reference_a.png "$out"/reference_b.png
  rm -rf "$out/images"
done

/usr/bin/python3 - "$RESULTS" "$VIEWS" "$((SECONDS - start))" <<'EOF'
import json, sys
root, views, seconds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
out = {"written_by": "bench/eval/facet_support.sh", "dataset": "building (bench/eval/run.sh's)",
       "strategy": "nbv", "views": views, "wall_seconds": seconds, "runs": {}}
for support in ("any", "edges"):
    loop = json.load(open(f"{root}/{support}/loop.json"))
    step = next(s for s in loop["steps"] if s["num_views"] == views)
    out["runs"][support] = {"accuracy": step["accuracy"], "completeness": step["completeness"],
                            "points": step["points"], "faces": step["faces"], "views": step["views"],
                            "loop_seconds": loop["seconds"]}
json.dump(out, open(f"{root}/summary.json", "w"), indent=1)
for s, r in out["runs"].items():
    print(f"{s}: at {views} views accuracy 80% {r['accuracy']['80']:.4f} m, 90% {r['accuracy']['90']:.4f} m")
EOF

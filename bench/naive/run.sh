#!/usr/bin/env bash
# The whole PRI process (decoding included) on Middlebury templeRing (47
# views of 640x480) with the reference mesh bench/eval reconstructed from
# all 47 views, against a naive one-thread reference and the paper's OpenCV
# warping, in alternating rounds of one run (issue #19: compute_pri >= 4x
# the naive reference). Writes bench/results/naive/{naive.json,naive.md}.
# Usage: bench/naive/run.sh [build-folder] [rounds]   (about a minute)
# The data: $MESHNBV_SHARED_DATA/middlebury/templeRing, default ../shared/data.
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build/release}
ROUNDS=${2:-5}
DATA=${MESHNBV_SHARED_DATA:-../shared/data}
TEMPLE=$DATA/middlebury/templeRing
MESH=bench/results/eval/temple/reference.ply
if [ ! -f "$TEMPLE/templeR_par.txt" ]; then
  echo "bench/naive: $TEMPLE/templeR_par.txt not found (set MESHNBV_SHARED_DATA): nothing measured" >&2
  exit 2
fi
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMESHNBV_BUILD_BENCH=ON >/dev/null
cmake --build "$BUILD" -j"$(nproc)" --target naive_pri
mkdir -p bench/results/naive
"$BUILD/bench/naive_pri" "$TEMPLE" "$MESH" bench/results/naive/naive.json "$ROUNDS" >/dev/null
/usr/bin/python3 - <<'PY'
import json
d = json.load(open("bench/results/naive/naive.json"))
m, a = d["median_seconds"], d["agreement_with_compute_pri"]
lines = [f"templeRing: {d['views']} views, reference mesh of {d['faces']:,} faces; {d['rounds']} alternating rounds, "
         "medians; compute_pri on all cores with its image cache emptied before each round, the others on one thread.",
         "", "| method | whole process (s) | / compute_pri | PRI against compute_pri: Pearson | Spearman | faces observed by one only |",
         "|---|---|---|---|---|---|",
         f"| compute_pri | {m['compute_pri']:.3f} | 1.00x | | | |"]
for k, name in (("naive", "naive reference"), ("paper", "paper's OpenCV warp (r = 8)")):
    lines.append(f"| {name} | {m[k]:.3f} | {m[k] / m['compute_pri']:.2f}x | {a[k]['pearson']:.4f} | "
                 f"{a[k]['spearman']:.4f} | {a[k]['faces_one_only']} |")
lines += ["", "Stages (medians, s): naive reference: decoding %.3f, visibility %.3f, faces (sampling and pairs) %.3f; "
          "compute_pri's first phase (visibility and view selection, timed alone) %.3f of its %.3f." % (
              m["naive_decode"], m["naive_visibility"], m["naive_faces"], m["compute_pri_selection"],
              m["compute_pri"])]
lines += ["", "compute_pri is %.2fx as fast as the naive reference (target: >= 4x): %s." % (
    d["naive_over_compute_pri"], "met" if d["naive_over_compute_pri"] >= 4 else "NOT met")]
open("bench/results/naive/naive.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY

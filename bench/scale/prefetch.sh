#!/usr/bin/env bash
# Photos decoded ahead of their turn (issue #19), against the commit before
# it (97f302a: each photo decoded and converted when its turn came, on one
# thread), whole `meshnbv pri` runs alternated in one session on the scale
# bench's survey upsampled to 1024x768 (1,457,600 faces, 128 photos: run
# bench/scale/run.sh first, it makes the scene). Wall time, PRI seconds,
# peak memory; outputs compared bit for bit.
# Writes bench/results/scale/prefetch.{json,md}.
# Usage: bench/scale/prefetch.sh [rounds]   (BASE_BUILD=folder: a baseline build to use)
set -euo pipefail
cd "$(dirname "$0")/../.."
ROUNDS=${1:-3}
BASE_COMMIT=97f302a
WORK=${MESHNBV_SCALE_WORK:-/tmp/meshnbv_scale}
SCENE=$WORK/cost_1_2_big.ply.json
[ -f "$SCENE" ] || { echo "no $SCENE: run bench/scale/run.sh first" >&2; exit 1; }
cmake --build build/release -j"$(nproc)" --target meshnbv
BASE_BUILD=${BASE_BUILD:-}
if [ -z "$BASE_BUILD" ]; then
  BASE_TREE=/tmp/meshnbv_prefetch_baseline
  [ -d "$BASE_TREE" ] || git worktree add --detach "$BASE_TREE" "$BASE_COMMIT" >/dev/null
  cmake -S "$BASE_TREE" -B "$BASE_TREE/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$BASE_TREE/build" -j"$(nproc)" --target meshnbv
  BASE_BUILD=$BASE_TREE/build
fi
/usr/bin/python3 - "$BASE_BUILD/apps/meshnbv" build/release/apps/meshnbv "$SCENE" "$WORK" "$ROUNDS" <<'PY'
import json, re, subprocess, sys
base, new, scene, work, rounds = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5])
runs = []
for r in range(rounds):
    for which, exe in (("base", base), ("new", new)):
        ply, summary = "%s/prefetch_%s.ply" % (work, which), "%s/prefetch_%s.json" % (work, which)
        p = subprocess.run(["/usr/bin/time", "-f", "wall %e peak_kb %M", exe, "pri", scene, "--out", ply, "--json",
                            summary, "--overwrite", "--quiet"], capture_output=True, text=True, check=True)
        m = re.search(r"wall ([\d.]+) peak_kb (\d+)", p.stderr)
        runs.append({"round": r + 1, "which": which, "wall_seconds": float(m.group(1)),
                     "pri_seconds": json.load(open(summary))["seconds"], "peak_mb": int(m.group(2)) / 1024})
same = open("%s/prefetch_base.ply" % work, "rb").read() == open("%s/prefetch_new.ply" % work, "rb").read()
def mean(which, key):
    v = [x[key] for x in runs if x["which"] == which]
    return sum(v) / len(v)
out = {"scene": scene, "baseline": "97f302a", "rounds": rounds, "identical": same, "runs": runs,
       "mean": {w: {k: mean(w, k) for k in ("wall_seconds", "pri_seconds", "peak_mb")} for w in ("base", "new")}}
out["pri_speedup"] = out["mean"]["base"]["pri_seconds"] / out["mean"]["new"]["pri_seconds"]
json.dump(out, open("bench/results/scale/prefetch.json", "w"), indent=1)
lines = ["Photos decoded ahead (this tree) against 97f302a, %d alternated rounds; 1,457,600 faces, 128 photos of "
         "1024x768, 2 cores; outputs identical: %s." % (rounds, "yes" if same else "NO"), "",
         "| build | mean wall s | mean PRI s | mean peak MB |", "|---|---|---|---|"]
for w in ("base", "new"):
    m = out["mean"][w]
    lines.append("| %s | %.2f | %.2f | %.0f |" % ({"base": "97f302a", "new": "this tree"}[w], m["wall_seconds"],
                                                   m["pri_seconds"], m["peak_mb"]))
lines += ["", "PRI time ratio (97f302a / this tree): %.2f" % out["pri_speedup"], ""]
open("bench/results/scale/prefetch.md", "w").write("\n".join(lines))
print("\n".join(lines))
PY

# meshnbv loop and meshnbv evaluate: every strategy on a tiny synthetic
# building (12 ring views of 640x480, bootstrap 3, up to 5 views) writes its
# files, and completeness does not fall as views are added; evaluate on a
# plane and its offset. The loop part skips when colmap is missing.
source "$(dirname "$0")/lib.bash"

# evaluate: a unit square and a copy 2 mm above it.
/usr/bin/python3 - "$TMP" <<'PY' || fail "prepare planes"
import sys
d = sys.argv[1]
for name, z in (("ref", 0.0), ("up", 0.002)):
    with open("%s/%s.ply" % (d, name), "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n")
        f.write("element face 2\nproperty list uchar int vertex_indices\nend_header\n")
        f.write("0 0 %g\n1 0 %g\n1 1 %g\n0 1 %g\n3 0 1 2\n3 0 2 3\n" % (z, z, z, z))
PY
"$MESHNBV" evaluate "$TMP/up.ply" "$TMP/ref.ply" --thresholds 0.001,0.003 --sample-spacing 0.01 \
  --json "$TMP/eval.json" >/dev/null || fail "evaluate"
/usr/bin/python3 - "$TMP/eval.json" <<'PY' || fail "evaluate json"
import json, sys
e = json.load(open(sys.argv[1]))
assert e["format"] == "meshnbv-evaluation"
assert [a["percentile"] for a in e["accuracy"]] == [80, 90, 99]
for a in e["accuracy"]:
    assert abs(a["distance"] - 0.002) < 1e-6, a
assert [c["share"] for c in e["completeness"]] == [0.0, 1.0], e["completeness"]
PY
expect_error "--overwrite" "$MESHNBV" evaluate "$TMP/up.ply" "$TMP/ref.ply" --json "$TMP/eval.json"
expect_error "not a number" "$MESHNBV" evaluate "$TMP/up.ply" "$TMP/ref.ply" --thresholds 1,x
expect_error "thresholds must be positive" "$MESHNBV" evaluate "$TMP/up.ply" "$TMP/ref.ply" --thresholds 0.1,-1

if ! QT_QPA_PLATFORM=offscreen colmap help >/dev/null 2>&1; then
  echo "SKIP loop part: colmap not installed (apt-get install colmap)"
  finish
  exit 0
fi

"$MESHNBV" synth building --out "$TMP/synth" --views 12 --size 640x480 --samples-per-pixel 1 --quiet >/dev/null \
  || fail "synth"
for s in nbv uniform random coverage; do
  "$MESHNBV" loop "$TMP/synth" --strategy $s --view-budget 5 --out "$TMP/$s" --cache "$TMP/cache" \
    --quiet >"$TMP/$s.txt" 2>&1 || { fail "loop $s: $(tail -3 "$TMP/$s.txt")"; continue; }
  grep -q "^step 2: 5 views" "$TMP/$s.txt" || fail "loop $s printed its steps: $(cat "$TMP/$s.txt")"
  for f in steps.csv loop.json reference.ply meshes/step_00_views_03.ply meshes/step_02_views_05.ply; do
    [ -f "$TMP/$s/$f" ] || fail "loop $s: missing $f"
  done
  /usr/bin/python3 - "$TMP/$s" "$s" <<'PY' || fail "loop $s results"
import csv, json, sys
d, strategy = sys.argv[1], sys.argv[2]
j = json.load(open(d + "/loop.json"))
assert j["format"] == "meshnbv-loop" and j["strategy"] == strategy and j["synthetic"]
steps = j["steps"]
assert [s["num_views"] for s in steps] == [3, 4, 5]
assert all(s["views"][-1] == s["added"] for s in steps[1:])
assert len(set(steps[-1]["views"])) == 5
rows = list(csv.DictReader(open(d + "/steps.csv")))
assert len(rows) == 3 and rows[2]["num_views"] == "5"
keys = [k for k in rows[0] if k.startswith("completeness_")]
assert len(keys) == 3 and any(k.startswith("accuracy_") for k in rows[0])
widest = keys[-1]
comp = [float(r[widest]) for r in rows]
# More views must not lose the surface (slack for the graph cut's choices).
for a, b in zip(comp, comp[1:]):
    assert b >= a - 0.03, comp
assert comp[0] > 0.05, comp
PY
done
# Without incremental PRI: the same views chosen, every face computed at
# every step (and with it, no step computed more faces than it has).
"$MESHNBV" loop "$TMP/synth" --strategy nbv --view-budget 5 --out "$TMP/nbv_full" --cache "$TMP/cache" \
  --no-incremental-pri --quiet >/dev/null 2>&1 || fail "loop --no-incremental-pri"
/usr/bin/python3 - "$TMP/nbv" "$TMP/nbv_full" <<'PY' || fail "loop incremental PRI against full"
import json, sys
inc, full = (json.load(open(d + "/loop.json")) for d in sys.argv[1:3])
assert inc["options"]["incremental_pri"] is True and full["options"]["incremental_pri"] is False
assert [s["views"] for s in inc["steps"]] == [s["views"] for s in full["steps"]]
for a, b in zip(inc["steps"][1:], full["steps"][1:]):
    assert b["pri_faces"]["recomputed"] == b["pri_faces"]["total"] > 0, b["pri_faces"]
    assert 0 <= a["pri_faces"]["recomputed"] <= a["pri_faces"]["total"], a["pri_faces"]
PY
# --bootstraps: uniform from 3 starting sets spread over the ring (centres
# 0, 6 and 3 of 12 views), each run in its folder; bootstraps.csv holds the
# mean and 95% interval of each metric per view count, checked here against
# the runs' own steps.csv and the t critical value of 2 degrees of freedom
# in closed form, (2p - 1) / sqrt(2 p (1 - p)) at p = 0.975.
"$MESHNBV" loop "$TMP/synth" --strategy uniform --view-budget 4 --bootstraps 3 --out "$TMP/boot" \
  --cache "$TMP/cache" --save-meshes none >"$TMP/boot.txt" 2>&1 || fail "loop --bootstraps: $(tail -3 "$TMP/boot.txt")"
grep -q "^3 starting sets: {0,1,11} {5,6,7} {2,3,4}" "$TMP/boot.txt" || fail "starting sets printed: $(head -5 "$TMP/boot.txt")"
grep -q "^run 3/3 step 1: 4 views" "$TMP/boot.txt" || fail "runs printed: $(cat "$TMP/boot.txt")"
/usr/bin/python3 - "$TMP/boot" <<'PY' || fail "loop --bootstraps results"
import csv, json, math, os, statistics, sys
d = sys.argv[1]
j = json.load(open(d + "/bootstraps.json"))
assert j["format"] == "meshnbv-loop-bootstraps" and j["strategy"] == "uniform"
assert [r["bootstrap_views"] for r in j["runs"]] == [[0, 1, 11], [5, 6, 7], [2, 3, 4]], j["runs"]
assert all(r["done"] for r in j["runs"])
p = 0.975
assert abs(j["t_critical"]["3"] - (2 * p - 1) / math.sqrt(2 * p * (1 - p))) < 1e-9, j["t_critical"]
runs = []
for r in j["runs"]:
    loop = json.load(open(os.path.join(d, r["folder"], "loop.json")))
    assert sorted(loop["steps"][0]["views"]) == ["view_%03d" % i for i in r["bootstrap_views"]], loop["steps"][0]

    runs.append(list(csv.DictReader(open(os.path.join(d, r["folder"], "steps.csv")))))
rows = list(csv.DictReader(open(d + "/bootstraps.csv")))
assert rows and set(r["num_views"] for r in rows) == {"3", "4"}, rows
checked = 0
for row in rows:
    if not row["metric"].startswith("completeness_"):
        continue
    x = [float(s[row["metric"]]) for run in runs for s in run if s["num_views"] == row["num_views"]]
    assert int(row["runs"]) == len(x) == 3, row
    m = statistics.fmean(x)
    half = j["t_critical"]["3"] * statistics.stdev(x) / math.sqrt(3)
    assert abs(float(row["mean"]) - m) < 1e-7, (row, x)
    assert abs(float(row["ci_low"]) - (m - half)) < 1e-6 and abs(float(row["ci_high"]) - (m + half)) < 1e-6, (row, x)
    assert float(row["min"]) == min(x) and float(row["max"]) == max(x)
    checked += 1
assert checked == 6, checked  # 3 thresholds x 2 view counts
for name, a in j["curve_areas"].items():
    assert a["runs"] == 3 and a["ci_low"] <= a["mean"] <= a["ci_high"], (name, a)
PY
expect_error "cannot be combined with --bootstraps" "$MESHNBV" loop "$TMP/synth" --bootstraps 2 \
  --bootstrap-views 0,1,2 --out "$TMP/b2" --cache "$TMP/cache"
expect_error "13 starting sets asked of 12 views" "$MESHNBV" loop "$TMP/synth" --bootstraps 13 \
  --out "$TMP/b3" --cache "$TMP/cache"
expect_error "--overwrite" "$MESHNBV" loop "$TMP/synth" --strategy uniform --bootstraps 3 --out "$TMP/boot" --cache "$TMP/cache"
# The cache is shared: features and matches were computed once.
[ "$(grep -c '^\$ .*feature_extractor' "$TMP/cache/colmap/colmap.log")" -eq 1 ] || fail "features computed once"
expect_error "--overwrite" "$MESHNBV" loop "$TMP/synth" --strategy uniform --view-budget 5 --out "$TMP/uniform" --cache "$TMP/cache"
expect_error "below the bootstrap" "$MESHNBV" loop "$TMP/synth" --view-budget 2 --out "$TMP/x" --cache "$TMP/cache"
expect_error "needs a synthetic dataset" "$MESHNBV" loop "$ROOT/sample_projects/building/project.mlp" \
  --nbv-candidates sampled --out "$TMP/y" --cache "$TMP/cache_box"
finish

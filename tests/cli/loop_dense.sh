# meshnbv loop --backend dense on a small synthetic building (18 ring views
# of 640x480, 20 degrees apart; bootstrap with 5 neighbours, up to 7 views): the steps carry
# the dense statistics and the time split, later steps match only their new
# pairs (the rest comes from the cache), the dense mesh beats the sparse one
# at the same views, and a step without dense points is recorded as failed
# with its reason while the loop goes on. Skips when colmap is missing.
source "$(dirname "$0")/lib.bash"

if ! QT_QPA_PLATFORM=offscreen colmap help >/dev/null 2>&1; then
  echo "SKIP: colmap not installed (apt-get install colmap)"
  finish
  exit 0
fi

"$MESHNBV" synth building --out "$TMP/synth" --views 18 --size 640x480 --samples-per-pixel 1 --quiet >/dev/null \
  || fail "synth"
COMMON=(--strategy uniform --cache "$TMP/cache" --facet-support edges --quiet --save-meshes none)
"$MESHNBV" loop "$TMP/synth" "${COMMON[@]}" --backend dense --bootstrap 5 --bootstrap-views 0,1,2,3,4 --view-budget 7 --out "$TMP/dense" >"$TMP/dense.txt" 2>&1 \
  || fail "loop dense: $(tail -3 "$TMP/dense.txt")"
"$MESHNBV" loop "$TMP/synth" "${COMMON[@]}" --backend sparse --bootstrap 5 --bootstrap-views 0,1,2,3,4 --view-budget 7 --out "$TMP/sparse" >"$TMP/sparse.txt" 2>&1 \
  || fail "loop sparse: $(tail -3 "$TMP/sparse.txt")"
/usr/bin/python3 - "$TMP/dense" "$TMP/sparse" <<'PY' || fail "dense loop results"
import csv, json, sys
dense, sparse = (json.load(open(d + "/loop.json")) for d in sys.argv[1:3])
assert dense["options"]["backend"] == "dense" and sparse["options"]["backend"] == "sparse"
steps = dense["steps"]
assert [s["num_views"] for s in steps] == [5, 6, 7], [s["num_views"] for s in steps]
for s in steps:
    assert "failure" not in s, s.get("failure")
    d = s["dense"]
    # Every view has a depth map or is listed as failed (a view across the
    # ring from the others shares no sparse points with them).
    failed = [f for f in d["failures"] if f.startswith("view ")]
    assert d["views"] + len(failed) == s["num_views"] and d["views"] >= 5, d
    assert d["points"] > 1000 and d["points"] <= d["raw_points"], d
    t = s["seconds"]
    assert abs(t["sparse"] + t["dense"] + t["mesh"] - t["reconstruct"]) < 0.05 * t["reconstruct"] + 0.01, t
# After the bootstrap a step matches only the pairs it has not seen.
for s in steps[1:]:
    assert 0 <= s["dense"]["pairs_computed"] < s["dense"]["pairs"], s["dense"]
assert steps[0]["dense"]["pairs_computed"] == steps[0]["dense"]["pairs"] > 0, steps[0]["dense"]
# Dense against sparse at the same views (uniform chooses the same ones).
assert [s["views"] for s in steps] == [s["views"] for s in sparse["steps"]]
key = sorted(steps[-1]["completeness"], key=float)[1]  # 1% of the diagonal
cd, cs = steps[-1]["completeness"][key], sparse["steps"][-1]["completeness"][key]
# Measured: 0.52 against 0.35 (5 neighbouring views cover a third of the ring).
assert cd > cs + 0.1 and cd > 0.45, (cd, cs)
assert steps[-1]["points"] > 10 * sparse["steps"][-1]["points"], (steps[-1]["points"], sparse["steps"][-1]["points"])
rows = list(csv.DictReader(open(sys.argv[1] + "/steps.csv")))
assert len(rows) == 3 and rows[2]["num_views"] == "7" and any(k.startswith("completeness_") for k in rows[0])
PY
# No view can have 4 agreeing partners among 3 views: the bootstrap step
# has no dense points, is recorded as failed, and the loop goes on.
"$MESHNBV" loop "$TMP/synth" "${COMMON[@]}" --backend dense --view-budget 4 --dense-min-agreeing 4 \
  --out "$TMP/failing" >"$TMP/failing.txt" 2>&1 || fail "loop with a failing step: $(tail -3 "$TMP/failing.txt")"
grep -q "^step 0: 3 views.*FAILED: no dense points (view .*stereo partners (needs 4))" "$TMP/failing.txt" \
  || fail "failed step printed: $(head -3 "$TMP/failing.txt")"
/usr/bin/python3 - "$TMP/failing" <<'PY' || fail "failed step recorded"
import json, sys
j = json.load(open(sys.argv[1] + "/loop.json"))
s0 = j["steps"][0]
assert s0["failure"].startswith("no dense points") and s0["faces"] == 0, s0
assert len(s0["dense"]["failures"]) == 3, s0["dense"]
assert [s["num_views"] for s in j["steps"]] == [3, 4], [s["num_views"] for s in j["steps"]]
PY
expect_error "dense block_size" "$MESHNBV" loop "$TMP/synth" --backend dense --dense-block-size 4 --out "$TMP/x" --cache "$TMP/cache"
expect_error "backend" "$MESHNBV" loop "$TMP/synth" --backend mvs --out "$TMP/x" --cache "$TMP/cache"
finish

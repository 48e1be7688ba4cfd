# meshnbv pri on the sample project: PLY with quality and colour, JSON summary, errors.
source "$(dirname "$0")/lib.bash"
S="$ROOT/sample_projects/building/project.mlp"
out=$("$MESHNBV" pri "$S" --out "$TMP/pri.ply" --json "$TMP/pri.json" --quiet) || fail "pri failed"
grep -q "faces 14188: " <<<"$out" || fail "summary line: $out"
head -c 2000 "$TMP/pri.ply" | grep -q "property float quality" || fail "no quality property"
head -c 2000 "$TMP/pri.ply" | grep -q "property uchar red" || fail "no face colour"
/usr/bin/python3 - "$TMP/pri.json" <<'PY' || fail "json content"
import json, sys
s = json.load(open(sys.argv[1]))
f = s["faces"]
assert f["total"] == 14188 and f["observed"] + f["unobserved"] + f["textureless"] == 14188, f
assert f["observed"] > 8000, f
p = s["pri_percentiles"]
assert 0 <= p["p0"] <= p["p50"] <= p["p95"] <= p["p100"], p
assert len(s["worst_faces"]) == 10 and s["worst_faces"][0]["pri"] == p["p100"], s["worst_faces"][:2]
assert all(w["views"] >= 2 for w in s["worst_faces"])
assert sum(s["histogram"]["counts"]) == f["observed"]
assert s["options"]["measure"] == "ssd" and s["options"]["max_views_per_face"] == 0
assert s["seconds"] > 0 and s["views_used"] == 12
PY
# NCC, limited views, two threads: same faces observed or fewer.
"$MESHNBV" pri "$S" --measure ncc --max-views-per-face 4 --threads 2 --out "$TMP/ncc.ply" --json "$TMP/ncc.json" --quiet >/dev/null || fail "ncc"
/usr/bin/python3 -c "import json,sys; s=json.load(open('$TMP/ncc.json')); assert s['options']['measure']=='ncc' and s['options']['max_views_per_face']==4; assert all(w['views']<=4 for w in s['worst_faces'])" || fail "ncc json"
# The evidence in the PLY (beside quality and pri_views) and the JSON: the
# measure and its unit, the evidence block, worst faces with pairs and texture.
# ssd compares every pair of the n views: n (n - 1) / 2.
/usr/bin/python3 - "$ROOT/tests/support" "$TMP/pri.ply" "$TMP/pri.json" ssd "squared intensity" <<'PY' || fail "ssd evidence"
import json, math, sys
sys.path.insert(0, sys.argv[1])
from ply_faces import read_face_properties
names, faces = read_face_properties(sys.argv[2])
s = json.load(open(sys.argv[3]))
for p in ("quality", "pri_views", "pri_pairs", "pri_samples", "pri_texture"):
    assert p in names, (p, names)
assert s["measure"] == sys.argv[4] and s["unit"] == sys.argv[5], (s["measure"], s["unit"])
observed = [f for f in faces if not math.isnan(f["quality"])]
assert len(faces) == 14188 and len(observed) == s["faces"]["observed"]
for f in observed:
    n = f["pri_views"]
    assert f["pri_pairs"] == n * (n - 1) / 2, f
    assert 3 <= f["pri_samples"] <= 561 and f["pri_texture"] >= 0, f  # r in [2, 32]
for f in faces:
    assert math.isnan(f["pri_texture"]) == (f["pri_views"] < 2), f
e = s["evidence"]
assert e["observed"] == len(observed)
assert e["two_views"] == sum(f["pri_views"] == 2 for f in observed), e
assert e["low_texture"] == sum(f["pri_texture"] < e["low_texture_below"] for f in observed), e
assert e["low_texture_below"] == 0.01
assert e["pairs_percentiles"]["p100"] == max(f["pri_pairs"] for f in observed)
assert e["texture_percentiles"]["p0"] == min(f["pri_texture"] for f in observed)
for w in s["worst_faces"]:
    f = faces[w["face"]]
    assert w["pairs"] == f["pri_pairs"] and abs(w["texture"] - f["pri_texture"]) < 1e-7, (w, f)
print("ssd: %d observed, %d on 2 views, %d on low texture" % (len(observed), e["two_views"], e["low_texture"]))
PY
# offset: the same outputs; it compares the n - 1 other views with the reference.
out=$("$MESHNBV" pri "$S" --measure offset --out "$TMP/offset.ply" --json "$TMP/offset.json" --quiet) || fail "offset failed"
grep -q "PRI (offset, scene units) median" <<<"$out" || fail "offset summary line: $out"
grep -q "^evidence: [0-9]* of [0-9]* observed faces rest on 2 views; [0-9]* on low texture (below 0.01)" <<<"$out" || fail "offset evidence line: $out"
/usr/bin/python3 - "$ROOT/tests/support" "$TMP/offset.ply" "$TMP/offset.json" <<'PY' || fail "offset evidence"
import json, math, sys
sys.path.insert(0, sys.argv[1])
from ply_faces import read_face_properties
names, faces = read_face_properties(sys.argv[2])
s = json.load(open(sys.argv[3]))
assert s["measure"] == "offset" and s["unit"] == "scene units" and s["options"]["measure"] == "offset", s
for p in ("quality", "pri_views", "pri_pairs", "pri_samples", "pri_texture"):
    assert p in names, (p, names)
observed = [f for f in faces if not math.isnan(f["quality"])]
assert len(observed) == s["faces"]["observed"] > 8000, len(observed)
assert all(f["quality"] >= 0 for f in observed)
exact = sum(f["pri_pairs"] == f["pri_views"] - 1 for f in observed)
assert all(1 <= f["pri_pairs"] <= f["pri_views"] - 1 for f in observed)
# Fewer than n - 1 where a view's patch is textureless at zero offset: a few percent here.
assert exact >= 0.95 * len(observed), (exact, len(observed))
assert all(3 <= f["pri_samples"] <= 153 for f in observed)  # r in [2, 16]
e = s["evidence"]
assert e["two_views"] == sum(f["pri_views"] == 2 for f in observed), e
assert e["low_texture"] == sum(f["pri_texture"] < 0.01 for f in observed), e
for w in s["worst_faces"]:
    assert 1 <= w["pairs"] <= w["views"] - 1 and w["pairs"] == faces[w["face"]]["pri_pairs"], w
print("offset: %d observed, median %.4g scene units" % (len(observed), s["pri_percentiles"]["p50"]))
PY
expect_error "--overwrite" "$MESHNBV" pri "$S" --out "$TMP/pri.ply" --quiet
"$MESHNBV" convert "$S" "$TMP/noimg.json" >/dev/null
sed -i 's/"image": "[^"]*"/"image": null/' "$TMP/noimg.json"
expect_error "at least 2 views with images" "$MESHNBV" pri "$TMP/noimg.json" --out "$TMP/x.ply"
if "$MESHNBV" pri "$S" --measure mad --out "$TMP/y.ply" 2>/dev/null; then fail "bad measure accepted"; fi
finish

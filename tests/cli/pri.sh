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
expect_error "--overwrite" "$MESHNBV" pri "$S" --out "$TMP/pri.ply" --quiet
"$MESHNBV" convert "$S" "$TMP/noimg.json" >/dev/null
sed -i 's/"image": "[^"]*"/"image": null/' "$TMP/noimg.json"
expect_error "at least 2 views with images" "$MESHNBV" pri "$TMP/noimg.json" --out "$TMP/x.ply"
if "$MESHNBV" pri "$S" --measure mad --out "$TMP/y.ply" 2>/dev/null; then fail "bad measure accepted"; fi
finish

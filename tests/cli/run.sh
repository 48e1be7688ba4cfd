# meshnbv run: every file of the main job, progress quiet or as JSON lines.
source "$(dirname "$0")/lib.bash"
"$MESHNBV" synth building --out "$TMP/p" --views 6 --size 160x120 --layout orbit --quiet >/dev/null || fail "synth"
"$MESHNBV" run "$TMP/p/project.mlp" --out "$TMP/r" --top 2 --quiet >"$TMP/out.txt" 2>"$TMP/err.txt" || fail "run"
for f in report.html overview_1.png overview_2.png cameras.png histogram.png nbv_1.png nbv_2.png pri.ply pri.json \
         suggestions.json suggestions.mlp frustums.ply viewer/meshnbv_viewer.js viewer/report_data.js; do
  [ -s "$TMP/r/$f" ] || fail "missing $f"
done
grep -q "report: $TMP/r/report.html" "$TMP/out.txt" || fail "report path printed"
[ ! -s "$TMP/err.txt" ] || fail "--quiet printed progress: $(head -2 "$TMP/err.txt")"
"$MESHNBV" info "$TMP/r/suggestions.mlp" | grep -q "views      8 (6 with image" || fail "mlp with the 2 suggested rasters"
"$MESHNBV" run "$TMP/p/project.mlp" --out "$TMP/r" --top 2 --progress json --overwrite >/dev/null 2>"$TMP/json.txt" || fail "run --progress json"
/usr/bin/python3 - "$TMP/json.txt" <<'PY' || fail "json progress"
import json, sys
lines = [l for l in open(sys.argv[1]) if l.strip()]
assert len(lines) > 5, lines
stages = set()
for l in lines:
    d = json.loads(l)
    assert set(d) == {"stage", "fraction", "elapsed", "eta"}, d
    assert 0 <= d["fraction"] <= 1
    stages.add(d["stage"])
assert {"visibility", "view selection", "pri", "suggest", "report"} <= stages, stages
PY
expect_error "--overwrite" "$MESHNBV" run "$TMP/p/project.mlp" --out "$TMP/r" --quiet
# The 3-D view: its scripts, loaded from the report's folder (no network),
# and the mesh decimated above --display-faces, which the page says.
grep -q '<script src="viewer/report_data.js"></script>' "$TMP/r/report.html" || fail "data script in report.html"
grep -q '<script src="viewer/meshnbv_viewer.js"></script>' "$TMP/r/report.html" || fail "viewer script in report.html"
! grep -qE '(src|href)="(https?:)?//' "$TMP/r/report.html" || fail "report.html refers to the network"
faces=$("$MESHNBV" info "$TMP/p/project.mlp" | sed -nE "s/^ +vertices [0-9]+, faces ([0-9]+),.*/\\1/p")
grep -q "Display mesh: the $faces faces" "$TMP/r/report.html" || fail "not decimated below the budget ($faces faces)"
"$MESHNBV" run "$TMP/p/project.mlp" --out "$TMP/d" --top 1 --display-faces 1000 --quiet >/dev/null || fail "run --display-faces"
grep -qE "Display mesh decimated from $faces to [0-9]{3,4} faces" "$TMP/d/report.html" || fail "decimation stated"
/usr/bin/python3 - "$TMP/d/viewer/report_data.js" <<'PY' || fail "decimated view data"
import json, sys
text = open(sys.argv[1]).read()
data = json.loads(text[text.index("=") + 1:].rstrip().rstrip(";"))
assert data["decimated"] and 0 < data["display_faces"] <= 1000, data["display_faces"]
assert data["arrays"]["members"]["count"] == data["faces"], data["arrays"]["members"]["count"]
assert data["arrays"]["member_begin"]["count"] == data["display_faces"] + 1
assert data["arrays"]["face_pri"]["count"] == data["faces"]
PY
expect_error "--display-faces" "$MESHNBV" run "$TMP/p/project.mlp" --out "$TMP/e" --display-faces 10 --quiet
finish

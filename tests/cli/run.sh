# meshnbv run: every file of the main job, progress quiet or as JSON lines.
source "$(dirname "$0")/lib.bash"
"$MESHNBV" synth building --out "$TMP/p" --views 6 --size 160x120 --layout orbit --quiet >/dev/null || fail "synth"
"$MESHNBV" run "$TMP/p/project.mlp" --out "$TMP/r" --top 2 --quiet >"$TMP/out.txt" 2>"$TMP/err.txt" || fail "run"
for f in report.html overview_1.png overview_2.png histogram.png nbv_1.png nbv_2.png pri.ply pri.json \
         suggestions.json suggestions.mlp frustums.ply; do
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
finish

# The report's 3-D view in a real browser (headless Debian chromium through
# playwright-core, WebGL on SwiftShader): report.html of `meshnbv run` opened
# from file:// shows the mesh, makes no request but file:// (and the data:
# pictures the page embeds), logs no error; clicking the first suggestion
# puts the camera at its pose (suggestions.json); clicking the canvas centre
# shows that face's PRI, the value in pri.ply. Fails (never skips) when
# chromium is missing: CI installs it (scripts/install-deps.sh).
# Arguments: meshnbv, repository root, scratch folder, shared data, node_modules.
source "$(dirname "$0")/../cli/lib.bash"
NODE_MODULES=$5
CHROMIUM=${MESHNBV_CHROMIUM:-/usr/bin/chromium}
if [ ! -x "$CHROMIUM" ]; then
  echo "FAIL: $CHROMIUM not found: install Debian's chromium (scripts/install-deps.sh) or set MESHNBV_CHROMIUM"
  exit 1
fi
[ -d "$NODE_MODULES/playwright-core" ] || { echo "FAIL: no playwright-core in $NODE_MODULES (the build's npm ci)"; exit 1; }
"$MESHNBV" synth building --out "$TMP/p" --views 6 --size 160x120 --layout orbit --quiet >/dev/null || fail "synth"
"$MESHNBV" run "$TMP/p/project.mlp" --out "$TMP/r" --top 2 --quiet >/dev/null || fail "run"
for f in viewer/meshnbv_viewer.js viewer/report_data.js; do [ -s "$TMP/r/$f" ] || fail "missing $f"; done
grep -q 'id="meshnbv-viewer"' "$TMP/r/report.html" || fail "report.html has no 3-D view"
NODE_PATH=$NODE_MODULES timeout -k 5 120 node "$(dirname "$0")/viewer_test.cjs" "$CHROMIUM" "$TMP/r" "$TMP/browser.json" \
  || fail "browser checks"
if [ -s "$TMP/browser.json" ]; then
  /usr/bin/python3 - "$ROOT/tests/support" "$TMP/r" "$TMP/browser.json" <<'PY' || fail "screenshot and picked face"
import json, math, sys
sys.path.insert(0, sys.argv[1])
from PIL import Image
from ply_faces import read_face_properties
folder, result = sys.argv[2], json.load(open(sys.argv[3]))
# The canvas shows the mesh: its middle fifth is mostly not the white background.
img = Image.open(result["screenshot"]).convert("RGB")
w, h = img.size
box = img.crop((2 * w // 5, 2 * h // 5, 3 * w // 5, 3 * h // 5))
pixels = list(box.getdata())
mesh = sum(1 for p in pixels if max(abs(c - 255) for c in p) > 12)
assert mesh > 0.5 * len(pixels), f"the canvas centre is background: {mesh} of {len(pixels)} pixels drawn"
# The face clicked at the centre: its value is the one in pri.ply.
picked = result["picked"]
assert picked is not None, "no face under the canvas centre"
_, faces = read_face_properties(folder + "/pri.ply")
face = faces[picked["face"]]
quality = face["quality"]
if math.isnan(quality):
    assert picked["pri"] is None, picked
else:
    assert picked["pri"] == quality, f"face {picked['face']}: shown {picked['pri']}, pri.ply {quality}"
assert picked["views"] == int(face["pri_views"]), (picked, face["pri_views"])
assert picked["pairs"] == int(face["pri_pairs"]), (picked, face["pri_pairs"])
assert picked["samples"] == int(face["pri_samples"]), (picked, face["pri_samples"])
print(f"picked face {picked['face']}: PRI {picked['pri']} ({picked['shown']!r} on the page), "
      f"{mesh} of {len(pixels)} centre pixels drawn")
PY
fi
finish

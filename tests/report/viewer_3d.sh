# The report's 3-D view in a real browser (headless Debian chromium through
# playwright-core, WebGL on SwiftShader): report.html of `meshnbv run` opened
# from file:// shows the mesh, makes no request but file:// (and the data:
# pictures the page embeds), logs no error; clicking the first suggestion
# puts the camera at its pose (suggestions.json); while a drag turns the
# camera the coarser interaction mesh is drawn, after the rest delay the
# display mesh (the scene is above the interaction budget); clicking the
# canvas centre shows that face's PRI, the value in pri.ply, and a face
# picked while the interaction mesh is on screen is the mesh's own (value
# in pri.ply, picked point on it). Fails (never skips) when
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
# Edge 0.12 m: 85,576 faces, above the interaction budget (40,000), so that
# the view has an interaction mesh to draw while turning.
"$MESHNBV" synth building --out "$TMP/p" --views 6 --size 160x120 --layout orbit --edge-length 0.12 --quiet >/dev/null \
  || fail "synth"
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
# The faces picked (clicked at the centre at rest; picked at the centre while
# the interaction mesh was on screen): their values are those in pri.ply,
# and the picked point lies on that face of the mesh (picking used the
# display mesh, which here is the mesh itself).
import struct
from ply_faces import _header
data = open(folder + "/pri.ply", "rb").read()
fmt, elements, at = _header(data)
assert fmt == "binary_little_endian", fmt
vertices, corners = [], []
for name, count, props in elements:
    for _ in range(count):
        row, lists = {}, {}
        for prop, code, item in props:
            if item is None:
                row[prop] = struct.unpack_from("<" + code, data, at)[0]
                at += struct.calcsize(code)
            else:
                n = struct.unpack_from("<" + code, data, at)[0]
                at += struct.calcsize(code)
                lists[prop] = struct.unpack_from("<%d%s" % (n, item), data, at)
                at += n * struct.calcsize(item)
        if name == "vertex":
            vertices.append((row["x"], row["y"], row["z"]))
        elif name == "face":
            corners.append(next(iter(lists.values())))
_, faces = read_face_properties(folder + "/pri.ply")
assert len(corners) == len(faces)


def distance_to_face(p, f):
    a, b, c = (vertices[i] for i in corners[f])
    sub = lambda u, v: [u[k] - v[k] for k in range(3)]
    dot = lambda u, v: sum(u[k] * v[k] for k in range(3))
    cross = lambda u, v: [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    n = cross(sub(b, a), sub(c, a))
    nn = math.sqrt(dot(n, n))
    off_plane = abs(dot(sub(p, a), n)) / nn
    # inside the triangle (barycentric signs, with a small tolerance)
    inside = all(dot(cross(sub(v1, v0), sub(p, v0)), n) >= -1e-3 * nn * nn ** 0.5
                 for v0, v1 in ((a, b), (b, c), (c, a)))
    return off_plane, inside, math.sqrt(nn)


for key in ("picked", "picked_while_turning"):
    picked = result[key]
    assert picked is not None, f"{key}: no face under the canvas centre"
    face = faces[picked["face"]]
    quality = face["quality"]
    if math.isnan(quality):
        assert picked["pri"] is None, picked
    else:
        assert picked["pri"] == quality, f"{key} face {picked['face']}: shown {picked['pri']}, pri.ply {quality}"
    assert picked["views"] == int(face["pri_views"]), (key, picked, face["pri_views"])
    assert picked["pairs"] == int(face["pri_pairs"]), (key, picked, face["pri_pairs"])
    assert picked["samples"] == int(face["pri_samples"]), (key, picked, face["pri_samples"])
    off, inside, size = distance_to_face(picked["point"], picked["face"])
    assert off <= 1e-3 * size and inside, f"{key}: point {picked['point']} not on face {picked['face']} ({off}, {inside})"
lod = result["lod"]
print(f"picked face {result['picked']['face']}: PRI {result['picked']['pri']} ({result['picked']['shown']!r} on the page), "
      f"face {result['picked_while_turning']['face']} while turning ({lod['interactionFaces']} of "
      f"{lod['displayFaces']} faces drawn); {mesh} of {len(pixels)} centre pixels drawn")
PY
fi
finish

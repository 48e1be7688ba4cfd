# A georeferenced scene (issue #20): the bundled building moved to
# (1e6, 2e6, 500), mesh and cameras. Float holds those coordinates only to
# 6-12 cm, so:
# - `pri` writes pri.ply with double coordinates (exact);
# - `suggest --pri pri.ply` gives the same suggestions as `run` (PRI
#   computed in the same process) and as `suggest` computing the PRI;
# - `suggest --pri` with a float copy of pri.ply (as an older `pri` wrote
#   it) keeps the scene's own mesh: still the same suggestions (with the
#   float mesh they move by metres);
# - a PRI file of another mesh (one vertex moved by 1 m) is refused.
source "$(dirname "$0")/lib.bash"
SRC=$ROOT/sample_projects/building

# The translated scene: exact double coordinates (ascii PLY, 17 digits),
# t' = t - R T so that every camera sees what it saw.
/usr/bin/python3 - "$SRC" "$TMP" <<'PY' || fail "prepare the far scene"
import json, os, struct, sys
src, out = sys.argv[1], sys.argv[2]
T = (1e6, 2e6, 500.0)
s = json.load(open(src + "/scene.json"))
data = open(src + "/degraded.ply", "rb").read()
end = data.index(b"end_header\n") + len(b"end_header\n")
element, nv, nf, face_props = None, 0, 0, []
for line in data[:end].decode().splitlines():
    w = line.split()
    if w[:1] == ["element"]:
        element = w[1]
        nv = int(w[2]) if element == "vertex" else nv
        nf = int(w[2]) if element == "face" else nf
    elif w[:1] == ["property"] and element == "vertex":
        assert w[1] == "float", line
    elif w[:1] == ["property"] and element == "face":
        face_props.append(w)
assert "binary_little_endian" in data[:end].decode()
assert face_props[0][1:4] == ["list", "uchar", "int"] and all(p[1] == "float" for p in face_props[1:])
verts = [struct.unpack_from("<3f", data, end + 12 * i) for i in range(nv)]
off, faces = end + 12 * nv, []
for i in range(nf):
    assert data[off] == 3
    faces.append(struct.unpack_from("<3i", data, off + 1))
    off += 1 + 12 + 4 * (len(face_props) - 1)
with open(out + "/far_mesh.ply", "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex %d\n" % nv)
    f.write("property double x\nproperty double y\nproperty double z\n")
    f.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % nf)
    for v in verts:
        f.write("%r %r %r\n" % tuple(float(v[k]) + T[k] for k in range(3)))
    for a in faces:
        f.write("3 %d %d %d\n" % a)
for v in s["views"]:
    R, t = v["camera"]["R"], v["camera"]["t"]
    v["camera"]["t"] = [t[r] - sum(R[r][k] * T[k] for k in range(3)) for r in range(3)]
    if v.get("image"):
        v["image"] = os.path.join(src, v["image"])
s["mesh"] = "far_mesh.ply"
json.dump(s, open(out + "/far.json", "w"), indent=1)
PY
FAR=$TMP/far.json
"$MESHNBV" info "$FAR" | grep -q "bbox     (999995, 2e+06, 499.9" || fail "far scene bbox: $("$MESHNBV" info "$FAR" | grep bbox)"

OPTS=(--top 3 --seed 7 --samples-per-side 0)
"$MESHNBV" pri "$FAR" --out "$TMP/pri.ply" --quiet >/dev/null || fail "pri"
head -c 400 "$TMP/pri.ply" | grep -q "property double x" || fail "pri.ply of a far mesh must hold double coordinates"
"$MESHNBV" suggest "$FAR" --pri "$TMP/pri.ply" "${OPTS[@]}" --out "$TMP/from_file.json" --quiet >/dev/null \
  || fail "suggest --pri"
"$MESHNBV" suggest "$FAR" "${OPTS[@]}" --out "$TMP/computed.json" --quiet >/dev/null || fail "suggest"
"$MESHNBV" run "$FAR" "${OPTS[@]}" --out "$TMP/run" --quiet >/dev/null || fail "run"

# pri.ply as an older meshnbv wrote it: float coordinates (cm off), and one
# of another mesh (vertex 0 moved by 1 m).
/usr/bin/python3 - "$TMP/pri.ply" "$TMP" <<'PY' || fail "float copies of pri.ply"
import struct, sys
src, out = sys.argv[1], sys.argv[2]
data = open(src, "rb").read()
end = data.index(b"end_header\n") + len(b"end_header\n")
header = data[:end].decode()
nv = int(header.split("element vertex ")[1].split()[0])
double = "property double x\nproperty double y\nproperty double z\n"
assert double in header and "binary_little_endian" in header
head = header.replace(double, double.replace("double", "float")).encode()
for name, bump in (("pri_float.ply", 0.0), ("pri_other_mesh.ply", 1.0)):
    body = bytearray()
    for i in range(nv):
        x, y, z = struct.unpack_from("<3d", data, end + 24 * i)
        body += struct.pack("<3f", x + (bump if i == 0 else 0.0), y, z)
    open(out + "/" + name, "wb").write(head + bytes(body) + data[end + 24 * nv:])
PY
"$MESHNBV" suggest "$FAR" --pri "$TMP/pri_float.ply" "${OPTS[@]}" --out "$TMP/from_float.json" --quiet >/dev/null \
  || fail "suggest --pri with float coordinates (within float precision of the scene's mesh)"
expect_error "the PRI was computed on a different mesh" \
  "$MESHNBV" suggest "$FAR" --pri "$TMP/pri_other_mesh.ply" "${OPTS[@]}" --out "$TMP/other.json" --quiet
[ ! -e "$TMP/other.json" ] || fail "suggestions written for another mesh"
# The same building at the origin (same faces, other vertices) is another mesh too.
expect_error "vertex 0 is at (999" "$MESHNBV" suggest "$SRC/project.mlp" --pri "$TMP/pri.ply" \
  --out "$TMP/x.json" --quiet

# The same suggested centres (to 1 micrometre) and energies everywhere.
/usr/bin/python3 - "$TMP/run/suggestions.json" "$TMP/from_file.json" "$TMP/computed.json" \
  "$TMP/from_float.json" <<'PY' || fail "suggestions differ"
import json, sys
ref = json.load(open(sys.argv[1]))["suggestions"]
assert len(ref) == 3, ref
assert all(abs(s["centre"][0] - 1e6) < 100 and abs(s["centre"][1] - 2e6) < 100 for s in ref), ref
for path in sys.argv[2:]:
    got = json.load(open(path))["suggestions"]
    assert len(got) == len(ref), (path, len(got))
    for a, b in zip(ref, got):
        d = max(abs(x - y) for x, y in zip(a["centre"], b["centre"]))
        assert d < 1e-6, "%s: %s: centre %s vs run's %s (%.3g m)" % (path, b["label"], b["centre"], a["centre"], d)
        e = abs(a["energy"]["total"] - b["energy"]["total"])
        assert e <= 1e-9 * max(1.0, abs(a["energy"]["total"])), (path, a["energy"], b["energy"])
PY
finish

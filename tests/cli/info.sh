# meshnbv info on the bundled sample project, as text and JSON, and its errors.
source "$(dirname "$0")/lib.bash"
out=$("$MESHNBV" info "$ROOT/sample_projects/box/box.mlp") || fail "info failed"
grep -q "vertices 98, faces 192" <<<"$out" || fail "mesh counts: $out"
grep -q "boundary edges 0, non-manifold edges 0" <<<"$out" || fail "checks: $out"
grep -q "views      8 (8 with image, 8 image files present" <<<"$out" || fail "views: $out"
"$MESHNBV" info "$ROOT/sample_projects/box/box.mlp" --json "$TMP/info.json" >/dev/null || fail "info --json"
/usr/bin/python3 - "$TMP/info.json" <<'PY' || fail "json content"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["mesh"]["faces"] == 192 and s["mesh"]["closed"] is True, s["mesh"]
assert s["views"]["count"] == 8 and s["views"]["with_image"] == 8, s["views"]
assert abs(s["views"]["fx"][0] - 288.0) < 1e-9
d = s["views"]["center_distance_to_mesh_box_center"]
assert abs(d[0] - 2.77308) < 1e-4 and abs(d[1] - d[0]) < 1e-9, d
PY
"$MESHNBV" info --help | grep -q -- "--image-dir" || fail "info --help"
"$MESHNBV" --help | grep -q "convert" || fail "--help lists commands"
expect_error "scene not found" "$MESHNBV" info "$TMP/missing.mlp"
printf '<MeshLabProject><MeshGroup>' > "$TMP/broken.mlp"
expect_error "malformed XML" "$MESHNBV" info "$TMP/broken.mlp"
mkdir -p "$TMP/empty"
expect_error "cannot tell the scene format" "$MESHNBV" info "$TMP/empty"
finish

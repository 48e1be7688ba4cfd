# meshnbv info on the bundled sample project (sample_projects/building), as text and JSON, and its errors.
source "$(dirname "$0")/lib.bash"
out=$("$MESHNBV" info "$ROOT/sample_projects/building/project.mlp") || fail "info failed"
grep -q "vertices 7110, faces 14188" <<<"$out" || fail "mesh counts: $out"
grep -q "boundary edges 0, non-manifold edges 0" <<<"$out" || fail "checks: $out"
grep -q "views      12 (12 with image, 12 image files present" <<<"$out" || fail "views: $out"
"$MESHNBV" info "$ROOT/sample_projects/building/project.mlp" --json "$TMP/info.json" >/dev/null || fail "info --json"
/usr/bin/python3 - "$TMP/info.json" <<'PY' || fail "json content"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["mesh"]["faces"] == 14188 and s["mesh"]["closed"] is True, s["mesh"]
assert s["views"]["count"] == 12 and s["views"]["with_image"] == 12, s["views"]
# 320 px over a 60 degree horizontal field of view: fx = 160 / tan(30 deg)
assert abs(s["views"]["fx"][0] - 277.128129) < 1e-5, s["views"]["fx"]
d = s["views"]["center_distance_to_mesh_box_center"]
assert 20 < d[0] <= d[1] < 25, d
PY
"$MESHNBV" info --help | grep -q -- "--image-dir" || fail "info --help"
"$MESHNBV" --help | grep -q "convert" || fail "--help lists commands"
expect_error "scene not found" "$MESHNBV" info "$TMP/missing.mlp"
printf '<MeshLabProject><MeshGroup>' > "$TMP/broken.mlp"
expect_error "malformed XML" "$MESHNBV" info "$TMP/broken.mlp"
mkdir -p "$TMP/empty"
expect_error "cannot tell the scene format" "$MESHNBV" info "$TMP/empty"
finish

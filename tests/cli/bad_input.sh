# Bad inputs (tests/data/bad/, listed in its README.md): every one gives one
# line of error naming the problem and a non-zero exit, and leaves no output
# behind; a write that fails half-way leaves no half-written file.
source "$(dirname "$0")/lib.bash"
BAD=$ROOT/tests/data/bad
OUT=$TMP/out
mkdir -p "$OUT"

# A small valid scene (pyramid, two 8x6 views), absolute paths into $BAD/scenes.
GOOD=$TMP/good.json
cam='"width": 8, "height": 6, "fx": 8, "fy": 8, "cx": 3.5, "cy": 2.5, "R": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]'
cat >"$GOOD" <<JSON
{"format": "meshnbv-scene", "version": 1, "mesh": "$BAD/scenes/pyramid.ply", "views": [
 {"label": "a", "image": "$BAD/scenes/view_a.png", "camera": {$cam, "t": [-0.5, -0.5, 3]}},
 {"label": "b", "image": "$BAD/scenes/view_b.png", "camera": {$cam, "t": [-0.4, -0.5, 3]}}]}
JSON
"$MESHNBV" info "$GOOD" >/dev/null || fail "the good scene does not read"

# The output folder must be empty after a failed command.
no_output() {
  if [ -n "$(ls -A "$OUT")" ]; then
    fail "output left behind by: $* ($(ls -A "$OUT" | tr '\n' ' '))"
    rm -rf "${OUT:?}"/*
  fi
}
# fails "fragment" command...: expect_error, then nothing written to $OUT.
fails() {
  expect_error "$@"
  no_output "${@:2}"
}
pri() { "$MESHNBV" pri "$@" --out "$OUT/pri.ply" --json "$OUT/pri.json" --quiet; }
run() { "$MESHNBV" run "$@" --out "$OUT/run" --quiet; }
convert() { "$MESHNBV" convert "$@" "$OUT/scene.json"; }

# Meshes, given with --mesh to the good scene: info and convert refuse them
# (pri reads the scene the same way: checked for a few).
bad_mesh() {
  local file=$BAD/$1 fragment=$2
  fails "$fragment" "$MESHNBV" info "$GOOD" --mesh "$file"
  fails "$fragment" convert "$GOOD" --mesh "$file"
  if [ "${3-}" = pri ]; then fails "$fragment" pri "$GOOD" --mesh "$file"; fi
}
bad_mesh face_index_out_of_range.ply "face 1: vertex index 7 out of range"
bad_mesh huge_vertex_count.ply "header declares 1000000000000 vertices" pri
bad_mesh huge_face_count.ply "header declares 1000000000000 faces"
bad_mesh huge_list_length.ply "face 0: truncated data"
bad_mesh malformed_header.ply "unknown property type 'quaternion'"
bad_mesh nan_vertex.ply "vertex 2: coordinate is not finite"
bad_mesh truncated_ascii.ply "the file is truncated"
bad_mesh truncated_binary.ply "face 1: truncated data"
bad_mesh wrong_count.ply "vertex 3: the line has 1 more value(s) than the header declares"
bad_mesh wrong_endianness.ply "vertex index 50331648 out of range" pri
bad_mesh wrong_endianness_be.ply "vertex index 50331648 out of range"
bad_mesh wrong_magic.ply "not a PLY file"
bad_mesh nan_vertex.obj "nan_vertex.obj:4: vertex 2" pri
bad_mesh out_of_range.obj "vertex index 9 (1-based) out of range"
bad_mesh huge_count.off "header declares 1000000000000 vertices"
bad_mesh nan_vertex.off "not a finite number ('nan')"
bad_mesh truncated.off "unexpected end of file: expected vertex 2"
bad_mesh missing.ply "missing.ply: file not found"

# Zero-area faces are reported, and a mesh with nothing but them cannot be used.
out=$("$MESHNBV" info "$GOOD" --mesh "$BAD/zero_area_faces.ply") || fail "info on zero-area faces"
grep -q "degenerate faces 3" <<<"$out" || fail "zero-area faces not reported: $out"
fails "no non-degenerate face" run "$BAD/scenes/zero_area_mesh.json"
fails "no non-degenerate face" "$MESHNBV" suggest "$BAD/scenes/zero_area_mesh.json" --out "$OUT/s.json"

# Scenes: unreadable ones fail in every command (pri checked for a few).
bad_scene() {
  local scene=$BAD/$1 fragment=$2
  fails "$fragment" "$MESHNBV" info "$scene"
  fails "$fragment" convert "$scene"
  if [ "${3-}" = pri ]; then fails "$fragment" pri "$scene"; fi
}
bad_scene scenes/malformed.mlp "malformed.mlp:5: malformed XML"
bad_scene scenes/nan_camera.mlp "raster 'a' FocalMm is not a finite number ('nan')"
bad_scene scenes/huge_viewport.mlp "raster 'a': ViewportPx" pri
bad_scene scenes/binary_camera_garbage.mlp "binary_camera_garbage.mlp: raster 'a' RotationMatrix: invalid base64"
bad_scene scenes/missing_mesh.mlp "gone.ply: file not found"
bad_scene scenes/not_utf8.mlp ".ply: file not found"
bad_scene scenes/missing_mesh.json "gone.ply: file not found"
bad_scene scenes/nan_camera.json "nan_camera.json: malformed JSON"
bad_scene scenes/truncated.json "truncated.json: malformed JSON"
bad_scene scenes/not_utf8.json "ill-formed UTF-8"
bad_scene scenes/wrong_type.json "wrong_type.json: \"version\" must be" pri
bad_scene scenes/huge_camera.json "view 0 ('a'): \"width\" must be"
bad_scene middlebury_count "declares 3 cameras but holds 2"
bad_scene middlebury_huge_count "declares 99999999999999 cameras but holds 1"
bad_scene middlebury_short_line "set_par.txt:3: expected 22 fields"
bad_scene middlebury_no_images "none of the 2 images is present" pri
bad_scene middlebury_unreadable_image "a.png: image does not decode"
bad_scene colmap_unknown_camera "refers to camera 9"
bad_scene colmap_truncated "images.txt:1: expected 10 fields"
bad_scene colmap_bad_model "unknown camera model 'FISHEYE'"
bad_scene colmap_zero_quaternion "zero quaternion"
bad_scene colmap_bin_truncated "number of images = 1 does not fit in the 32 bytes left"
bad_scene colmap_bin_unknown_model "unknown camera model id 42"
bad_scene colmap_bin_huge_count "number of images = 4611686018427387904 does not fit"
bad_scene bundler_truncated "truncated: the file ends inside camera 1" pri
bad_scene bundler_huge_count "declares 99999999999 cameras"
bad_scene bundler_list_mismatch "lists 1 images but"
bad_scene bundler_missing_image "gone.png (its size fixes the principal point)"

# Images missing, unreadable or of the wrong size: the scene reads (info and
# convert work), what needs the pixels fails.
"$MESHNBV" info "$BAD/scenes/image_missing.json" >/dev/null || fail "info with a missing image"
fails "missing.png: image file not found" pri "$BAD/scenes/image_missing.json"
fails "unreadable.png: image does not decode" pri "$BAD/scenes/image_unreadable.json"
fails "image is 16x12 but its camera says 8x6" pri "$BAD/scenes/image_wrong_size.json"
fails "missing.png: image file not found" run "$BAD/scenes/image_missing.json"

# Cameras facing away from the mesh: nothing is observed, so there is nothing
# to rank or suggest.
fails "no observed face" run "$BAD/scenes/cameras_facing_away.json"
# ... and the reason, plainly, before computing.
run "$BAD/scenes/cameras_facing_away.json" 2>&1 >/dev/null | grep -q "^warning: only 0% of the mesh's faces .* another coordinate frame" \
  || fail "cameras facing away: no warning that the mesh lies in no view"
fails "no observed face" "$MESHNBV" suggest "$BAD/scenes/cameras_facing_away.json" --out "$OUT/s.json"

# Paths that are not UTF-8 work like any other, and name themselves in errors.
odd=$(printf '%s/caf\xe9' "$TMP")
odd_mesh=$(printf '%s/m\xff.ply' "$odd")
mkdir -p "$odd"
cp "$BAD/scenes/pyramid.ply" "$odd_mesh"
"$MESHNBV" info "$GOOD" --mesh "$odd_mesh" >/dev/null || fail "non-UTF-8 mesh path"
"$MESHNBV" convert "$GOOD" "$odd/scene.mlp" --mesh "$odd_mesh" >/dev/null || fail "convert to a non-UTF-8 folder"
"$MESHNBV" info "$odd/scene.mlp" >/dev/null || fail "read back from a non-UTF-8 folder"
expect_error "scene not found" "$MESHNBV" info "$(printf '%s/nope\xff.json' "$TMP")"
expect_error "file not found" "$MESHNBV" info "$GOOD" --mesh "$(printf '%s/nope\xfe.ply' "$TMP")"

# A write that fails half-way (file size limit: the kernel refuses the rest)
# leaves nothing, and an existing output untouched.
limited() { (ulimit -f 8; trap '' XFSZ; exec "$@"); }
SAMPLE=$ROOT/sample_projects/building/project.mlp
fails "write failed" limited "$MESHNBV" convert "$SAMPLE" "$OUT/big.json"
echo "old" >"$OUT/keep_mesh.ply"
expect_error "write failed" limited "$MESHNBV" convert "$SAMPLE" "$OUT/keep.json" --overwrite
[ "$(cat "$OUT/keep_mesh.ply")" = "old" ] || fail "existing output changed by a failed write"
[ "$(ls -A "$OUT")" = "keep_mesh.ply" ] || fail "temporary files left: $(ls -A "$OUT")"
finish

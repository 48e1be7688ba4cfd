# meshnbv synth: every output file, same seed same bytes, clear errors.
source "$(dirname "$0")/lib.bash"
"$MESHNBV" synth city --out "$TMP/a" --views 3 --size 64x48 --degrade hole --degrade noise:0.004 --quiet >/dev/null || fail "synth city"
for f in truth.ply degraded.ply gt_error.csv project.mlp scene.json README.md images/view_000.png images/view_002.png; do
  [ -f "$TMP/a/$f" ] || fail "missing $f"
done
[ "$(ls "$TMP/a/images" | wc -l)" -eq 3 ] || fail "image count"
head -1 "$TMP/a/gt_error.csv" | grep -q "face,gt_error" || fail "gt_error.csv header"
grep -q "hole" "$TMP/a/README.md" || fail "README lists the degradations"
"$MESHNBV" synth city --out "$TMP/b" --views 3 --size 64x48 --degrade hole --degrade noise:0.004 --quiet >/dev/null || fail "second run"
cmp -s "$TMP/a/images/view_001.png" "$TMP/b/images/view_001.png" || fail "same seed, different image"
cmp -s "$TMP/a/degraded.ply" "$TMP/b/degraded.ply" || fail "same seed, different mesh"
"$MESHNBV" info "$TMP/a/project.mlp" | grep -q "views      3 (3 with image" || fail "project reads back"
"$MESHNBV" synth object --mesh "$TMP/a/truth.ply" --out "$TMP/obj" --views 2 --size 32x24 --quiet >/dev/null || fail "object scene"
expect_error "not empty" "$MESHNBV" synth city --out "$TMP/a" --views 3 --size 64x48 --quiet
expect_error "--size must look like" "$MESHNBV" synth city --out "$TMP/c" --size 64-48
expect_error "needs a mesh" "$MESHNBV" synth object --out "$TMP/d"
expect_error "unknown degradation" "$MESHNBV" synth city --out "$TMP/e" --degrade melt
finish

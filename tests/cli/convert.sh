# meshnbv convert between .mlp, JSON and COLMAP, with overwrite protection.
source "$(dirname "$0")/lib.bash"
S="$ROOT/sample_projects/building/project.mlp"
"$MESHNBV" convert "$S" "$TMP/box.json" >/dev/null || fail "to json"
"$MESHNBV" convert "$TMP/box.json" "$TMP/colmap" >/dev/null || fail "json to colmap"
[ -f "$TMP/colmap/cameras.txt" ] && [ -f "$TMP/colmap/images.txt" ] || fail "colmap files"
"$MESHNBV" convert "$TMP/colmap" "$TMP/back.mlp" >/dev/null || fail "colmap to mlp"
a=$("$MESHNBV" info "$S" --json - | /usr/bin/python3 -c 'import json,sys; v=json.load(sys.stdin)["views"]; print(v["count"], v["fx"], v["cx"], v["image_files_present"])')
b=$("$MESHNBV" info "$TMP/back.mlp" --json - | /usr/bin/python3 -c 'import json,sys; v=json.load(sys.stdin)["views"]; print(v["count"], v["fx"], v["cx"], v["image_files_present"])')
[ "$a" = "$b" ] || fail "views differ after mlp->json->colmap->mlp: '$a' vs '$b'"
expect_error "--overwrite" "$MESHNBV" convert "$S" "$TMP/box.json"
"$MESHNBV" convert "$S" "$TMP/box.json" --overwrite >/dev/null || fail "overwrite"
expect_error "cannot tell the output format" "$MESHNBV" convert "$S" "$TMP/x.txt"
finish

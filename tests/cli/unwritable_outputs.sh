# Outputs that cannot be written (issue #20): every command checks every
# output before it reads or computes anything, and fails with one line
# naming the output, exit code 1, and nothing written. The scene given is
# missing on purpose: if the error named it, the output would have been
# checked too late. Then the same on a real scene: nothing left behind.
source "$(dirname "$0")/lib.bash"
S=$ROOT/sample_projects/building/project.mlp
NOPE=$TMP/no_such_scene.mlp
FILE=$TMP/regular_file            # a file where a folder is needed
echo "not a folder" >"$FILE"
UNDER=$FILE/sub                   # a path under a regular file
mkdir -p "$TMP/planes"
/usr/bin/python3 - "$TMP/planes" <<'PY' || fail "prepare planes"
import sys
d = sys.argv[1]
with open(d + "/plane.ply", "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n")
    f.write("element face 2\nproperty list uchar int vertex_indices\nend_header\n")
    f.write("0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")
PY
PLANE=$TMP/planes/plane.ply

# unwritable "fragment" command...: one line of error holding fragment, and
# no trace of the scene (it was never read).
unwritable() {
  local fragment=$1; shift
  local err
  err=$("$@" 2>&1 >/dev/null)
  local rc=$?
  [ $rc -eq 1 ] || fail "exit code $rc (expected 1): $*"
  [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "expected one line of error, got: $err"
  case "$err" in "meshnbv: error: "*) ;; *) fail "error does not start with 'meshnbv: error: ': $err";; esac
  case "$err" in *"$fragment"*) ;; *) fail "error '$err' lacks '$fragment' ($*)";; esac
  case "$err" in *no_such_scene*) fail "the scene was read before the output was checked: $err";; esac
}

# 1. Paths under a regular file (works for root too), for every output of every command.
F="it is a file, not a folder"
unwritable "$F" "$MESHNBV" pri "$NOPE" --out "$UNDER/pri.ply"
unwritable "$F" "$MESHNBV" pri "$NOPE" --out "$TMP/ok.ply" --json "$UNDER/pri.json"
unwritable "$F" "$MESHNBV" suggest "$NOPE" --out "$UNDER/s.json"
unwritable "$F" "$MESHNBV" suggest "$NOPE" --out "$TMP/s.json" --mlp "$UNDER/s.mlp"
unwritable "$F" "$MESHNBV" suggest "$NOPE" --out "$TMP/s.json" --frustums "$UNDER/f.ply"
unwritable "$F" "$MESHNBV" suggest "$NOPE" --out "$TMP/s.json" --colmap-model "$UNDER/colmap"
unwritable "$F" "$MESHNBV" run "$NOPE" --out "$UNDER/run"
unwritable "$F" "$MESHNBV" loop "$NOPE" --out "$UNDER/loop"
unwritable "$F" "$MESHNBV" loop "$NOPE" --out "$TMP/loop" --cache "$UNDER/cache"
unwritable "$F" "$MESHNBV" convert "$NOPE" "$UNDER/scene.json"
unwritable "$F" "$MESHNBV" convert "$NOPE" "$UNDER/scene.mlp"
unwritable "$F" "$MESHNBV" convert "$NOPE" "$UNDER/colmap"
unwritable "$F" "$MESHNBV" synth building --out "$UNDER/synth"
unwritable "$F" "$MESHNBV" evaluate "$TMP/nope.ply" "$PLANE" --json "$UNDER/e.json"
unwritable "$F" "$MESHNBV" info "$NOPE" --json "$UNDER/i.json"
# ... deeper below it, too.
unwritable "$F" "$MESHNBV" pri "$NOPE" --out "$UNDER/a/b/pri.ply"

# 2. A folder output naming an existing file, a file output naming a folder.
E="is a file, expected a folder"
unwritable "$E" "$MESHNBV" run "$NOPE" --out "$FILE"
unwritable "$E" "$MESHNBV" loop "$NOPE" --out "$FILE"
unwritable "$E" "$MESHNBV" synth city --out "$FILE"
unwritable "$E" "$MESHNBV" suggest "$NOPE" --out "$TMP/s.json" --colmap-model "$FILE"
unwritable "$E" "$MESHNBV" convert "$NOPE" "$FILE" --out-format colmap
mkdir -p "$TMP/a_folder"
unwritable "is a folder, expected a file" "$MESHNBV" pri "$NOPE" --out "$TMP/a_folder" --overwrite
unwritable "is a folder, expected a file" "$MESHNBV" suggest "$NOPE" --out "$TMP/a_folder" --overwrite
# Existing outputs without --overwrite, still before reading.
unwritable "--overwrite" "$MESHNBV" pri "$NOPE" --out "$FILE"
touch "$TMP/exists.json"
unwritable "--overwrite" "$MESHNBV" convert "$NOPE" "$TMP/exists.json"
mkdir -p "$TMP/colmap_out" && touch "$TMP/colmap_out/images.txt"
unwritable "--overwrite" "$MESHNBV" suggest "$NOPE" --out "$TMP/s.json" --colmap-model "$TMP/colmap_out"

# 3. /proc: no file can be created there, not even by root.
P="cannot create files in folder '/proc'"
unwritable "$P" "$MESHNBV" pri "$NOPE" --out /proc/meshnbv_pri.ply
unwritable "$P" "$MESHNBV" run "$NOPE" --out /proc/meshnbv_run
unwritable "$P" "$MESHNBV" convert "$NOPE" /proc/meshnbv_scene.json

# 4. A read-only folder: chmod for a normal user; for root (whom chmod does
# not stop) a read-only bind mount in a private mount namespace, if allowed.
RO=$TMP/readonly
mkdir -p "$RO"
if [ "$(id -u)" -ne 0 ]; then
  chmod a-w "$RO"
  ro() { "$@"; }
  have_ro=1
elif unshare -m sh -c 'mount --bind "$0" "$0" && mount -o remount,bind,ro "$0" && ! touch "$0/probe"' \
       "$RO" 2>/dev/null; then
  ro() { unshare -m sh -c 'mount --bind "$0" "$0" && mount -o remount,bind,ro "$0" && exec "$@"' "$RO" "$@"; }
  have_ro=1
else
  echo "SKIP read-only folder part: root without mount namespaces (chmod does not stop root)"
  have_ro=0
fi
if [ "$have_ro" = 1 ]; then
  R="cannot create files in folder '$RO'"
  unwritable "$R" ro "$MESHNBV" pri "$NOPE" --out "$RO/pri.ply"
  unwritable "$R" ro "$MESHNBV" pri "$NOPE" --out "$TMP/ok.ply" --json "$RO/new/pri.json"
  unwritable "$R" ro "$MESHNBV" suggest "$NOPE" --out "$RO/s.json"
  unwritable "$R" ro "$MESHNBV" suggest "$NOPE" --out "$TMP/s.json" --mlp "$RO/s.mlp"
  unwritable "$R" ro "$MESHNBV" suggest "$NOPE" --out "$TMP/s.json" --frustums "$RO/f.ply"
  unwritable "$R" ro "$MESHNBV" suggest "$NOPE" --out "$TMP/s.json" --colmap-model "$RO/colmap"
  unwritable "$R" ro "$MESHNBV" run "$NOPE" --out "$RO/run"
  unwritable "$R" ro "$MESHNBV" run "$NOPE" --out "$RO"
  unwritable "$R" ro "$MESHNBV" loop "$NOPE" --out "$RO/loop"
  unwritable "$R" ro "$MESHNBV" convert "$NOPE" "$RO/scene.mlp"
  unwritable "$R" ro "$MESHNBV" convert "$NOPE" "$RO/colmap"
  unwritable "$R" ro "$MESHNBV" synth building --out "$RO/synth"
  unwritable "$R" ro "$MESHNBV" evaluate "$TMP/nope.ply" "$PLANE" --json "$RO/e.json"
  [ -z "$(ls -A "$RO")" ] || fail "something was written into the read-only folder: $(ls -A "$RO")"
  chmod u+w "$RO"
fi

# 5. On the real scene: the same refusals, and nothing written anywhere.
OUT=$TMP/out
mkdir -p "$OUT"
expect_error "$F" "$MESHNBV" run "$S" --out "$UNDER/run" --quiet
expect_error "$F" "$MESHNBV" pri "$S" --out "$OUT/pri.ply" --json "$UNDER/pri.json" --quiet
expect_error "$F" "$MESHNBV" suggest "$S" --out "$OUT/s.json" --colmap-model "$UNDER/colmap" --quiet
expect_error "$E" "$MESHNBV" run "$S" --out "$FILE" --quiet
[ -z "$(ls -A "$OUT")" ] || fail "outputs left behind: $(ls -A "$OUT")"
[ "$(cat "$FILE")" = "not a folder" ] || fail "the regular file changed"
# And what is writable still works, creating missing folders.
"$MESHNBV" pri "$S" --out "$OUT/new/deeper/pri.ply" --quiet >/dev/null || fail "pri into a new folder"
[ -s "$OUT/new/deeper/pri.ply" ] || fail "pri.ply not written into the new folder"
[ -z "$(find "$OUT" -name '.meshnbv_write_probe*')" ] || fail "write probes left behind"
finish

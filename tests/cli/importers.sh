# Real projects in: COLMAP models with distorted lenses, read as text and as
# binary (written here by an independent writer, /usr/bin/python3 struct, in
# COLMAP's documented layout), and `meshnbv run` on them.
source "$(dirname "$0")/lib.bash"
"$MESHNBV" synth building --out "$TMP/p" --views 6 --size 160x120 --layout orbit --quiet >/dev/null || fail "synth"
"$MESHNBV" convert "$TMP/p/project.mlp" "$TMP/model" >/dev/null || fail "convert to COLMAP"
[ -s "$TMP/model/cameras.txt" ] || fail "no cameras.txt"

# Lenses COLMAP writes by default (SIMPLE_RADIAL) and OPENCV with tangential
# terms: same focal length and principal point, a small distortion.
lens_model() {  # <folder> <model> <extra params>
  rm -rf "$1"; cp -r "$TMP/model" "$1"
  /usr/bin/python3 - "$1/cameras.txt" "$2" "$3" <<'PY'
import sys
path, model, extra = sys.argv[1:4]
out = []
for line in open(path):
    if line.startswith("#") or not line.strip():
        out.append(line); continue
    cid, _, w, h, fx, fy, cx, cy = line.split()[:8]
    if model == "SIMPLE_RADIAL":
        out.append(f"{cid} SIMPLE_RADIAL {w} {h} {fx} {cx} {cy} {extra}\n")
    else:
        out.append(f"{cid} OPENCV {w} {h} {fx} {fy} {cx} {cy} {extra}\n")
open(path, "w").write("".join(out))
PY
}
lens_model "$TMP/radial" SIMPLE_RADIAL "-0.02"
lens_model "$TMP/opencv" OPENCV "-0.02 0.004 0.0007 -0.0005"
grep -q "SIMPLE_RADIAL" "$TMP/radial/cameras.txt" || fail "SIMPLE_RADIAL model written"

for m in radial opencv; do
  "$MESHNBV" run "$TMP/$m" --mesh "$TMP/p/degraded.ply" --out "$TMP/run_$m" --top 1 --quiet \
    >"$TMP/out_$m.txt" 2>"$TMP/err_$m.txt" || fail "run on a $m COLMAP model: $(tail -1 "$TMP/err_$m.txt")"
  [ -s "$TMP/run_$m/report.html" ] || fail "$m: no report"
  [ -s "$TMP/run_$m/pri.ply" ] || fail "$m: no pri.ply"
  [ ! -e "$TMP/run_$m/suggestions.mlp" ] || fail "$m: a .mlp was written for a distorted lens"
  grep -q "warning: suggestions.mlp skipped: view .* has a lens" "$TMP/err_$m.txt" || fail "$m: no one-line skip warning"
done

# Binary model: the same OPENCV model through an independent writer.
/usr/bin/python3 - "$TMP/opencv" "$TMP/opencv_bin" <<'PY' || fail "binary writer"
import os, struct, sys
src, dst = sys.argv[1:3]
os.makedirs(dst, exist_ok=True)
models = {"SIMPLE_PINHOLE": 0, "PINHOLE": 1, "SIMPLE_RADIAL": 2, "RADIAL": 3, "OPENCV": 4}
def data_lines(name):
    return [l.rstrip("\n") for l in open(os.path.join(src, name)) if not l.startswith("#")]
cams = [l.split() for l in data_lines("cameras.txt") if l.strip()]
with open(os.path.join(dst, "cameras.bin"), "wb") as f:
    f.write(struct.pack("<Q", len(cams)))
    for c in cams:
        params = [float(p) for p in c[4:]]
        f.write(struct.pack("<IiQQ", int(c[0]), models[c[1]], int(c[2]), int(c[3])))
        f.write(struct.pack("<%dd" % len(params), *params))
lines = data_lines("images.txt")
images = [lines[i].split() for i in range(0, len(lines), 2) if lines[i].strip()]
with open(os.path.join(dst, "images.bin"), "wb") as f:
    f.write(struct.pack("<Q", len(images)))
    for im in images:
        f.write(struct.pack("<I7dI", int(im[0]), *[float(v) for v in im[1:8]], int(im[8])))
        f.write(im[9].encode() + b"\0" + struct.pack("<Q", 0))
with open(os.path.join(dst, "points3D.bin"), "wb") as f:
    f.write(struct.pack("<Q", 0))
PY
"$MESHNBV" info "$TMP/opencv_bin" --json "$TMP/bin.json" >"$TMP/info_bin.txt" 2>&1 \
  || fail "info on a binary model without --format: $(tail -1 "$TMP/info_bin.txt")"
grep -q "from       COLMAP (binary model)" "$TMP/info_bin.txt" || fail "binary model not named"
grep -q "lens     brown k1=-0.02 k2=0.004 p1=0.0007 p2=-0.0005 x6" "$TMP/info_bin.txt" || fail "lens not reported: $(cat "$TMP/info_bin.txt")"
"$MESHNBV" info "$TMP/opencv" --json "$TMP/txt.json" >/dev/null || fail "info text"
/usr/bin/python3 - "$TMP/bin.json" "$TMP/txt.json" <<'PY' || fail "binary and text differ"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for key in ("fx", "fy", "cx", "cy", "lenses", "resolutions"):
    assert a["views"][key] == b["views"][key], (key, a["views"][key], b["views"][key])
PY

# COLMAP's own converter, when installed, writes a binary model we must read alike.
if command -v colmap >/dev/null; then
  mkdir -p "$TMP/colmap_bin"
  QT_QPA_PLATFORM=offscreen colmap model_converter --input_path "$TMP/opencv" --output_path "$TMP/colmap_bin" \
    --output_type BIN >/dev/null 2>&1 || fail "colmap model_converter"
  "$MESHNBV" info "$TMP/colmap_bin" --json "$TMP/colmap.json" >/dev/null || fail "info on COLMAP's binary"
  /usr/bin/python3 - "$TMP/colmap.json" "$TMP/txt.json" <<'PY' || fail "COLMAP's binary differs from the text model"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for key in ("fx", "fy", "cx", "cy", "lenses", "resolutions"):
    assert a["views"][key] == b["views"][key], (key, a["views"][key], b["views"][key])
PY
else
  echo "note: colmap not installed, COLMAP's own binary writer not checked"
fi

# A mesh from another frame (here: the cameras moved 1000 units away): said
# plainly before computing.
rm -rf "$TMP/moved"; cp -r "$TMP/opencv" "$TMP/moved"
/usr/bin/python3 - "$TMP/moved/images.txt" <<'PY' || fail "moved cameras"
import sys
path = sys.argv[1]
out, image_line = [], True
for line in open(path):
    if line.startswith("#"):
        out.append(line); continue
    if image_line and line.strip():
        f = line.split()
        f[7] = str(float(f[7]) + 1000.0)  # TZ: the scene 1000 units further, outside the images
        f[5] = str(float(f[5]) + 1000.0)  # TX
        line = " ".join(f) + "\n"
    out.append(line)
    image_line = not image_line
open(path, "w").write("".join(out))
PY
"$MESHNBV" info "$TMP/moved" --mesh "$TMP/p/degraded.ply" >"$TMP/info_moved.txt" 2>&1 || fail "info with a moved mesh"
grep -q "warning: only 0% of the mesh's faces .* another coordinate frame" "$TMP/info_moved.txt" || fail "no frame warning: $(cat "$TMP/info_moved.txt")"
"$MESHNBV" info "$TMP/opencv" --mesh "$TMP/p/degraded.ply" >"$TMP/info_ok.txt" 2>&1 || fail "info"
! grep -q "another coordinate frame" "$TMP/info_ok.txt" || fail "frame warning on the right mesh"
finish

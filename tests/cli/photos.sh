# Photos as cameras write them: a portrait JPEG stored on its side with its
# EXIF orientation tag, a 16-bit PNG, and a photo that fits its camera
# neither way. `meshnbv info` reports them from the headers; `pri` reads the
# tagged photo turned (the camera has the turned size) and the 16-bit one
# at 16 bits, and refuses the misfit naming both sizes. The photos are
# written here by PIL (Debian's python3-pil), independently of OpenCV.
source "$(dirname "$0")/lib.bash"
"$MESHNBV" synth building --out "$TMP/p" --views 6 --size 160x120 --layout orbit --quiet >/dev/null || fail "synth"
/usr/bin/python3 - "$TMP/p" <<'PY' || fail "writing the photos"
import json, sys
from PIL import Image
d = sys.argv[1]
s = json.load(open(d + "/scene.json"))
def exif(tag):
    e = Image.Exif()
    e[0x0112] = tag
    return e
# View 0: stored turned 90 degrees anticlockwise, tag 6 (turn clockwise to view).
im = Image.open(d + "/" + s["views"][0]["image"]).convert("RGB")
im.transpose(Image.Transpose.ROTATE_90).save(d + "/turned.jpg", quality=95, exif=exif(6))
s["views"][0]["image"] = "turned.jpg"
# View 1: 16-bit grey, 257 x the 8-bit luma plus a ramp below one 8-bit step.
g = Image.open(d + "/" + s["views"][1]["image"]).convert("L")
w, h = g.size
px = [g.getpixel((x, y)) * 257 + min(200, (x * 7 + y) % 200) for y in range(h) for x in range(w)]
g16 = Image.new("I;16", (w, h))
g16.putdata(px)
g16.save(d + "/deep.png")
s["views"][1]["image"] = "deep.png"
json.dump(s, open(d + "/scene.json", "w"))
# View 2 on its side without a tag to turn it by.
Image.open(d + "/" + s["views"][2]["image"]).transpose(Image.Transpose.ROTATE_90).save(d + "/side.jpg", exif=exif(1))
s["views"][2]["image"] = "side.jpg"
json.dump(s, open(d + "/misfit.json", "w"))
PY
out=$("$MESHNBV" info "$TMP/p/misfit.json") || fail "info: $out"
echo "$out" | grep -q "^photos     .*120x160 x2" || fail "stored sizes not reported: $out"
echo "$out" | grep -q "bits 16 x1 8 x5" || fail "bit depths not reported: $out"
echo "$out" | grep -q "EXIF orientation 1 x1 6 x1" || fail "orientation tags not reported: $out"
echo "$out" | grep -q "turned   1 photos stored on their side" || fail "the turned photo not reported: $out"
echo "$out" | grep -q "mismatch 1 photos of another size than their camera's, e.g. view_002: 120x160, camera 160x120" \
  || fail "the misfit not reported: $out"
"$MESHNBV" info "$TMP/p/misfit.json" --json "$TMP/info.json" >/dev/null || fail "info --json"
/usr/bin/python3 -c 'import json,sys; p=json.load(open(sys.argv[1]))["photos"]; assert p["read_turned"]==1 and p["size_mismatch"]==1 and p["bits"]=={"16":1,"8":5}, p' \
  "$TMP/info.json" || fail "info JSON photos"
expect_error "image is 120x160 but its camera says 160x120 (turned by its EXIF orientation it is still 120x160)" \
  "$MESHNBV" pri "$TMP/p/misfit.json" --out "$TMP/misfit_pri.ply"
[ -e "$TMP/misfit_pri.ply" ] && fail "a refused run left its output"
"$MESHNBV" pri "$TMP/p/scene.json" --out "$TMP/pri.ply" --json "$TMP/pri.json" --quiet >/dev/null || fail "pri on the turned and 16-bit photos"
/usr/bin/python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); assert s["faces"]["observed"] > 0 and s["views_used"] == 6, s["views_used"]' \
  "$TMP/pri.json" || fail "pri did not use every photo"
finish

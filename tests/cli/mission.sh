# meshnbv mission: the files of a mission from a --georef file and from the
# photos' EXIF GPS (tags written by Pillow, an independent writer), read
# back; the bad inputs of issue 18 give one-line errors and write nothing.
source "$(dirname "$0")/lib.bash"
S="$ROOT/sample_projects/building/project.mlp"
"$MESHNBV" suggest "$S" --top 5 --out "$TMP/s.json" --quiet >/dev/null || fail "suggest"
echo '{"crs": "EPSG:32632", "transform": [1,0,0,500000, 0,1,0,5000000, 0,0,1,100, 0,0,0,1]}' > "$TMP/georef.json"
out=$("$MESHNBV" mission "$S" --suggestions "$TMP/s.json" --georef "$TMP/georef.json" --out "$TMP/m" \
      --max-altitude 26 --battery-minutes 0.5 --max-waypoints 3 2>&1) || fail "mission: $out"
grep -q "5 of 5 suggestions in" <<<"$out" || fail "summary: $out"
for f in mission.kml mission.kmz mission.geojson waypoints.csv mission.json mission.svg litchi_1.csv litchi_2.csv; do
  [ -s "$TMP/m/$f" ] || fail "missing $f"
done
[ -e "$TMP/m/litchi.csv" ] && fail "litchi.csv beside litchi_<k>.csv"
/usr/bin/python3 - "$TMP/m" <<'PY' || fail "mission files"
import json, sys, zipfile, glob
d = sys.argv[1]
m = json.load(open(d + "/mission.json"))
assert m["format"] == "meshnbv-mission" and len(m["flights"]) >= 2
for f in m["flights"]:
    assert f["minutes"] <= 0.5 + 1e-9 and len(f["photos"]) <= 3, f
assert m["options"]["max_altitude"] == 26 and m["options"]["battery_minutes"] == 0.5
assert any(n["action"] == "moved" and "max_altitude" in n["reason"] for n in m["notes"]), m["notes"]
z = zipfile.ZipFile(d + "/mission.kmz")
assert sorted(z.namelist()) == ["wpmz/template.kml", "wpmz/waylines.wpml"]
header = open(d + "/litchi_1.csv").readline().strip()
assert header.startswith("latitude,longitude,altitude(m),heading(deg),curvesize(m),rotationdir,gimbalmode,gimbalpitchangle,actiontype1,actionparam1,")
assert header.endswith("altitudemode,speed(m/s),poi_latitude,poi_longitude,poi_altitude(m),poi_altitudemode,photo_timeinterval,photo_distinterval")
rows = sum(1 for f in glob.glob(d + "/litchi_*.csv") for l in open(f).readlines()[1:] if l.split(",")[8] == "1")
assert rows == 5, rows
import xml.etree.ElementTree as ET
svg = ET.parse(d + "/mission.svg").getroot()
texts = [t.text for t in svg.iter("{http://www.w3.org/2000/svg}text")]
assert len(texts) == len(m["flights"]) and texts[0].startswith("flight 1: "), texts
g = json.load(open(d + "/mission.geojson"))
assert sum(1 for f in g["features"] if f["properties"]["kind"] == "photo") == 5
PY
expect_error "--overwrite" "$MESHNBV" mission "$S" --suggestions "$TMP/s.json" --georef "$TMP/georef.json" --out "$TMP/m"

# EXIF GPS: the scene's photos as JPEGs tagged with positions of a known
# placement (1 scene unit = 1 m, rotated 90 degrees: scene x = north).
mkdir -p "$TMP/exif"
/usr/bin/python3 - "$ROOT/sample_projects/building" "$TMP/exif" <<'PY' || fail "tagging photos"
import json, math, os, sys
from PIL import Image
src, dst = sys.argv[1], sys.argv[2]
s = json.load(open(os.path.join(src, "scene.json")))
s["mesh"] = os.path.join(src, s["mesh"])
lat0, lon0, h0 = 46.5, 7.25, 500.0
def dms(x):
    d = int(x); m = int((x - d) * 60); return (d, m, round(((x - d) * 60 - m) * 60, 4))
for i, v in enumerate(s["views"]):
    R, t = v["camera"]["R"], v["camera"]["t"]
    c = [-sum(R[k][j] * t[k] for k in range(3)) for j in range(3)]
    north, east, up = c[0], -c[1], c[2]
    lat = lat0 + north / 111132.0
    lon = lon0 + east / (111320.0 * math.cos(math.radians(lat0)))
    name = "view_%03d.jpg" % i
    ex = Image.Exif()
    if i < int(os.environ.get("GPS_VIEWS", "99")):
        ex[0x8825] = {1: "N", 2: dms(lat), 3: "E", 4: dms(lon), 5: b"\x00", 6: round(h0 + up, 3)}
    Image.open(os.path.join(src, v["image"])).convert("RGB").save(os.path.join(dst, name), exif=ex.tobytes(), quality=90)
    v["image"] = name
json.dump(s, open(os.path.join(dst, "scene.json"), "w"))
PY
out=$("$MESHNBV" mission "$TMP/exif/scene.json" --suggestions "$TMP/s.json" --out "$TMP/m_exif" 2>&1) || fail "mission from EXIF: $out"
grep -q "EXIF GPS of 12 photos (EPSG:32632)" <<<"$out" || fail "georeference from EXIF: $out"
/usr/bin/python3 - "$TMP/m_exif/mission.json" <<'PY' || fail "EXIF fit"
import json, sys
m = json.load(open(sys.argv[1]))
fit = m["georeference"]["fit"]
assert len(fit["photos"]) == 12 and fit["rms_residual_m"] < 0.5, fit["rms_residual_m"]
PY

# A scene in a local east-north-up frame (COLMAP's model_aligner
# --alignment_type enu): every photo's WGS84 position against the closed-form
# ENU -> ECEF -> geodetic conversion written out here (WGS84 ellipsoid,
# Bowring's iteration), within 1 cm.
out=$("$MESHNBV" mission "$S" --suggestions "$TMP/s.json" --georef enu:46.5,7.25,500 --out "$TMP/m_enu" 2>&1) \
  || fail "mission --georef enu: $out"
grep -q "expressed in EPSG:32632 (largest deviation" <<<"$out" || fail "ENU localized: $out"
/usr/bin/python3 - "$TMP/m_enu/waypoints.csv" <<'PY' || fail "ENU positions"
import csv, math, sys
a, f = 6378137.0, 1 / 298.257223563
e2 = f * (2 - f)
lat0, lon0, h0 = math.radians(46.5), math.radians(7.25), 500.0
def ecef(lat, lon, h):
    n = a / math.sqrt(1 - e2 * math.sin(lat) ** 2)
    return ((n + h) * math.cos(lat) * math.cos(lon), (n + h) * math.cos(lat) * math.sin(lon), (n * (1 - e2) + h) * math.sin(lat))
o = ecef(lat0, lon0, h0)
sl, cl, sp, cp = math.sin(lon0), math.cos(lon0), math.sin(lat0), math.cos(lat0)
rows = list(csv.DictReader(open(sys.argv[1])))
assert rows, "no waypoints"
for r in rows:
    e, n, u = float(r["x"]), float(r["y"]), float(r["z"])
    X = o[0] - sl * e - sp * cl * n + cp * cl * u
    Y = o[1] + cl * e - sp * sl * n + cp * sl * u
    Z = o[2] + cp * n + sp * u
    lon = math.atan2(Y, X)
    p = math.hypot(X, Y)
    lat = math.atan2(Z, p * (1 - e2))
    for _ in range(10):
        nn = a / math.sqrt(1 - e2 * math.sin(lat) ** 2)
        h = p / math.cos(lat) - nn
        lat = math.atan2(Z, p * (1 - e2 * nn / (nn + h)))
    dn = (math.radians(float(r["latitude"])) - lat) * 6371000
    de = (math.radians(float(r["longitude"])) - lon) * 6371000 * math.cos(lat)
    dh = float(r["ellipsoidal_height"]) - h
    assert math.sqrt(dn * dn + de * de + dh * dh) < 0.01, (r["label"], dn, de, dh)
PY

# run: the mission section of the report when the scene is georeferenced
# (EXIF GPS here), and why not when it is not.
out=$("$MESHNBV" run "$TMP/exif/scene.json" --top 3 --out "$TMP/run_exif" --quiet 2>&1) || fail "run with GPS: $out"
grep -q "^mission: 3 photos in 1 flight(s)" <<<"$out" || fail "run's mission summary: $out"
for f in mission.kml mission.kmz litchi.csv mission.geojson waypoints.csv mission.json mission.svg; do
  [ -s "$TMP/run_exif/mission/$f" ] || fail "run: missing mission/$f"
done
grep -q "<h2>Flying the suggested views</h2>" "$TMP/run_exif/report.html" || fail "run: no mission section"
grep -q "EXIF GPS of 12 photos" "$TMP/run_exif/report.html" || fail "run: the report lacks the georeference"
grep -q "<svg" "$TMP/run_exif/report.html" || fail "run: the report lacks the top view"
out=$("$MESHNBV" run "$S" --top 2 --out "$TMP/run_plain" --quiet 2>&1) || fail "run without GPS: $out"
grep -q "No drone mission: no georeference" "$TMP/run_plain/report.html" || fail "run: no reason for the missing mission"
[ -e "$TMP/run_plain/mission" ] && fail "run wrote a mission without a georeference"
# Asked for (--georef) but impossible: the run fails before writing anything.
expect_error "no suggestion can be flown" "$MESHNBV" run "$S" --top 2 --out "$TMP/run_bad" --quiet \
  --georef "$TMP/georef.json" --max-altitude 3 --gimbal-pitch-max -85
[ -e "$TMP/run_bad" ] && fail "run wrote results despite the mission's error"

# Bad input: one line, nothing written.
bad() {
  local fragment=$1 dir=$2; shift 2
  expect_error "$fragment" "$@" --out "$TMP/$dir"
  [ -e "$TMP/$dir" ] && fail "$dir written despite the error"
}
bad "no georeference: the scene's source states no CRS, its photos carry no EXIF GPS, and no --georef" none \
  "$MESHNBV" mission "$S" --suggestions "$TMP/s.json"
(cd "$TMP/exif" && /usr/bin/python3 -c "
from PIL import Image
for i in range(2, 12):
    n = 'view_%03d.jpg' % i; Image.open(n).save(n + '.tmp.jpg'); __import__('os').replace(n + '.tmp.jpg', n)
") || fail "stripping GPS"
bad "at least 3 photos with GPS, found 2" two "$MESHNBV" mission "$TMP/exif/scene.json" --suggestions "$TMP/s.json"
cat > "$TMP/bowtie.geojson" <<'GEO'
{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "bowtie"},
 "geometry": {"type": "Polygon", "coordinates": [[[9.0, 45.15], [9.001, 45.151], [9.001, 45.15], [9.0, 45.151], [9.0, 45.15]]]}}]}
GEO
bad "intersects itself" bowtie "$MESHNBV" mission "$S" --suggestions "$TMP/s.json" --georef "$TMP/georef.json" --keep-out "$TMP/bowtie.geojson"
bad "no suggestion can be flown within the constraints" infeasible "$MESHNBV" mission "$S" --suggestions "$TMP/s.json" \
  --georef "$TMP/georef.json" --max-altitude 3 --gimbal-pitch-max -85
bad "min_altitude must be below max_altitude" alt "$MESHNBV" mission "$S" --suggestions "$TMP/s.json" \
  --georef "$TMP/georef.json" --min-altitude 50 --max-altitude 40
bad "--target-gsd must be" gsd "$MESHNBV" mission "$S" --suggestions "$TMP/s.json" --georef "$TMP/georef.json" --target-gsd -1
echo '{"crs": "EPSG:32632", "transform": [1,0,0,0, 0,2,0,0, 0,0,1,0, 0,0,0,1]}' > "$TMP/skew.json"
bad "similarity" skew "$MESHNBV" mission "$S" --suggestions "$TMP/s.json" --georef "$TMP/skew.json"
bad "--georef enu: takes LAT,LON,H" enu2 "$MESHNBV" mission "$S" --suggestions "$TMP/s.json" --georef enu:46.5,7.25
bad "the ENU origin must be" enu_range "$MESHNBV" mission "$S" --suggestions "$TMP/s.json" --georef enu:95,7.25,0
bad "not a suggestions file" notsug "$MESHNBV" mission "$S" --suggestions "$TMP/georef.json" --georef "$TMP/georef.json"
finish

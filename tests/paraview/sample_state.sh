#!/usr/bin/env bash
# sample_projects/paraview/meshnbv_sample.py in pvpython: it runs, saves a
# state ParaView can open, and its picture shows the mesh in the PRI map's
# green and red and the suggestions' frustums in orange and yellow.
#   sample_state.sh PLUGIN.so WORK
set -euo pipefail
PLUGIN=$1 WORK=$2
REPO=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$WORK" && mkdir -p "$WORK"
MESHNBV_PARAVIEW_PLUGIN=$PLUGIN "$REPO/tests/support/with_xvfb.sh" 1280x1024x24 \
  "$REPO/plugins/paraview/tools/pvpython" "$REPO/sample_projects/paraview/meshnbv_sample.py" \
  --screenshot "$WORK/sample.png" --state "$WORK/sample.pvsm"
grep -q 'type="MeshNBVSceneReader"' "$WORK/sample.pvsm" || { echo "FAIL: no MeshNBV reader in the state"; exit 1; }
grep -q 'type="MeshNBVSuggestNextView"' "$WORK/sample.pvsm" || { echo "FAIL: no Suggest Next View in the state"; exit 1; }
/usr/bin/python3 - "$WORK/sample.png" <<'PY'
import sys
from PIL import Image
im = Image.open(sys.argv[1]).convert("RGB")
counts = {"green": 0, "red": 0, "orange": 0, "yellow": 0}
for r, g, b in im.getdata():
    if b > 80:
        continue
    if g > 200 and r < 80: counts["green"] += 1
    elif r > 200 and g < 60: counts["red"] += 1
    elif r > 200 and 100 < g < 170: counts["orange"] += 1
    elif r > 200 and g > 200: counts["yellow"] += 1
print("pixels:", counts)
assert counts["green"] > 2000 and counts["red"] > 200, counts
assert counts["orange"] > 100 and counts["yellow"] > 100, counts
PY
echo "sample state: OK"

#!/usr/bin/env bash
# Screenshot of ParaView's GUI with the MeshNBV plugin, under Xvfb: the
# bundled sample project after Compute PRI and Suggest Next View (top 3),
# as sample_projects/paraview/meshnbv_sample.py builds it. pvpython saves
# that pipeline as a state; the GUI loads the plugin from PV_PLUGIN_PATH
# (as an installed plugin would be found) and opens the state.
#
#   gui_screenshot.sh PLUGIN.so OUT.png
set -euo pipefail
PLUGIN=$(realpath "$1")
OUT=$2
HERE=$(cd "$(dirname "$0")" && pwd)
REPO=$(cd "$HERE/../../.." && pwd)
WORK=$(mktemp -d "${TMPDIR:-/tmp}/meshnbv_paraview_gui.XXXXXX")
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  rm -rf "$WORK"
}
trap cleanup EXIT

# A ParaView of its own: settings in the work folder.
export HOME=$WORK/home XDG_CONFIG_HOME=$WORK/home/.config
mkdir -p "$XDG_CONFIG_HOME/ParaView"

# One X server of our own for both steps (xvfb-run -a can hand a display
# to two scripts started at once).
source "$REPO/tests/support/xvfb_screen.bash"
start_xvfb_screen "$WORK" 1280x900x24
MESHNBV_PARAVIEW_PLUGIN=$PLUGIN "$HERE/pvpython" \
  "$REPO/sample_projects/paraview/meshnbv_sample.py" --state "$WORK/sample.pvsm" > "$WORK/pvpython.log" 2>&1 ||
  { cat "$WORK/pvpython.log"; exit 1; }
PV_PLUGIN_PATH=$(dirname "$PLUGIN") paraview --state="$WORK/sample.pvsm" \
  > "$WORK/gui.log" 2>&1 &
pids+=($!)
# Wait for the window to show the state (the mesh's green), at most 60 s.
for _ in $(seq 60); do
  sleep 1
  if ! kill -0 "${pids[1]}" 2>/dev/null; then echo "paraview exited:"; cat "$WORK/gui.log"; exit 1; fi
  # The welcome dialog (modal, before any rendering) closes on Escape.
  /usr/bin/python3 "$REPO/plugins/meshlab/tools/xinput.py" key Escape || true
  /usr/bin/python3 "$REPO/plugins/meshlab/tools/xwd_to_png.py" "$WORK/fb/Xvfb_screen0" "$WORK/now.png"
  if /usr/bin/python3 - "$WORK/now.png" <<'PY'
import sys
from PIL import Image
im = Image.open(sys.argv[1]).convert("RGB")
green = sum(1 for r, g, b in im.getdata() if g > 200 and r < 80 and b < 80)
sys.exit(0 if green > 2000 else 1)
PY
  then break; fi
done
sleep 2  # the last panels
/usr/bin/python3 "$REPO/plugins/meshlab/tools/xwd_to_png.py" "$WORK/fb/Xvfb_screen0" "$WORK/screen.png"
# The window only (the screen around it is black).
/usr/bin/python3 - "$WORK/screen.png" "$OUT" <<'PY'
import sys
from PIL import Image
im = Image.open(sys.argv[1]).convert("RGB")
im.crop(im.point(lambda v: 255 if v > 8 else 0).getbbox()).save(sys.argv[2])
PY
if grep -q "ERR|" "$WORK/gui.log"; then
  echo "paraview reported errors:"; grep "ERR|" "$WORK/gui.log" | head -5; exit 1
fi
echo "screenshot: $OUT"

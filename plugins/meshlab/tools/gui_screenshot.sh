#!/usr/bin/env bash
# Screenshot of MeshLab's GUI (the build's private prefix, so the plugin is
# loaded) under Xvfb: the bundled sample project after Compute PRI and
# Suggest Next View (top 3), i.e. the mesh coloured by PRI and the suggested
# rasters nbv_1..3 in the layer panel. A scripted alternative to
# docs/images/meshlab_gui.png, which was taken after running the filters
# from the GUI's own menus (docs/meshlab.md).
#
#   gui_screenshot.sh BUILD_DIR OUT.png
set -euo pipefail
BUILD=$(realpath "$1")
OUT=$2
HERE=$(cd "$(dirname "$0")" && pwd)
REPO=$(cd "$HERE/../../.." && pwd)
PREFIX=$BUILD/plugins/meshlab/prefix
# Work files in the build folder (not the system's temporary folder).
WORK=$BUILD/plugins/meshlab/gui_screenshot
rm -rf "$WORK"
mkdir -p "$WORK"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  rm -rf "$WORK"
}
trap cleanup EXIT

cp -r "$REPO/sample_projects/building" "$WORK/project"
sed -e 's/name="top" value="1"/name="top" value="3"/' \
  "$REPO/sample_projects/meshlab/suggest_next_view.mlx" > "$WORK/suggest.mlx"
xvfb-run -a -s "-screen 0 1280x1024x24" "$PREFIX/bin/meshlabserver" \
  -p "$WORK/project/project.mlp" -s "$REPO/sample_projects/meshlab/compute_pri.mlx" \
  -s "$WORK/suggest.mlx" -w "$WORK/project/out.mlp" \
  -o "$WORK/project/mesh_pri.ply" -m fc fq > "$WORK/server.log" 2>&1 ||
  { cat "$WORK/server.log"; exit 1; }
grep -E '^nbv_' "$WORK/server.log" | sort -u
# -w does not keep face colours (meshlabserver passes its data mask as an IO
# mask): point the project at the mesh saved with -o -m fc fq instead.
sed 's/"[^"]*_out\.ply"/"mesh_pri.ply"/g' "$WORK/project/out.mlp" > "$WORK/project/gui.mlp"

source "$REPO/tests/support/xvfb_screen.bash"
start_xvfb_screen "$WORK" 1280x1024x24
QT_DEBUG_PLUGINS=1 "$PREFIX/bin/meshlab" "$WORK/project/gui.mlp" > "$WORK/gui.log" 2>&1 &
pids+=($!)
sleep 8
grep -o 'loaded library "[^"]*meshnbv[^"]*"' "$WORK/gui.log" || { echo "the plugin did not load:"; cat "$WORK/gui.log"; exit 1; }
# Tilt the view (MeshLab opens looking down -z) to see roof and facades.
python3 "$HERE/xinput.py" drag 217 470 217 330
python3 "$HERE/xinput.py" move 700 780
sleep 1.5
python3 "$HERE/xwd_to_png.py" "$WORK/fb/Xvfb_screen0" "$OUT" --crop 0,0,852,795
echo "screenshot: $OUT"

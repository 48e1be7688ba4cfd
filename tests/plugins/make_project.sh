#!/usr/bin/env bash
# Fixture of the meshlab/ tests: a small synthetic project and variants.
#   make_project.sh MESHNBV MESHLABSERVER XVFB_RUN WORK
# WORK/project/ml.mlp          8 orbit views of `synth building`, 320x240,
#                              saved by meshlabserver (cameras in MeshLab's
#                              6-7 digit text, read alike by both sides)
# WORK/project/no_rasters.mlp  the mesh only
# WORK/project/no_images.mlp   rasters without <Plane>
# WORK/project/given.mlp       view_006 and view_007 without image (candidates)
# WORK/project/transformed.mlp the mesh layer moved by its MLMatrix44 (x + 0.05)
set -euo pipefail
MESHNBV=$1 SERVER=$2 XVFB=$3 WORK=$4
rm -rf "$WORK/project"
mkdir -p "$WORK"
"$MESHNBV" synth building --out "$WORK/project" --views 8 --size 320x240 --layout orbit --quiet
"$XVFB" -a -n $((200 + $$ % 300)) -s "-screen 0 1280x1024x24" \
  "$SERVER" -p "$WORK/project/project.mlp" -w "$WORK/project/ml.mlp" > "$WORK/setup.log" 2>&1 ||
  { cat "$WORK/setup.log"; exit 1; }
P=$WORK/project
grep -q '<MLRaster label="view_007">' "$P/ml.mlp" || { echo "ml.mlp has no raster view_007"; exit 1; }
awk '/<RasterGroup>/ {print " <RasterGroup/>"; skip = 1; next}
     /<\/RasterGroup>/ {skip = 0; next}
     !skip' "$P/ml.mlp" > "$P/no_rasters.mlp"
sed '/<Plane /d' "$P/ml.mlp" > "$P/no_images.mlp"
sed -e '/fileName="images\/view_006.png"/d' -e '/fileName="images\/view_007.png"/d' \
  "$P/ml.mlp" > "$P/given.mlp"
awk '/<MLMatrix44>/ {print; getline; print "1 0 0 0.05 "; next} {print}' "$P/ml.mlp" > "$P/transformed.mlp"
grep -q '^1 0 0 0.05 $' "$P/transformed.mlp" || { echo "transformed.mlp: no MLMatrix44 to edit"; exit 1; }
echo "meshlab test project: $P"

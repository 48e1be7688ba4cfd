#!/usr/bin/env bash
# The worked example of docs/missions.md: suggestions on the bundled
# building, then a mission with a keep-out box, a low altitude limit and a
# small battery, so that suggestions are moved and the route is split.
# Writes bench/results/missions/example.txt (the command's output) and
# example_mission.json, example_mission.svg. usage: bench/missions/example.sh [MESHNBV]
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
MESHNBV=${1:-$ROOT/build/dev/apps/meshnbv}
OUT=$ROOT/bench/results/missions
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
mkdir -p "$OUT"
S=$ROOT/sample_projects/building/project.mlp
"$MESHNBV" suggest "$S" --top 8 --out "$WORK/suggestions.json" --quiet > /dev/null
echo '{"crs": "EPSG:32632", "transform": [1,0,0,500000, 0,1,0,5000000, 0,0,1,100, 0,0,0,1]}' > "$WORK/georef.json"
{
  echo "\$ meshnbv mission project.mlp --suggestions suggestions.json --georef georef.json \\"
  echo "    --keep-out-box 5,-30,0,30,-5,20 --max-altitude 25 --battery-minutes 0.6 --out mission"
  "$MESHNBV" mission "$S" --suggestions "$WORK/suggestions.json" --georef "$WORK/georef.json" \
    --keep-out-box 5,-30,0,30,-5,20 --max-altitude 25 --battery-minutes 0.6 --out "$WORK/mission" |
    sed "s|$WORK/||"
  echo "\$ ls mission"
  ls "$WORK/mission"
} > "$OUT/example.txt"
cp "$WORK/mission/mission.json" "$OUT/example_mission.json"
cp "$WORK/mission/mission.svg" "$OUT/example_mission.svg"
cat "$OUT/example.txt"

#!/usr/bin/env bash
# The screenshot of the report's 3-D view in docs/images/report_3d.png:
# `meshnbv run` on the bundled sample project, the view opened in headless
# chromium (libs/report/web/screenshot.cjs).
# Usage: scripts/report-screenshot.sh [build-folder] [out.png]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build/release}
OUT=${2:-docs/images/report_3d.png}
CHROMIUM=${MESHNBV_CHROMIUM:-/usr/bin/chromium}
[ -x "$CHROMIUM" ] || { echo "report-screenshot: $CHROMIUM not found (scripts/install-deps.sh)" >&2; exit 1; }
cmake --build "$BUILD" --target meshnbv
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
"$BUILD/apps/meshnbv" run sample_projects/building/project.mlp --out "$WORK/report" --quiet >/dev/null
NODE_PATH=$BUILD/libs/report_web/node_modules node libs/report/web/screenshot.cjs "$CHROMIUM" "$WORK/report" "$OUT"
echo "report-screenshot: $OUT"

#!/usr/bin/env bash
# The report's 3-D view on a ~1M-face mesh (issue #21): the synthetic city at
# edge 0.24 m (511k faces) with each triangle split in two along its longest
# edge (1.02M faces, the same surface: bench/report/split_scene.py), 8 photos
# of 320x240 on an orbit; `meshnbv run` writes the report (the view's mesh
# decimated to the default budget), then headless chromium (SwiftShader:
# software WebGL, 2 cores) opens it 3 times: time from navigation start to
# the first frame with the mesh, frame time while turning the model (60
# frames of 6 degrees, median), display mesh size (bench/report/measure.cjs).
# Writes bench/results/report/report_3d.{json,md}.
# Usage: bench/report/run.sh [build-folder]
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build/release}
OUT=bench/results/report
WORK=${MESHNBV_REPORT_WORK:-/tmp/meshnbv_report_bench}
CHROMIUM=${MESHNBV_CHROMIUM:-/usr/bin/chromium}
[ -x "$CHROMIUM" ] || { echo "bench/report: $CHROMIUM not found (scripts/install-deps.sh)" >&2; exit 1; }
cmake --build "$BUILD" --target meshnbv
MESHNBV=$BUILD/apps/meshnbv
rm -rf "$WORK"
mkdir -p "$WORK" "$OUT"
"$MESHNBV" synth city --edge-length 0.24 --views 8 --size 320x240 --layout orbit --out "$WORK/city" --quiet >/dev/null
/usr/bin/python3 bench/report/split_scene.py "$WORK/city/scene.json" "$WORK/split" >/dev/null
start=${EPOCHREALTIME/[.,]/}
"$MESHNBV" run "$WORK/split/scene.json" --out "$WORK/report" --top 3 --quiet >/dev/null
run_ms=$(((${EPOCHREALTIME/[.,]/} - start) / 1000))
NODE_PATH=$BUILD/libs/report_web/node_modules node bench/report/measure.cjs "$CHROMIUM" "$WORK/report" 3 >"$WORK/browser.json"
/usr/bin/python3 - "$WORK" "$OUT" "$run_ms" <<'PY'
import json, os, platform, subprocess, sys
work, out, run_ms = sys.argv[1], sys.argv[2], int(sys.argv[3])
b = json.load(open(os.path.join(work, "browser.json")))
chromium = subprocess.run(["/usr/bin/chromium", "--version"], capture_output=True, text=True).stdout.strip()
viewer = os.path.join(work, "report", "viewer")
result = {
    "what": "report.html's 3-D view on a 1M-face mesh, headless chromium, software WebGL (SwiftShader)",
    "scene": "synth city --edge-length 0.24, each triangle split in two (bench/report/split_scene.py), 8 photos 320x240",
    "faces": b["faces"],
    "display_faces": b["display_faces"],
    "decimated": b["decimated"],
    "meshnbv_run_seconds": run_ms / 1000,
    "report_data_mb": round(os.path.getsize(os.path.join(viewer, "report_data.js")) / 1e6, 1),
    "viewer_script_kb": round(os.path.getsize(os.path.join(viewer, "meshnbv_viewer.js")) / 1e3),
    "time_to_first_frame_ms": round(b["first_frame_ms_median"]),
    "frame_ms_median": round(b["frame_ms_median"], 1),
    "frame_ms_p90": round(b["frame_ms_p90"], 1),
    "loads": b["loads"],
    "canvas_pixels": b["canvas_pixels"],
    "renderer": b["renderer"],
    "browser": chromium,
    "machine": {"cpus": os.cpu_count(), "system": platform.platform()},
    "note": "software rendering (SwiftShader, no GPU on this machine)",
}
json.dump(result, open(os.path.join(out, "report_3d.json"), "w"), indent=1)
with open(os.path.join(out, "report_3d.md"), "w") as f:
    f.write("# The report's 3-D view on a 1M-face mesh\n\n"
            "bench/report/run.sh: %s; %s. Headless %s, WebGL in software (SwiftShader), %d cores, "
            "canvas %dx%d; median of 3 page loads.\n\n" % (result["scene"], "`meshnbv run` %.1f s" % result["meshnbv_run_seconds"],
                                                           chromium, os.cpu_count(), *b["canvas_pixels"]))
    f.write("| faces | display faces | report_data.js | time to first frame | frame while turning (median) | p90 |\n"
            "|---|---|---|---|---|---|\n")
    f.write("| %d | %d | %.1f MB | %d ms | %.1f ms | %.1f ms |\n\n" % (
        result["faces"], result["display_faces"], result["report_data_mb"], result["time_to_first_frame_ms"],
        result["frame_ms_median"], result["frame_ms_p90"]))
    f.write("All figures are for software rendering (SwiftShader; no GPU on this machine).\n")
print(json.dumps({k: result[k] for k in ("faces", "display_faces", "time_to_first_frame_ms", "frame_ms_median")}))
PY

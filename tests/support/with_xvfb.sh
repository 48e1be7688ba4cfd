#!/usr/bin/env bash
# with_xvfb.sh SIZE COMMAND...: runs COMMAND under an Xvfb of its own
# (xvfb_screen.bash: a display Xvfb picks and reports once it accepts
# connections), stopped afterwards. Instead of `xvfb-run -a`, whose
# display :99 can still belong to the server of the run before it.
set -euo pipefail
size=$1
shift
work=$(mktemp -d "${TMPDIR:-/tmp}/meshnbv_xvfb.XXXXXX")
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
source "$(dirname "$0")/xvfb_screen.bash"
start_xvfb_screen "$work" "$size"
"$@"

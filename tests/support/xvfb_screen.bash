# Sourced by the GUI screenshot scripts (plugins/*/tools/gui_screenshot.sh)
# and tests/support/with_xvfb.sh.
#
# start_xvfb_screen WORK SIZE: starts Xvfb on a free display with its screen
# kept as a file (WORK/fb/Xvfb_screen0, which xwd_to_png.py converts),
# exports DISPLAY and appends the server's pid to the caller's `pids`.
# Xvfb picks the display itself and writes its number, as one line, to a
# file (-displayfd) only once it accepts connections: no race with a
# socket left by an earlier server, nor with another test starting one.
# -noreset: an X server resets when its last client disconnects and
# refuses connections meanwhile; pvpython opens and closes a connection
# before its render window's, which then failed one run in two here.
start_xvfb_screen() {
  local work=$1 size=$2
  mkdir -p "$work/fb"
  : >"$work/display"
  Xvfb -displayfd 3 -noreset -screen 0 "$size" -fbdir "$work/fb" 3>"$work/display" >"$work/xvfb.log" 2>&1 &
  local server=$!
  pids+=("$server")
  # A loaded machine can take seconds. `read` succeeds once the whole line
  # (number and newline) is there.
  local i display=
  for i in $(seq 300); do
    read -r display <"$work/display" && [ -n "$display" ] && break
    display=
    kill -0 "$server" 2>/dev/null || { echo "Xvfb exited:"; cat "$work/xvfb.log"; return 1; }
    sleep 0.1
  done
  [ -n "$display" ] || { echo "Xvfb did not start in 30 s:"; cat "$work/xvfb.log"; return 1; }
  export DISPLAY=":$display"
}

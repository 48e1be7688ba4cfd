# Sourced by the GUI screenshot scripts (plugins/*/tools/gui_screenshot.sh).
#
# start_xvfb_screen WORK SIZE: starts Xvfb on a free display with its screen
# kept as a file (WORK/fb/Xvfb_screen0, which xwd_to_png.py converts),
# exports DISPLAY and appends the server's pid to the caller's `pids`.
start_xvfb_screen() {
  local work=$1 size=$2 display=$((300 + $$ % 600))
  while [ -e "/tmp/.X$display-lock" ]; do display=$((display + 1)); done
  mkdir -p "$work/fb"
  Xvfb ":$display" -screen 0 "$size" -fbdir "$work/fb" > "$work/xvfb.log" 2>&1 &
  local server=$!
  pids+=("$server")
  # Ready when its socket exists (a loaded machine can take seconds).
  local i
  for i in $(seq 300); do
    [ -S "/tmp/.X11-unix/X$display" ] && break
    kill -0 "$server" 2>/dev/null || { echo "Xvfb :$display exited:"; cat "$work/xvfb.log"; return 1; }
    sleep 0.1
  done
  [ -S "/tmp/.X11-unix/X$display" ] || { echo "Xvfb :$display did not start in 30 s"; return 1; }
  export DISPLAY=":$display"
}

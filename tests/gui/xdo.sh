# Shared by the GUI end-to-end scripts (sourced): pointer and key helpers relative to the window found by
# find_window. GLFW polls input once a frame, so every action leaves time to be seen (testing-recipes).

# find_window TITLE: sets X, Y, WIDTH, HEIGHT of the first visible window whose title matches.
find_window() {
  local wid
  wid="$(timeout 60 xdotool search --sync --onlyvisible --name "$1" | head -n 1)"
  eval "$(xdotool getwindowgeometry --shell "$wid")"
}
# at X Y: moves the pointer to window coordinates.
at() {
  xdotool mousemove --sync $((X + $1)) $((Y + $2))
  sleep 0.3
}
# key KEYS: presses and releases (e.g. ctrl+s).
key() {
  xdotool keydown "$1"
  sleep 0.3
  xdotool keyup "$1"
  sleep 0.8
}
# click X Y: a left click at window coordinates.
click() {
  at "$1" "$2"
  xdotool click 1
  sleep 0.5
}
# drag X0 Y0 X1 Y1: left button down at the first point, moved in six steps, released at the second.
drag() {
  at "$1" "$2"
  xdotool mousedown 1
  sleep 0.4
  for i in 1 2 3 4 5 6; do
    xdotool mousemove --sync $((X + $1 + ($3 - $1) * i / 6)) $((Y + $2 + ($4 - $2) * i / 6))
    sleep 0.15
  done
  sleep 0.4
  xdotool mouseup 1
  sleep 1.0
}

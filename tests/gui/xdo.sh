# Shared by the GUI end-to-end scripts (sourced): their start and end, and pointer and key helpers relative to
# the window found by find_window. GLFW polls input once a frame, so every action leaves time to be seen
# (testing-recipes).

# e2e_start NAME SCRIPT ARGS...: call first. Outside a display of its own it checks the tools (exit 77: skipped,
# unless SYLVA_REQUIRE_DISPLAY=1) and re-runs SCRIPT with ARGS under `xvfb-run -a` (a new display: no other
# test's window can take the pointer focus, there is no window manager). Inside, it makes the scratch directory
# $work, removed on exit together with the process $pid if that still runs.
e2e_start() {
  local name="$1" script="$2"
  shift 2
  if [ -z "${SYLVA_E2E_INNER:-}" ]; then
    local tool
    for tool in xvfb-run xdotool import convert; do
      if ! command -v "$tool" >/dev/null; then
        echo "$name: $tool not found (apt install xvfb xdotool imagemagick)" >&2
        [ "${SYLVA_REQUIRE_DISPLAY:-0}" = 1 ] && exit 1
        exit 77
      fi
    done
    exec xvfb-run -a -s "-screen 0 1280x720x24" env SYLVA_E2E_INNER=1 bash "$script" "$@"
  fi
  work="$(mktemp -d)"
  pid=""
  trap e2e_cleanup EXIT
}
e2e_cleanup() {
  if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then kill "$pid" 2>/dev/null || true; fi
  rm -rf "$work"
}
# e2e_quit NAME LOG: Ctrl+Q, then fails (printing LOG) unless the process $pid exits with status 0.
e2e_quit() {
  key ctrl+q
  local status=0
  wait "$pid" || status=$?
  pid=""
  if [ "$status" -ne 0 ]; then
    echo "$1: the editor exited with status $status" >&2
    cat "$2" >&2
    exit 1
  fi
}

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

#!/usr/bin/env bash
# End-to-end test of `sylva view --procedural-world` driven by real input, as a user would: on its own Xvfb
# display the viewer opens over the 2^20 x 2^20-sample procedural world (fixed time step, so flights repeat);
# once its log says the view is complete, W is held for 12 frames (the fly camera goes 180 m ahead at 300 m/s and
# 0.05 s a frame) and the ground on screen must change while it streams in; L must switch to the level colours
# (the ground changes again), and a second L back to shading. The viewer must then quit on Esc with status 0
# and log no error. On a failure the screenshots go to <golden-out>/llvmpipe/viewer-stream-e2e.*.png.
#
# Usage: viewer-stream-e2e.sh SYLVA_EXE SOURCE_DIR GOLDEN_OUT_DIR
# Exit 77 (skipped) when xvfb-run, xdotool or ImageMagick is missing, unless SYLVA_REQUIRE_DISPLAY=1.
set -euo pipefail
exe="$(realpath "$1")"
src="$(realpath "$2")"
out="$(realpath -m "$3")/llvmpipe"
name=viewer-stream-e2e

# shellcheck source=tests/gui/xdo.sh
. "$src/tests/gui/xdo.sh"
e2e_start "$name" "$0" "$@"

# The ground in the lower half of the window (window coordinates, 640x360 window, panel hidden).
ground_crop="600x150+20+200"
# view_complete N: waits (at most 60 s) until the log has said N times that the view is complete.
view_complete() {
  local i
  for i in $(seq 600); do
    [ "$(grep -c 'streamed view complete' "$work/log" || true)" -ge "$1" ] && return 0
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.1
  done
}
cd "$work"
"$exe" --log-level info view --procedural-world --width 640 --height 360 --fixed-step 0.05 --no-ui >"$work/log" 2>&1 &
pid=$!
find_window 'Sylva viewer: streamed terrain'
view_complete 1

# shot NAME: a screenshot with the pointer parked at the top (a new spot each time: a synced move to where the
# pointer already is would wait for a motion that never comes).
shots=0
shot() {
  shots=$((shots + 1))
  at $((560 + shots * 10)) 20
  screenshot "$work/$1.png"
}
failed=0
expect_changed() {
  local n
  n="$(differing "$ground_crop" "$1" "$2")"
  echo "$name: $4: $n pixels of the ground differ ($1 → $2)"
  if [ -z "$n" ] || [ "$n" -lt "$3" ]; then
    echo "$name: $4: expected at least $3 differing pixels" >&2
    failed=1
  fi
}

shot start
xdotool keydown w
frames 12
xdotool keyup w
frames 2
view_complete 2
shot flown
expect_changed start flown 5000 "flying ahead"
key l
shot levels
expect_changed flown levels 30000 "level colours"
key l
shot shaded
quit_key Escape
status=0
wait "$pid" || status=$?
pid=""
if [ "$status" -ne 0 ]; then
  echo "$name: the viewer exited with status $status" >&2
  failed=1
fi
if grep -q '\[error\]' "$work/log"; then
  echo "$name: the viewer logged an error:" >&2
  grep '\[error\]' "$work/log" >&2
  failed=1
fi
if [ "$failed" -ne 0 ]; then
  mkdir -p "$out"
  for s in start flown levels shaded; do
    [ -f "$work/$s.png" ] && cp "$work/$s.png" "$out/$name.$s.png"
  done
  cat "$work/log" >&2
  exit 1
fi
echo "$name: passed"

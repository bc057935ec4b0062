#!/usr/bin/env bash
# End-to-end test of `sylva view SCENE.json` driven by real input, as a user would: on its own Xvfb display the
# viewer opens data/scenes/meadow.json (960x540, fixed step). Space pauses the scene time (so frames repeat)
# and key 1 turns the shadows off (llvmpipe draws frames several times faster without them). Then:
#   key 4 turns the grass off:      the lower part of the view (the ground) differs;
#   key 4 turns the grass on again: the ground is as before;
#   G walks (eyes 1.8 m above the ground instead of the camera's 2.5 m): the view moves;
#   B throws a ball from the eye:   the log says so (the meadow has physics) and the ball fills the view;
#   R turns auto quality on:        the governor steps the quality down (the log says which step).
# The viewer must then quit on Esc with status 0 and log no error. Last, a scripted run
# (--frames 1 --no-ui --screenshot) must show exactly the frame `sylva render SCENE.json` writes.
# On a failure the screenshots go to <golden-out>/llvmpipe/viewer-scene-e2e.*.png.
#
# The pass toggles are driven with their keys: keys go through GLFW's event queue, so none is missed however
# slow the frames (a click on the panel's checkbox works by hand but did not register reliably here).
#
# Usage: viewer-scene-e2e.sh SYLVA_EXE SOURCE_DIR GOLDEN_OUT_DIR
# Exit 77 (skipped) when xvfb-run, xdotool or ImageMagick is missing, unless SYLVA_REQUIRE_DISPLAY=1.
set -euo pipefail
exe="$(realpath "$1")"
src="$(realpath "$2")"
out="$(realpath -m "$3")/llvmpipe"
name=viewer-scene-e2e

# shellcheck source=tests/gui/xdo.sh
. "$src/tests/gui/xdo.sh"
e2e_start "$name" "$0" "$@"
if ! command -v compare >/dev/null; then
  echo "$name: ImageMagick's compare not found" >&2
  exit 1
fi

scene="$src/data/scenes/meadow.json"
# Crops (WxH+X+Y, window coordinates), clear of both panels (the Timings window, top right, grows and shrinks
# with the passes that ran): the ground below the scene panel (the lower part of the view), and the middle of
# the view right of it (where a thrown ball shows).
ground_crop="700x150+0+385"
view_crop="270x300+440+120"

# In an empty directory with a cache of its own: bark and leaves are the procedural ones whatever was fetched
# into data/external, and nothing is written outside $work.
cd "$work"
export XDG_CACHE_HOME="$work/cache"
"$exe" --log-level debug view "$scene" --width 960 --height 540 --fixed-step 0.04 >"$work/log" 2>&1 &
pid=$!
find_window 'Sylva viewer'

# A frame of this scene takes from a fraction of a second to several on llvmpipe (other builds share the
# cores), so every step waits for frames shown (tests/gui/xdo.sh), not for a time. The scene is built after the
# window opens, and find_window has waited for the first frame. The pointer rests over the scene from then on
# (away from the panels: no tooltips, and keys go to the window under it).
at 700 300

# shot NAME: a screenshot of the whole screen as $work/NAME.png once two frames have shown the last action.
shot() {
  screenshot "$work/$1.png"
}
failed=0
# expect_changed CROP A B MIN WHAT: fails unless at least MIN pixels of CROP differ between A and B.
expect_changed() {
  local n
  n="$(differing "$1" "$2" "$3")"
  echo "$name: $5: $n pixels of $1 differ ($2 → $3)"
  if [ -z "$n" ] || [ "$n" -lt "$4" ]; then
    echo "$name: $5: expected at least $4 differing pixels" >&2
    failed=1
  fi
}
# expect_same CROP A B MAX WHAT: fails when more than MAX pixels of CROP differ between A and B.
expect_same() {
  local n
  n="$(differing "$1" "$2" "$3")"
  echo "$name: $5: $n pixels of $1 differ ($2 → $3)"
  if [ -z "$n" ] || [ "$n" -gt "$4" ]; then
    echo "$name: $5: expected at most $4 differing pixels" >&2
    failed=1
  fi
}
# 1. Paused (frames repeat), shadows off (frames are several times faster).
key space
key 1
shot start
if ! grep -q "pass shadows off" "$work/log"; then
  echo "$name: key 1 did not turn the shadows off" >&2
  failed=1
fi
# 2. Grass off with key 4, then on again.
key 4
shot nograss
expect_changed "$ground_crop" start nograss 5000 "grass off (key 4)"
key 4
shot grass
expect_same "$ground_crop" start grass 200 "grass on again (key 4)"
if [ "$(grep -c "pass grass o[nf]" "$work/log" || true)" -ne 2 ]; then
  echo "$name: key 4 did not turn the grass off and on" >&2
  failed=1
fi
# 3. Walk: the eyes drop from 2.5 m to 1.8 m above the ground.
key g
shot walk
expect_changed "$view_crop" grass walk 2000 "walk (G)"
# 4. A ball thrown from the eye fills the middle of the view.
key b
shot ball
expect_changed "$view_crop" walk ball 5000 "throw a ball (B)"
if ! grep -q "ball thrown at" "$work/log"; then
  echo "$name: B threw no ball" >&2
  failed=1
fi

# 5. R turns auto quality on (a fixed step starts the viewer at full quality): frames of a second or more on
# llvmpipe miss 10 frames/s, so the governor steps down and says so.
key r
wait_log "$work/log" "quality step [1-9]"
if ! grep -q "auto quality on" "$work/log" || ! grep -q "quality step [1-9]" "$work/log"; then
  echo "$name: R did not turn auto quality on, or it never stepped down" >&2
  failed=1
fi
frames 2

# 6. Esc over the scene quits.
quit_key Escape
status=0
if ! timeout 30 tail --pid="$pid" -f /dev/null; then
  echo "$name: the viewer did not quit on Esc" >&2
  kill "$pid" 2>/dev/null || true
fi
wait "$pid" || status=$?
pid=""
if [ "$status" -ne 0 ]; then
  echo "$name: the viewer exited with status $status" >&2
  failed=1
fi
if grep -q "\[error\]" "$work/log"; then
  echo "$name: the viewer logged errors" >&2
  failed=1
fi

# 7. Scripted: the first frame without the panel is the frame `sylva render` draws, pixel for pixel.
if ! "$exe" view "$scene" --width 320 --height 180 --frames 1 --no-ui --screenshot "$work/scripted.png" \
  >"$work/scripted.log" 2>&1; then
  echo "$name: the scripted run failed:" >&2
  cat "$work/scripted.log" >&2
  failed=1
elif ! "$exe" render "$scene" --width 320 --height 180 -o "$work/render.png" >"$work/render.log" 2>&1; then
  echo "$name: sylva render failed:" >&2
  cat "$work/render.log" >&2
  failed=1
elif ! "$exe" imgdiff "$work/scripted.png" "$work/render.png" --max-diff 0 >"$work/imgdiff.log" 2>&1; then
  echo "$name: the scripted viewer frame differs from sylva render's:" >&2
  cat "$work/imgdiff.log" >&2
  failed=1
fi

if [ "$failed" -ne 0 ]; then
  mkdir -p "$out"
  for s in start nograss grass walk ball scripted render; do
    [ -f "$work/$s.png" ] && cp "$work/$s.png" "$out/$name.$s.png"
  done
  echo "$name: screenshots in $out/$name.*.png; viewer log (but the per-frame lines):" >&2
  grep -v "scene viewer: frame" "$work/log" >&2
fi
exit "$failed"

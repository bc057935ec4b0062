#!/usr/bin/env bash
# End-to-end test of the viewer's Trees panel driven by real input, as a user would: on its own Xvfb display,
# `sylva view --trees` opens on a small forest (no wind, so frames repeat); xdotool scrolls the panel to its
# bottom, turns Foliage off and on again, switches the trees view to the bark tile ids and back, and the bark
# to flat colours. After each click a screenshot of the near tree must change (or come back) as expected:
#   foliage off: the crown differs;      foliage on again: as at the start;
#   view "bark tiles": the tree differs; view "shaded" again: as at the start;
#   bark "flat colours": the trunk differs.
# The viewer must then quit on Esc with status 0 and log no error. On a failure the screenshots go to
# <golden-out>/llvmpipe/viewer-trees-e2e.*.png.
#
# The widgets are clicked at fixed window coordinates: the panel is scrolled to its bottom before each click, so
# they sit at a fixed distance above the Trees section's last rows (its stats, the reload button and the status
# text). If the panel's layout changes, look at the screenshots and update the coordinates below.
#
# Usage: viewer-trees-e2e.sh SYLVA_EXE SOURCE_DIR GOLDEN_OUT_DIR
# Exit 77 (skipped) when xvfb-run, xdotool or ImageMagick is missing, unless SYLVA_REQUIRE_DISPLAY=1.
set -euo pipefail
exe="$(realpath "$1")"
src="$(realpath "$2")"
out="$(realpath -m "$3")/llvmpipe"
name=viewer-trees-e2e

# shellcheck source=tests/gui/xdo.sh
. "$src/tests/gui/xdo.sh"
e2e_start "$name" "$0" "$@"
if ! command -v compare >/dev/null; then
  echo "$name: ImageMagick's compare not found" >&2
  exit 1
fi

# Window coordinates of the widgets once the panel is scrolled to its bottom (1280x720 window).
foliage_box=(27 310)
view_combo=(120 243)
view_shaded=(120 267)
view_tiles=(120 335)
bark_combo=(120 270)
bark_flat=(120 328)
# Crops (WxH+X+Y, window coordinates) of the near tree and of its trunk, right of the panel.
tree_crop="260x350+520+130"
trunk_crop="50x150+615+320"

# In an empty directory with a cache of its own: bark and leaves are the procedural ones whatever was fetched
# into data/external, and nothing is written outside $work.
cd "$work"
export XDG_CACHE_HOME="$work/cache"
"$exe" --log-level info view --trees --trees-count 30 --no-trees-wind --width 1280 --height 720 \
  --fixed-step 0.04 >"$work/log" 2>&1 &
pid=$!
find_window 'Sylva viewer'

# shot NAME: a screenshot of the whole screen as $work/NAME.png, with the pointer parked over the scene (no
# tooltips), once two frames have shown the last action (tests/gui/xdo.sh waits for frames shown, not for a
# time: a frame can take seconds while other tests share the cores).
shot() {
  at 900 650
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

# bottom: scrolls the panel to its bottom (the wheel over the panel scrolls it, not the camera). Before every
# click: rows come and go above the widgets (the pass table has a row per pass of the frame, e.g. "foliage"),
# and ImGui keeps the scroll offset when the content grows.
bottom() {
  at 250 400
  xdotool click --repeat 15 --delay 20 5
  frames 2
}

# pick CX CY IX IY: opens the combo at window coordinates CX CY and clicks its item at IX IY (press, in
# tests/gui/xdo.sh, returns once two frames have shown the open popup).
pick() {
  bottom
  press "$1" "$2"
  press "$3" "$4"
}

# 1. The start.
bottom
shot start
# 2. Foliage off, then on again.
press "${foliage_box[@]}"
shot bare
expect_changed "$tree_crop" start bare 3000 "foliage off"
bottom
press "${foliage_box[@]}"
shot leafy
expect_same "$tree_crop" start leafy 200 "foliage on again"
# 3. The bark tile ids, then the shaded view again.
pick "${view_combo[@]}" "${view_tiles[@]}"
shot tiles
expect_changed "$tree_crop" leafy tiles 3000 "trees view: bark tiles"
pick "${view_combo[@]}" "${view_shaded[@]}"
shot shaded
expect_same "$tree_crop" start shaded 200 "trees view: shaded again"
# 4. Flat bark colours.
pick "${bark_combo[@]}" "${bark_flat[@]}"
shot flat
# The near tree is a silver birch: a slim, pale trunk some 8 pixels wide, about 1,200 pixels in the crop.
expect_changed "$trunk_crop" shaded flat 250 "bark: flat colours"

# 5. Esc over the scene quits.
at 900 600
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
if [ "$failed" -ne 0 ]; then
  mkdir -p "$out"
  for s in start bare leafy tiles shaded flat; do
    [ -f "$work/$s.png" ] && cp "$work/$s.png" "$out/$name.$s.png"
  done
  echo "$name: screenshots in $out/$name.*.png; viewer log:" >&2
  cat "$work/log" >&2
fi
exit "$failed"

#!/usr/bin/env bash
# End-to-end test of `sylva fold edit` driven by real input, as a user would: on its own Xvfb display, xdotool
# opens an image through Ctrl+N and the path prompt, draws a rectangle zone (R + drag), adds two anchors
# (A + drags), synthesises (Ctrl+Enter), saves (Ctrl+S), opens and closes the help with F1, then opens the
# image in an "external editor" (Ctrl+E; a script that rewrites it) and checks that the editor reloads it. The saved project must equal
# tests/gui/fold-editor-e2e.expected.json byte for byte, and a screenshot of the whole screen must match
# tests/golden/refs/llvmpipe/fold-editor-e2e.png. On a mismatch the actuals go to
# <golden-out>/llvmpipe/fold-editor-e2e.actual.{png,json} (promote the PNG with scripts/promote-goldens.sh,
# copy the JSON over the expected file after reviewing it).
#
# Usage: fold-editor-e2e.sh SYLVA_EXE SOURCE_DIR GOLDEN_OUT_DIR
# Exit 77 (skipped) when xvfb-run, xdotool or ImageMagick's import is missing, unless SYLVA_REQUIRE_DISPLAY=1.
set -euo pipefail
exe="$1"
src="$2"
out="$3/llvmpipe"
name=fold-editor-e2e

# shellcheck source=tests/gui/xdo.sh
. "$src/tests/gui/xdo.sh"
e2e_start "$name" "$0" "$@"
cp "$src/data/folding/beach.png" "$work/beach.png"
export XDG_CONFIG_HOME="$work/config"
# The "external image editor": replaces the image with a mirrored copy half a second after it is opened.
convert "$work/beach.png" -flop "$work/mirrored.png"
export SYLVA_IMAGE_EDITOR="sh -c 'sleep 0.5; cp \"$work/mirrored.png\" \"\$1\"' editor {}"

"$exe" --log-level info fold edit --width 1280 --height 720 --fixed-step 0.04 --paused-at 1.0 --autosave 0 >"$work/log" 2>&1 &
pid=$!
find_window 'Sylva fold editor'

# 1. Open an image: Ctrl+N, replace the prompt's text with the path, Enter.
at 640 360
key ctrl+n
key ctrl+a
xdotool type --delay 30 "$work/beach.png"
frames 2
key Return
# 2. A rectangle zone over the surf.
at 520 320
key r
drag 330 300 780 520
# 3. Two anchors: the water moves up the beach.
key a
drag 420 420 430 470
drag 640 410 650 470
# 4. Synthesise and save.
key ctrl+Return
key ctrl+s
# 5. The screenshot, with the pointer parked over the tool panel (no hover effects on the canvas).
at 120 650
screenshot "$work/shot.png"
# 5b. F1, tapped as people tap it (down and up between two frames), opens the help; F1 again closes it.
xdotool key F1
frames 2
screenshot "$work/help.png"
xdotool key F1
frames 2
screenshot "$work/closed.png"
# 6. Edit the image "externally": the editor must notice the new pixels and reload them.
key ctrl+e
wait_log "$work/log" "reloaded .*beach.png"
e2e_quit "$name" "$work/log"

failed=0
if ! grep -q "reloaded .*beach.png" "$work/log"; then
  echo "$name: the image changed on disk but the editor did not reload it" >&2
  cat "$work/log" >&2
  failed=1
fi
project="$work/beach.fold.json"
expected="$src/tests/gui/$name.expected.json"
mkdir -p "$out"
if [ ! -f "$project" ]; then
  echo "$name: the editor saved no project at $project" >&2
  cat "$work/log" >&2
  failed=1
elif ! cmp -s "$project" "$expected"; then
  echo "$name: saved project differs from $expected:" >&2
  diff -u "$expected" "$project" >&2 || true
  cp "$project" "$out/$name.actual.json"
  failed=1
fi
if "$exe" imgdiff "$work/help.png" "$work/shot.png" --max-diff 2 --max-fraction 0.02 >/dev/null 2>&1; then
  echo "$name: F1 did not open the help window" >&2
  cp "$work/help.png" "$out/$name.help.actual.png"
  failed=1
fi
if ! "$exe" imgdiff "$work/closed.png" "$work/shot.png" --max-diff 2 --max-fraction 0.0005 >/dev/null 2>&1; then
  echo "$name: F1 again did not close the help window" >&2
  cp "$work/closed.png" "$out/$name.closed.actual.png"
  failed=1
fi
ref="$src/tests/golden/refs/llvmpipe/$name.png"
if ! "$exe" imgdiff "$work/shot.png" "$ref" --max-diff 2 --max-fraction 0.0005 \
  --diff "$out/$name.diff.png" --report "$out/$name.json"; then
  cp "$work/shot.png" "$out/$name.actual.png"
  echo "$name: screenshot differs from $ref (actual: $out/$name.actual.png, diff: $out/$name.diff.png)" >&2
  failed=1
fi
exit "$failed"

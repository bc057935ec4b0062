#!/usr/bin/env bash
# End-to-end test of every canvas tool of `sylva fold edit`, driven by real input on a display of its own
# (xdotool): polygon zone, translate, scale, curve mapping, lasso deform (then a drag of one of its points
# with select/move), folding zone, still line and the freeze brush; save; then delete the zone, undo, save
# again. Both saves must equal tests/gui/fold-editor-tools-e2e.expected.json byte for byte, the brush must
# have written its mask, and the log must hold no GL error. On a mismatch the actual project goes to
# <golden-out>/llvmpipe/fold-editor-tools-e2e.actual.json.
#
# Usage: fold-editor-tools-e2e.sh SYLVA_EXE SOURCE_DIR GOLDEN_OUT_DIR   (exit 77: skipped, as fold-editor-e2e.sh)
set -euo pipefail
exe="$1"
src="$2"
out="$3/llvmpipe"
name=fold-editor-tools-e2e

# shellcheck source=tests/gui/xdo.sh
. "$src/tests/gui/xdo.sh"
e2e_start "$name" "$0" "$@"
cp "$src/data/folding/beach.png" "$work/beach.png"
export XDG_CONFIG_HOME="$work/config"

"$exe" --log-level info fold edit "$work/beach.png" --project "$work/tools.json" --width 1280 --height 720 \
  --fixed-step 0.04 --paused-at 1.0 --autosave 0 >"$work/log" 2>&1 &
pid=$!
find_window 'Sylva fold editor'

at 520 320
key p
click 350 260
click 600 250
click 700 480
click 380 500
key Return
key t
drag 500 400 510 390
key s
drag 520 380 560 380
key c
for p in "400 300" "450 280" "500 280" "550 300" "400 330" "450 320" "500 320" "550 330"; do
  click $p
done
key l
click 420 420
click 480 410
click 470 460
key Return
key v
drag 480 410 490 440
key f
click 600 300
click 650 300
click 650 350
key Return
key z
click 360 480
click 420 490
key Return
key b
drag 620 420 680 440
key ctrl+s
cp "$work/tools.json" "$work/first.json"
# Delete the zone, bring it back, save again.
at 520 320
key Delete
key ctrl+z
key ctrl+s
e2e_quit "$name" "$work/log"

failed=0
expected="$src/tests/gui/$name.expected.json"
mkdir -p "$out"
for saved in first.json tools.json; do
  if ! cmp -s "$work/$saved" "$expected"; then
    echo "$name: $saved differs from $expected:" >&2
    diff -u "$expected" "$work/$saved" >&2 || true
    echo "$name: the editor's log:" >&2
    tail -n 40 "$work/log" >&2
    cp "$work/$saved" "$out/$name.actual.json"
    failed=1
  fi
done
if [ ! -s "$work/tools.zone.freeze.png" ]; then
  echo "$name: the freeze brush wrote no mask (tools.zone.freeze.png)" >&2
  ls -la "$work" >&2
  failed=1
fi
if grep -q "GL error" "$work/log"; then
  echo "$name: GL errors in the editor's log:" >&2
  grep "GL error" "$work/log" | head -5 >&2
  failed=1
fi
exit "$failed"

#!/usr/bin/env bash
# The developers' loop between commits (also `scripts/test.sh --quick`): rebuilds the release preset
# incrementally, then runs every unit test and the gl + golden tests of the modules named, or, with none named,
# of the modules the working tree changes against HEAD (tracked changes and new files):
#   scripts/quick-test.sh [MODULE ...]      MODULE: core gl platform shader render ui media terrain blades capture
#                                           grass trees texsynth folding physics scene wind cli fuzz, or all
# A change under engine/M, shaders/M, tests/*/M or bench/M selects M; apps/, bench/areas (what `sylva bench`
# runs) and tests/cli, tests/gui select cli, and so does ui (only the program's windows use it)
# (the program's end-to-end tests); a change to a module every other builds on (core gl platform shader render),
# to shaders/common or shaders/shared, to tests/support or to the build files selects all. The README's test
# command (scripts/test.sh) still runs everything, with the sanitizers and the fuzz targets.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="$(nproc 2>/dev/null || echo 2)"
known=(core gl platform shader render ui media terrain blades capture grass trees texsynth folding physics scene wind cli
  fuzz)
foundation=" core gl platform shader render "

selected=()
add() {
  local m="$1"
  [[ " ${selected[*]} " == *" $m "* ]] || selected+=("$m")
}
if [ $# -gt 0 ]; then
  for m in "$@"; do
    if [ "$m" != all ] && [[ " ${known[*]} " != *" $m "* ]]; then
      echo "quick-test: unknown module '$m' (modules: ${known[*]} all)" >&2
      exit 2
    fi
    add "$m"
  done
else
  while IFS= read -r f; do
    case "$f" in
      tests/cli/* | tests/gui/* | apps/* | bench/areas/*) add cli ;;
      engine/*/* | shaders/*/* | bench/*/*)
        m="${f#*/}"
        m="${m%%/*}"
        case "$m" in
          common | shared) add all ;;
          ui) add ui && add cli ;;
          *) add "$m" ;;
        esac
        ;;
      tests/support/* | cmake/* | CMakeLists.txt | CMakePresets.json) add all ;;
      tests/*/*/*)
        m="${f#tests/*/}"
        add "${m%%/*}"
        ;;
    esac
  done < <({ git diff --name-only HEAD; git ls-files --others --exclude-standard; } | sort -u)
fi
for m in "${selected[@]}"; do
  [[ "$foundation" == *" $m "* ]] && selected=(all) && break
done

scripts/build.sh release
if [ ${#selected[@]} -eq 0 ]; then
  echo "quick-test: no module changed; running the unit tests only (name modules to run their gl tests)"
fi
# -L twice: a test must carry both labels.
run=(ctest --test-dir build/release --output-on-failure -j "$jobs" --timeout 600)
display=()
if command -v xvfb-run >/dev/null; then
  display=(xvfb-run -a -s "-screen 0 1280x720x24")
fi
export SYLVA_REQUIRE_GL=1
echo "quick-test: unit tests"
"${run[@]}" -L '^unit$'
if [ ${#selected[@]} -gt 0 ]; then
  if [[ " ${selected[*]} " == *" all "* ]]; then
    modules='.*'
  else
    modules="$(IFS='|'; echo "${selected[*]}")"
  fi
  echo "quick-test: gl and golden tests of: ${selected[*]}"
  "${display[@]}" "${run[@]}" -L '^(gl|golden)$' -L "^module:(${modules})$"
fi

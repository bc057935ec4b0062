#!/usr/bin/env bash
# Promote reviewed golden-test actuals to references.
#   scripts/promote-goldens.sh [--build DIR] [NAME ...]
# A failing golden test writes <build>/golden-out/<device class>/<name>.actual.png (+ .diff.png, .json).
# Look at them first (the diff shows failing pixels in red); then this copies each actual over
# tests/golden/refs/<device class>/<name>.png. With NAMEs, only those are promoted.
set -euo pipefail
cd "$(dirname "$0")/.."
build="build/release"
names=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    -h|--help) sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) names+=("$1"); shift ;;
  esac
done
if [ ! -d "$build/golden-out" ]; then
  echo "promote-goldens: no $build/golden-out (run the golden tests first, or pass --build DIR)" >&2
  exit 2
fi
count=0
for actual in "$build"/golden-out/*/*.actual.png; do
  [ -e "$actual" ] || continue
  class=$(basename "$(dirname "$actual")")
  name=$(basename "$actual" .actual.png)
  if [ ${#names[@]} -gt 0 ] && [[ ! " ${names[*]} " == *" $name "* ]]; then
    continue
  fi
  mkdir -p "tests/golden/refs/$class"
  cp "$actual" "tests/golden/refs/$class/$name.png"
  rm -f "$actual" "$build/golden-out/$class/$name.diff.png" "$build/golden-out/$class/$name.json"
  echo "promoted $class/$name"
  count=$((count + 1))
done
echo "$count reference(s) promoted; review 'git diff --stat tests/golden/refs' before committing"

#!/usr/bin/env bash
# Refreshes tests/ctest-costs/<preset>.txt from a full run's CTestCostData.txt (run it after scripts/test.sh, or
# point it at a fresh clone's build folder). scripts/test.sh copies these files into a build folder that has no
# cost data yet, so that a fresh clone's CTest starts the longest tests first, as it does on a machine that has
# run them before (docs/testing.md, "Where the time goes"). Tests that hold a resource lock run one at a time, so
# together they bound their phase: they get 1,000 s more than they took, so that one of them always runs (the
# longest first) while the other core takes the rest. Durations only, no list of the last failures.
# Usage: scripts/update-test-costs.sh [PRESET [BUILD_DIR]]   (default: release, asan and tsan from build/<preset>)
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -gt 0 ]; then
  runs=("$1:${2:-build/$1}")
else
  runs=(release:build/release asan:build/asan tsan:build/tsan)
fi
for run in "${runs[@]}"; do
  preset="${run%%:*}"
  dir="${run#*:}"
  data="$dir/Testing/Temporary/CTestCostData.txt"
  if [ ! -f "$data" ]; then
    echo "update-test-costs.sh: $data not found (run the $preset tests first)" >&2
    exit 1
  fi
  locked="$(mktemp)"
  ctest --test-dir "$dir" --show-only=json-v1 |
    jq -r '.tests[] | select(any(.properties[]?; .name == "RESOURCE_LOCK")) | .name' >"$locked"
  # Names of parameterised tests hold spaces: the last two fields are the runs and the seconds.
  awk -v locked="$locked" '
    BEGIN { while ((getline name < locked) > 0) lock[name] = 1 }
    /^---/ { exit }
    NF >= 3 { c = $NF; n = $0; sub(/ [0-9]+ [0-9.eE+-]+$/, "", n); printf "%s 1 %.1f\n", n, c + (n in lock ? 1000 : 0) }' \
    "$data" | LC_ALL=C sort >"tests/ctest-costs/$preset.txt"
  rm -f "$locked"
  echo "tests/ctest-costs/$preset.txt: $(wc -l <"tests/ctest-costs/$preset.txt") tests, $(awk '$NF >= 1000' \
    "tests/ctest-costs/$preset.txt" | wc -l) holding a lock"
done

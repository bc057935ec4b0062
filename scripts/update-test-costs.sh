#!/usr/bin/env bash
# Refreshes tests/ctest-costs/<preset>.txt from the durations of a full run (Testing/Temporary/LastTest.log: run
# it after scripts/test.sh, or point it at a fresh clone's build folder; not CTestCostData.txt, whose running
# averages include the seeded values). scripts/test.sh copies these files into a build folder that has no cost
# data yet, so that a fresh clone's CTest starts the longest tests first, as it does on a machine that has run
# them before (docs/testing.md, "Where the time goes"). Tests that hold a resource lock run one at a time, so
# together they bound their phase: they get 1,000 s more than they took, so that one of them always runs (the
# longest first) while the other core takes the rest.
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
  data="$dir/Testing/Temporary/LastTest.log"
  if [ ! -f "$data" ]; then
    echo "update-test-costs.sh: $data not found (run the $preset tests first)" >&2
    exit 1
  fi
  # Copied first: any ctest call in that folder, --show-only too, starts a new LastTest.log.
  log="$(mktemp)"
  locked="$(mktemp)"
  cp "$data" "$log"
  ctest --test-dir "$dir" --show-only=json-v1 |
    jq -r '.tests[] | select(any(.properties[]?; .name == "RESOURCE_LOCK")) | .name' >"$locked"
  # Each test's block names it ("N/M Test: NAME") and ends with its duration ("Test time = S sec").
  awk -v locked="$locked" '
    BEGIN { while ((getline name < locked) > 0) lock[name] = 1; name = "" }
    /^[0-9]+\/[0-9]+ Test: / { name = $0; sub(/^[0-9]+\/[0-9]+ Test: /, "", name) }
    /^Test time = / && name != "" { printf "%s 1 %.1f\n", name, $4 + (name in lock ? 1000 : 0); name = "" }' \
    "$log" | LC_ALL=C sort >"tests/ctest-costs/$preset.txt"
  rm -f "$log" "$locked"
  echo "tests/ctest-costs/$preset.txt: $(wc -l <"tests/ctest-costs/$preset.txt") tests, $(awk '$NF >= 1000' \
    "tests/ctest-costs/$preset.txt" | wc -l) holding a lock"
done

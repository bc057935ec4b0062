#!/usr/bin/env bash
# Regenerates the blade-model library in data/blades/ (docs/capture.md#the-blade-library) with `sylva capture`:
# one file per synthetic shape, captured from a swaying fakenect recording (so refining sees real motion), and
# the leaves of the Middlebury Aloe (scripts/fetch-sample-data.sh), scaled to a real aloe's leaf length because
# its disparity map has no calibrated depth. Deterministic: same binary, same files.
#
# Usage: scripts/make-blade-library.sh [path/to/sylva]   (default build/release/bin/sylva)
set -euo pipefail
cd "$(dirname "$0")/.."
sylva="${1:-build/release/bin/sylva}"
work="$(mktemp -d)"
trap 'rm -rf "${work}"' EXIT

shapes=(slim quadratic slender bamboo sharp)
counts=(5 3 4 3 4)
for i in "${!shapes[@]}"; do
  shape="${shapes[$i]}"
  "${sylva}" capture synth --shape "${shape}" --count "${counts[$i]}" --frames 30 --amplitude 0.3 \
    --seed $((i + 1)) -o "${work}/${shape}" > /dev/null
  "${sylva}" capture "${work}/${shape}" --name "${shape}" -o "data/blades/${shape}.json" \
    --overlay "${work}/${shape}.png" -q
  echo "data/blades/${shape}.json"
done

if [[ -f data/external/aloeGT.png ]]; then
  "${sylva}" capture data/external/aloeGT.png --roi 0,0,1282,760 --centre 770,640 --name aloe --scale-to 0.6 \
    -o data/blades/aloe.json --overlay "${work}/aloe.png" -q
  echo "data/blades/aloe.json"
else
  echo "make-blade-library: data/external/aloeGT.png missing (scripts/fetch-sample-data.sh); aloe.json kept" >&2
fi

#!/usr/bin/env bash
# Draws the terrain pages' plots with gnuplot (Debian: gnuplot-nox, installed by scripts/setup-debian.sh):
#   docs/images/terrain/equal-error.png   vertices per frame of distance and screen-space-error LOD at the same
#                                         measured worst error (docs/data/terrain-equal-error.tsv, docs/terrain-lod.md §10)
#   docs/images/terrain/stream-memory.png RAM tiles and process RSS over a streamed flight (docs/terrain-data.md,
#                                         "Streaming"), from docs/data/terrain-stream.tsv
# With a `sylva bench terrain-stream` report as argument, docs/data/terrain-stream.tsv is first rewritten from it
# (jq, also installed by scripts/setup-debian.sh).
#
# Usage: scripts/plot-terrain.sh [out/bench-terrain-stream.json]
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
data="${repo_root}/docs/data"
out="${repo_root}/docs/images/terrain"
for tool in gnuplot jq; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "plot-terrain: $tool not found; install it (scripts/setup-debian.sh)" >&2
    exit 1
  fi
done
if [ $# -ge 1 ]; then
  [ -f "$1" ] || { echo "plot-terrain: $1: no such report" >&2; exit 1; }
  {
    printf 'km\tRAM tiles MB\tprocess RSS MB\n'
    jq -r '[.sample_km, .ram_mb_samples, .rss_mb_samples] | transpose[] | @tsv' "$1"
  } >"${data}/terrain-stream.tsv"
  jq -r '"# \(.source); budgets: RAM \(.ram_budget_mb) MB, GPU \(.gpu_budget_mb) MB (tile cache \(.gpu_tiles_mb) MB)"' "$1" \
    >"${data}/terrain-stream.note"
fi
for f in terrain-equal-error.tsv terrain-stream.tsv; do
  [ -f "${data}/${f}" ] || { echo "plot-terrain: ${data}/${f} is missing" >&2; exit 1; }
done
ram_budget="$(jq -r '.ram_budget_mb' "${1:-/dev/null}" 2>/dev/null || true)"
[ -n "$ram_budget" ] && [ "$ram_budget" != null ] || ram_budget=512
mkdir -p "${out}"

gnuplot <<GP
set terminal pngcairo size 900,420 font "DejaVu Sans,11" background rgb "white"
set datafile separator "\t"
set style data histograms
set style histogram clustered gap 1.5
set style fill solid 0.9 border -1
set boxwidth 0.9
set grid ytics lc rgb "#dddddd"
set key top left
set logscale y
set yrange [1000:5000000]
set ylabel "vertices a frame (log scale)"
set title "Distance LOD and screen-space-error LOD at the same worst error (<= 1 px), 640x360, 50 poses"
set output "${out}/equal-error.png"
plot "${data}/terrain-equal-error.tsv" using 2:xtic(1) title columnheader(2) lc rgb "#c0504d", \
     "" using 3 title columnheader(3) lc rgb "#4f81bd"

unset logscale y
set style data lines
set key bottom right
set xlabel "distance flown (km)"
set ylabel "MB"
set yrange [0:*]
set title "Streaming the 2^{20} × 2^{20}-sample procedural world at 300 m/s: memory over a 100 km flight"
set output "${out}/stream-memory.png"
plot "${data}/terrain-stream.tsv" using 1:2 title "RAM tiles" lw 2 lc rgb "#4f81bd", \
     "" using 1:3 title "process RSS" lw 2 lc rgb "#c0504d", \
     ${ram_budget} title "RAM budget" dt 2 lc rgb "#4f81bd"
GP
echo "${out}/equal-error.png"
echo "${out}/stream-memory.png"

#!/usr/bin/env bash
# Draws the performance page's plots (docs/performance.md) from its data files with gnuplot (Debian:
# gnuplot-nox, installed by scripts/setup-debian.sh): per pass, the meadow's frame cost before and after issue
# 28 against each pass's budget, and the viewer's frame time after each change against its 10 frames/s.
#
# Usage: scripts/plot-performance.sh      (from anywhere; reads docs/data/*.tsv, writes docs/images/performance/)
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
data="${repo_root}/docs/data"
out="${repo_root}/docs/images/performance"
if ! command -v gnuplot >/dev/null 2>&1; then
  echo "plot-performance: gnuplot not found; install it (Debian: apt-get install gnuplot-nox, or scripts/setup-debian.sh)" >&2
  exit 1
fi
for f in meadow-passes.tsv viewer-frames.tsv; do
  if [ ! -f "${data}/${f}" ]; then
    echo "plot-performance: ${data}/${f} is missing" >&2
    exit 1
  fi
done
mkdir -p "${out}"
tmp="$(mktemp -d)"
trap 'rm -rf "${tmp}"' EXIT

gnuplot <<GP
set terminal pngcairo size 900,440 font "DejaVu Sans,11" background rgb "white"
set datafile separator "\t"
set style data histograms
set style histogram clustered gap 1.5
set style fill solid 0.9 border -1
set boxwidth 0.9
set grid ytics lc rgb "#dddddd"
set key top right
set logscale y
set yrange [5:4000]
set ylabel "wall ms a frame (log scale)"
set title "The meadow at 1280×720 on llvmpipe (2 cores): each pass before and after issue 28"
set output "${tmp}/meadow-passes.png"
plot "${data}/meadow-passes.tsv" using 2:xtic(1) title "before" lc rgb "#c0504d", \
     "" using 3 title "after" lc rgb "#4f81bd", \
     "" using 4 title "budget" lc rgb "#9bbb59"

set datafile separator whitespace
unset logscale y
set yrange [0:1100]
set ylabel "wall ms a frame"
set key top right
set title "The viewer on the meadow at 960×540 on llvmpipe (2 cores), auto quality"
set style histogram rowstacked
set bmargin 5
set boxwidth 0.6
set output "${tmp}/viewer-frames.png"
plot "${data}/viewer-frames.tsv" using 2:xtic(1) title "frame" lc rgb "#4f81bd", \
     100 with lines lw 2 dt 2 lc rgb "#c0504d" title "10 frames/s"
GP
for f in meadow-passes.png viewer-frames.png; do
  mv "${tmp}/${f}" "${out}/${f}"
  echo "plot-performance: ${out}/${f}"
done

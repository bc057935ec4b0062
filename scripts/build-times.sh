#!/usr/bin/env bash
# Prints where a Ninja build spent its time, from the build directory's .ninja_log (the last build of each
# output): the slowest N compile steps and the slowest N link steps, in seconds, plus the totals.
#   scripts/build-times.sh [BUILD_DIR] [N]      (default build/release, 20)
# Run it after a cold build (rm -rf the directory first) for figures comparable with docs/testing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${1:-build/release}"
n="${2:-20}"
log="$dir/.ninja_log"
[ -f "$log" ] || { echo "build-times: no $log (is $dir a Ninja build?)" >&2; exit 2; }
[[ "$n" =~ ^[0-9]+$ ]] || { echo "build-times: N must be a whole number, got '$n'" >&2; exit 2; }
# .ninja_log v5: start_ms end_ms mtime output hash; a later line for the same output replaces an earlier one.
awk -v n="$n" -F'\t' '
  NR > 1 { t[$4] = ($2 - $1) / 1000.0 }
  END {
    for (o in t) {
      kind = (o ~ /\.o$/) ? "compile" : ((o ~ /\.a$/) ? "archive" : "link")
      sum[kind] += t[o]; cnt[kind]++
      printf "%s\t%.1f\t%s\n", kind, t[o], o
    }
    for (k in sum) printf "total\t%.1f\t%s (%d steps)\n", sum[k], k, cnt[k] > "/dev/stderr"
  }' "$log" 2>"$dir/.build-times-totals" | sort -t$'\t' -k2,2 -g -r >"$dir/.build-times"
for kind in compile link; do
  echo "slowest $n $kind steps (s, $dir):"
  grep "^$kind"$'\t' "$dir/.build-times" | head -n "$n" | awk -F'\t' '{ printf "  %7.1f  %s\n", $2, $3 }'
done
echo "totals (CPU-seconds of each kind; the build ran them on $(nproc) cores):"
sort "$dir/.build-times-totals" | awk -F'\t' '{ printf "  %7.1f  %s\n", $2, $3 }'
rm -f "$dir/.build-times" "$dir/.build-times-totals"

#!/usr/bin/env bash
# Runs every `sylva bench` area and the GL golden and property tests on this machine's GPU and stores the
# reports under bench/results/<UTC time>-<renderer>/ (docs/performance.md, "On a GPU"): one JSON per area,
# its log, the context (`sylva info --json`, nvidia-smi when there is one), the tests' JUnit XML and a
# summary.json of what passed. Meant for an NVIDIA machine: a software renderer (llvmpipe) is refused
# unless --allow-software, which exists to check this script where no GPU is.
#
# Usage: scripts/gpu-bench.sh [--build DIR] [--results DIR] [--areas "AREA ..."] [--quick] [--no-tests]
#                             [--allow-software]
#   --build DIR        a release build (default: build/release; DIR/bin/sylva must exist)
#   --results DIR      where the reports go (default: bench/results/<UTC time>-<renderer>)
#   --areas "A B"      the bench areas (default: every area but soak; `scene` runs at 1280x720 and 1920x1080)
#   --quick            3 frames after 1 warm-up frame per area that takes --frames (checks the script)
#   --no-tests         skip the GL golden and property tests
#   --allow-software   run on a software renderer too
# Exit status: 0 when every area and test ran, 1 when one failed (the others still run), 2 for bad usage or
# a refused renderer.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$root/build/release
results=
areas="demo terrain terrain-stream grass grass-sim trees fold capture scene"
quick=0
tests=1
software=0

usage() {
  sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'
}
die() {
  echo "gpu-bench: $*" >&2
  exit 2
}

while [ $# -gt 0 ]; do
  case $1 in
  --build) build=${2:?--build needs a folder}; shift 2 ;;
  --results) results=${2:?--results needs a folder}; shift 2 ;;
  --areas) areas=${2:?--areas needs a list}; shift 2 ;;
  --quick) quick=1; shift ;;
  --no-tests) tests=0; shift ;;
  --allow-software) software=1; shift ;;
  -h | --help) usage; exit 0 ;;
  *) die "unknown option '$1' (see --help)" ;;
  esac
done

build=$(cd "$build" 2>/dev/null && pwd) || die "--build: no such folder"
sylva=$build/bin/sylva
[ -x "$sylva" ] || die "$sylva not found: build it first (scripts/build.sh release) or pass --build DIR"
known=$("$sylva" bench --help | sed -n 's/.*area TEXT:{\([^}]*\)}.*/\1/p' | tr ',' ' ')
for area in $areas; do
  case " $known " in
  *" $area "*) ;;
  *) die "--areas: unknown area '$area' (one of: $known)" ;;
  esac
done

# The context, and whether it is a GPU at all.
info=$("$sylva" info --json) || die "no OpenGL 4.5 context (sylva info failed)"
field() { printf '%s' "$info" | sed -n "s/^  \"$1\": \"\\(.*\\)\",\\{0,1\\}\$/\\1/p" | head -n 1; }
renderer=$(field renderer)
class=$(field device_class)
case $class in
llvmpipe | softpipe | software | swrast)
  [ "$software" = 1 ] || die "the renderer is $renderer ($class), not a GPU: run on an NVIDIA machine, or pass --allow-software to check the script"
  ;;
esac

slug=$(printf '%s' "$renderer" | tr -c 'A-Za-z0-9' '-' | tr -s '-' | sed 's/^-//; s/-$//' | cut -c1-40)
[ -n "$results" ] || results=$root/bench/results/$(date -u +%Y%m%d-%H%M%S)-${slug:-unknown}
mkdir -p "$results"
results=$(cd "$results" && pwd)
printf '%s\n' "$info" >"$results/info.json"
if command -v nvidia-smi >/dev/null 2>&1; then
  nvidia-smi -q >"$results/nvidia-smi.txt" 2>&1 || true
fi

frames=()
[ "$quick" = 1 ] && frames=(--frames 3 --warmup 1)
summary=()
failed=0
# One bench run: its JSON report, its log, and a line of the summary.
run() {
  local name=$1
  shift
  local start end status=0
  start=$(date +%s)
  echo "== $name: sylva bench $*"
  (cd "$root" && "$sylva" bench "$@" -o "$results/$name.json") >"$results/$name.log" 2>&1 || status=$?
  end=$(date +%s)
  tail -n 3 "$results/$name.log"
  [ "$status" = 0 ] || failed=1
  summary+=("{\"name\": \"$name\", \"status\": $status, \"seconds\": $((end - start))}")
}
for area in $areas; do
  case $area in
  scene)
    run scene-1280x720 scene "${frames[@]}" --width 1280 --height 720
    run scene-1920x1080 scene "${frames[@]}" --width 1920 --height 1080
    ;;
  demo | terrain | soak) run "$area" "$area" "${frames[@]}" ;;
  terrain-stream)
    # The issue's flight: 100 km at 300 m/s over the 2^20 x 2^20-sample world, at full HD (--quick: 1 km).
    if [ "$quick" = 1 ]; then
      run terrain-stream terrain-stream --distance 1 --width 1920 --height 1080
    else
      run terrain-stream terrain-stream --width 1920 --height 1080
    fi
    ;;
  *) run "$area" "$area" ;;
  esac
done

# The GL tests: goldens (the pictures) and the GL properties (CPU/GPU agreement, counts, watertightness).
tests_status=null
if [ "$tests" = 1 ]; then
  echo "== GL golden and property tests"
  tests_status=0
  ctest --test-dir "$build" -L 'gl|golden' -j "$(nproc)" --timeout 600 --output-junit "$results/gl-tests.xml" \
    >"$results/gl-tests.log" 2>&1 || tests_status=$?
  tail -n 4 "$results/gl-tests.log"
  [ "$tests_status" = 0 ] || failed=1
fi

{
  printf '{\n  "version": 1,\n  "renderer": "%s",\n  "device_class": "%s",\n' "$renderer" "$class"
  printf '  "commit": "%s",\n' "$(git -C "$root" rev-parse HEAD 2>/dev/null || echo unknown)"
  printf '  "date": "%s",\n  "quick": %s,\n  "runs": [\n' "$(date -u +%Y-%m-%dT%H:%M:%SZ)" \
    "$([ "$quick" = 1 ] && echo true || echo false)"
  for i in "${!summary[@]}"; do
    printf '    %s%s\n' "${summary[$i]}" "$([ "$i" -lt $((${#summary[@]} - 1)) ] && echo ,)"
  done
  printf '  ],\n  "gl_tests_status": %s\n}\n' "$tests_status"
} >"$results/summary.json"
echo "gpu-bench: reports in $results"
exit "$failed"

#!/usr/bin/env bash
# Fuzzes Sylva's loaders and parsers with libFuzzer (+ ASan/UBSan), built by the `asan` preset (clang: the same
# objects serve the sanitizer test run and the fuzz targets):
#   scripts/fuzz.sh [TARGET|all] [SECONDS] [--merge]
# TARGET: png exr npy npz gdal json shader fold flow flow_ffmpeg cli blade_models depth_png fakenect … (default
# all: the list below); SECONDS per target (default 60).
# Each run starts from the committed seeds (fuzz/corpus/TARGET) and regression inputs (fuzz/regressions/TARGET) and
# works in build/fuzz-work/TARGET. A crash, leak, sanitizer report, timeout (>10 s) or allocation over the limit
# writes the input there as crash-*/leak-*/timeout-*/oom-* and makes the script fail; copy it into
# fuzz/regressions/TARGET when fixing the defect. --merge adds inputs that reach new coverage to fuzz/corpus/TARGET.
# Prints one summary line per target: executions, executions/s, coverage (edges) and features. Targets run
# side by side, one per core (SYLVA_FUZZ_JOBS overrides), each for SECONDS. SYLVA_FUZZ_SEED fixes libFuzzer's
# random seed (the CI smoke run, scripts/test.sh, uses 1, so a finding there repeats on every run and on the
# developer's machine); unset, each run explores from a new seed.
set -euo pipefail
cd "$(dirname "$0")/.."
target="${1:-all}"
seconds="${2:-60}"
merge="${3:-}"
all=(png exr npy npz gdal tile_pyramid json shader fold flow flow_ffmpeg cli blade_models depth_png fakenect tree_json piece_import leaf_model texsynth_tileset scene_file farm_manifest)
if [ "$target" = all ]; then targets=("${all[@]}"); else targets=("$target"); fi
for t in "${targets[@]}"; do
  [[ " ${all[*]} " == *" $t "* ]] || { echo "fuzz.sh: unknown target '$t' (targets: ${all[*]})" >&2; exit 2; }
done
[[ "$seconds" =~ ^[0-9]+$ ]] || { echo "fuzz.sh: SECONDS must be a whole number, got '$seconds'" >&2; exit 2; }
[[ "${SYLVA_FUZZ_SEED:-1}" =~ ^[1-9][0-9]*$ ]] ||
  { echo "fuzz.sh: SYLVA_FUZZ_SEED must be a positive whole number, got '$SYLVA_FUZZ_SEED'" >&2; exit 2; }

scripts/build.sh asan sylva_fuzz >/dev/null
# Memory ceiling per input: loaders accept fields up to their documented limits, but a small input must never
# make them allocate near this much (see docs/testing.md).
limit_mb=2048
# An allocation the sanitizer's allocator cannot serve returns NULL, as malloc does in production, instead of
# aborting: GDAL asks for what a corrupt header implies and reports its own failure cleanly (see
# fuzz/regressions/gdal/tiff-strip-needs-28gb-inside-gdal.tif). Our own code never gets that far: every size it
# allocates is checked first, and -malloc_limit_mb reports any allocation over the limit as a finding.
export ASAN_OPTIONS="allocator_may_return_null=1:${ASAN_OPTIONS:-}"
# Leaks inside third-party decoders GDAL drives (HDF4) are theirs, listed in tests/sanitizers/fuzz-lsan.supp.
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/fuzz-lsan.supp:print_suppressions=0:${LSAN_OPTIONS:-}"
status=0
# fuzz_one TARGET: one target's run and its summary line; exit status 1 on a finding.
fuzz_one() {
  local t="$1" work="build/fuzz-work/$1" log rc execs rate cov
  mkdir -p "$work/corpus"
  local seeds=("fuzz/corpus/$t")
  [ -d "fuzz/regressions/$t" ] && seeds+=("fuzz/regressions/$t")
  log="$work/fuzz.log"
  local seed=()
  [ -n "${SYLVA_FUZZ_SEED:-}" ] && seed=(-seed="$SYLVA_FUZZ_SEED")
  set +e
  "build/asan/fuzz/fuzz_$t" "${seed[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb="$limit_mb" \
    -malloc_limit_mb="$limit_mb" -max_len=65536 -print_final_stats=1 -artifact_prefix="$work/" \
    "$work/corpus" "${seeds[@]}" >"$log" 2>&1
  rc=$?
  set -e
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -1 || true)
  if [ $rc -ne 0 ]; then
    {
      echo "fuzz.sh: $t FAILED after ${execs:-?} executions (exit $rc); input and log in $work/"
      grep -m3 -E 'ERROR: (AddressSanitizer|libFuzzer|UndefinedBehaviorSanitizer|LeakSanitizer)|runtime error|uncaught exception|Test unit written' "$log" || tail -5 "$log"
    } >&2
    return 1
  fi
  echo "fuzz.sh: $t ok: $execs executions in ${seconds} s ($rate/s), ${cov:-cov: ?}"
  if [ "$merge" = --merge ]; then
    "build/asan/fuzz/fuzz_$t" -merge=1 -max_len=65536 "fuzz/corpus/$t" "$work/corpus" >>"$log" 2>&1
  fi
}
jobs="${SYLVA_FUZZ_JOBS:-$(nproc 2>/dev/null || echo 2)}"
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || { echo "fuzz.sh: SYLVA_FUZZ_JOBS must be a positive whole number, got '$jobs'" >&2; exit 2; }
running=0
for t in "${targets[@]}"; do
  if [ "$running" -ge "$jobs" ]; then
    wait -n || status=1
    running=$((running - 1))
  fi
  fuzz_one "$t" &
  running=$((running + 1))
done
while [ "$running" -gt 0 ]; do
  wait -n || status=1
  running=$((running - 1))
done
exit $status

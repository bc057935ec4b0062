#!/usr/bin/env bash
# Configures and builds one CMake preset (default: release): scripts/build.sh [PRESET] [TARGET ...]
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
shift || true
jobs="$(nproc 2>/dev/null || echo 2)"
# Build trees made before the presets moved to Ninja (Unix Makefiles) cannot be reconfigured in place: start
# them afresh (only the CMake cache and the objects are lost).
cache="build/$preset/CMakeCache.txt"
if [ -f "$cache" ] && ! grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$' "$cache"; then
  echo "build.sh: build/$preset was made with another generator; configuring it afresh with Ninja" >&2
  rm -rf "build/$preset/CMakeCache.txt" "build/$preset/CMakeFiles"
fi
cmake --preset "$preset" >/dev/null
if [ $# -gt 0 ]; then
  cmake --build --preset "$preset" -j "$jobs" --target "$@"
else
  cmake --build --preset "$preset" -j "$jobs"
fi

#!/usr/bin/env bash
# The API reference (docs/library.md): scripts/api-docs.sh [OUT_DIR]   (default build/api; open OUT_DIR/html/index.html)
# Runs Doxygen over every module's public headers and the module pages in docs/api/. Warnings are errors
# (docs/api/Doxyfile: WARN_AS_ERROR): an undocumented public declaration, a malformed doc comment or a broken
# reference fails, and the first twenty are printed.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$(mkdir -p "${1:-$root/build/api}" && cd "${1:-$root/build/api}" && pwd)"
command -v doxygen >/dev/null || { echo "api-docs.sh: doxygen not found; run scripts/setup-debian.sh" >&2; exit 1; }
cd "$root"
includes="$(ls -d engine/*/include | tr '\n' ' ')"
status=0
{
  cat docs/api/Doxyfile
  echo "INPUT = docs/api $includes"
  echo "STRIP_FROM_INC_PATH = $includes"
  echo "OUTPUT_DIRECTORY = $out"
  echo "WARN_LOGFILE = $out/warnings.log"
} | doxygen - >/dev/null || status=$?
warnings="$(grep -c . "$out/warnings.log" || true)"
if [ "$status" -ne 0 ] || [ "$warnings" -ne 0 ]; then
  head -20 "$out/warnings.log" | sed "s#^$root/##" >&2
  echo "api-docs.sh: Doxygen found $warnings problems in the public headers or docs/api/ (all: $out/warnings.log)" >&2
  exit 1
fi
echo "api-docs.sh: $out/html/index.html (no warnings)"

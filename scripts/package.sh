#!/usr/bin/env bash
# The Debian packages (docs/library.md): scripts/package.sh [BUILD_DIR]
# Builds the release preset (unless BUILD_DIR, an existing build tree, is given), writes
# BUILD_DIR/package/sylva_<version>_amd64.deb and sylva-dev_<version>_amd64.deb through CPack, and checks
# both with lintian (any error fails; warnings are printed). Prints the two paths last.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-}"
if [ -z "$build" ]; then
  "$root/scripts/build.sh" release
  build="$root/build/release"
fi
build="$(cd "$build" && pwd)"
for tool in cpack dpkg-shlibdeps lintian; do
  command -v "$tool" >/dev/null || { echo "package.sh: $tool not found; run scripts/setup-debian.sh" >&2; exit 1; }
done
rm -f "$build"/package/*.deb
(cd "$build" && cpack --config CPackConfig.cmake >"$build/package/cpack.log" 2>&1) || {
  tail -20 "$build/package/cpack.log" >&2
  echo "package.sh: cpack failed (log: $build/package/cpack.log)" >&2
  exit 1
}
debs=("$build"/package/*.deb)
[ ${#debs[@]} -eq 2 ] || { echo "package.sh: expected 2 packages, cpack wrote ${#debs[@]}" >&2; exit 1; }
# lintian warns when run as root (CI's case); that line is not about the packages.
status=0
report="$(lintian --fail-on error --tag-display-limit 0 "${debs[@]}" 2>&1)" || status=$?
grep -v "running with root privileges" <<<"$report" >&2 || true
if [ "$status" -ne 0 ]; then
  echo "package.sh: lintian found errors in ${debs[*]}" >&2
  exit 1
fi
printf '%s\n' "${debs[@]}"

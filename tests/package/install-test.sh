#!/usr/bin/env bash
# PackageInstall (docs/library.md): the Debian packages as a user gets them. Writes both with
# scripts/package.sh (lintian: no errors), unpacks them into an empty root (dpkg -x: the files exactly as
# `apt install ./sylva_*.deb` puts them, without touching this machine's /usr), then from there:
#   - `sylva --version` names this release and a git revision; `sylva info` gets a context;
#   - `sylva render` draws the installed meadow scene from another working directory (data found beside the
#     installed program, never through the working directory or the source tree);
#   - the four examples configure with find_package(Sylva 0.2) against the unpacked prefix alone, build with
#     -Wall -Wextra -Werror and run: a height query (no GL), a terrain with grass into a PNG, a tree as glTF, a
#     folding frame on the CPU.
# Usage: install-test.sh BUILD_DIR SOURCE_DIR. Exit 77 (skipped) without EGL unless SYLVA_REQUIRE_GL=1.
set -euo pipefail
build="$(cd "$1" && pwd)"
source="$(cd "$2" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fail() { echo "PackageInstall: $*" >&2; exit 1; }

mapfile -t debs < <("$source/scripts/package.sh" "$build")
[ ${#debs[@]} -eq 2 ] || fail "scripts/package.sh gave ${#debs[@]} packages"
# What dpkg-shlibdeps cannot see (scripts/test-fresh-install.sh found it on a fresh Debian 12): contexts come
# through glvnd's libEGL, loaded at run time, and need a driver (Mesa's llvmpipe without a GPU).
runtime="$(printf '%s\n' "${debs[@]}" | grep '/sylva_')"
dpkg-deb -f "$runtime" Depends | grep -qw libegl1 || fail "sylva's Depends lacks libegl1"
dpkg-deb -f "$runtime" Recommends | grep -qw libgl1-mesa-dri || fail "sylva's Recommends lacks libgl1-mesa-dri"
root="$work/root"
for deb in "${debs[@]}"; do
  dpkg -x "$deb" "$root"
done
echo "unpacked ${debs[*]##*/} into $root"
sylva="$root/usr/bin/sylva"
version="$(grep -Po '^project\(Sylva VERSION \K[0-9.]+' "$source/CMakeLists.txt")"
"$sylva" --version | grep -Eq "^sylva $version \(git [0-9a-f]{7,}(-dirty)?\)$" ||
  fail "sylva --version printed '$("$sylva" --version)', not 'sylva $version (git <revision>)'"
[ -f "$root/usr/share/man/man1/sylva.1.gz" ] || fail "no manual page in the package"
[ -f "$root/usr/lib/x86_64-linux-gnu/cmake/Sylva/SylvaConfig.cmake" ] || fail "no SylvaConfig.cmake in sylva-dev"

if ! "$sylva" info >"$work/info.txt" 2>&1; then
  if [ "${SYLVA_REQUIRE_GL:-0}" = "1" ]; then
    cat "$work/info.txt" >&2
    fail "the installed sylva info found no OpenGL context"
  fi
  echo "no EGL context: skipping the rendering checks"
  exit 77
fi
mkdir "$work/elsewhere"
(cd "$work/elsewhere" && SYLVA_DATA_DIR= "$sylva" render "$root/usr/share/sylva/data/scenes/meadow.json" \
  -o meadow.png --width 160 --height 90 >"$work/render.txt" 2>&1) || {
  cat "$work/render.txt" >&2
  fail "the installed sylva could not render its meadow scene"
}
[ -s "$work/elsewhere/meadow.png" ] || fail "sylva render wrote no meadow.png"

# The examples see only the unpacked prefix: no build tree, no source tree on CMake's search path.
cmake -S "$source/examples" -B "$work/examples" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$root/usr" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF \
  -DCMAKE_CXX_FLAGS="-Wall -Wextra -Werror" >"$work/configure.txt" 2>&1 || {
  cat "$work/configure.txt" >&2
  fail "the examples did not configure against the package"
}
grep -q "$root/usr/lib/x86_64-linux-gnu/cmake/Sylva" "$work/examples/CMakeCache.txt" ||
  fail "find_package(Sylva) did not take the unpacked package"
cmake --build "$work/examples" >"$work/build.txt" 2>&1 || {
  tail -30 "$work/build.txt" >&2
  fail "the examples did not build against the package"
}
ex="$work/examples"
cd "$work/elsewhere"
dem="$source/data/external/jacksboro_fault_dem.npz"
if [ ! -f "$dem" ]; then
  # Without the fetched sample data: a procedural field the installed sylva writes.
  dem="$work/procedural.npy"
  "$sylva" terrain heightmap --seed 3 --size 129 -o "$dem" >/dev/null
fi
"$ex/height_query/height_query" "$dem" 100 100 | tee "$work/height.txt"
grep -Eq '^ +100\.00 +100\.00 +-?[0-9]' "$work/height.txt" || fail "height_query printed no height at (100, 100)"
"$ex/terrain_grass/terrain_grass" grass.png 320 180
[ -s grass.png ] || fail "terrain_grass wrote no grass.png"
"$ex/tree_gltf/tree_gltf" silver-birch 3 birch.glb
[ "$(head -c 4 birch.glb)" = "glTF" ] || fail "tree_gltf wrote no binary glTF"
"$ex/folding_frame/folding_frame" "$root/usr/share/sylva/data/folding/beach.json" 1.0 beach.png
[ -s beach.png ] || fail "folding_frame wrote no beach.png"
echo "PackageInstall: the packages install, render, and build and run the four examples"

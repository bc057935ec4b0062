#!/usr/bin/env bash
# The library's "done when" on a fresh machine (docs/library.md): scripts/test-fresh-install.sh [BUILD_DIR]
# Needs root and the Debian mirror. Builds the packages (scripts/package.sh), makes an empty Debian 12 root with
# debootstrap (minbase: no compiler, no GL, nothing of Sylva's), and there, as a user would:
#   apt install ./sylva_*.deb ./sylva-dev_*.deb g++ ninja-build   (apt fetches every dependency they declare)
#   sylva --version; sylva info; sylva render the installed meadow scene
#   cmake -S examples -B … && cmake --build …; run the four examples (data from /usr/share/sylva/data)
# About 3 minutes and 370 MB of downloads. Not part of scripts/test.sh (CI has no network to spare for it);
# PackageInstall covers the same files without apt.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build/release}"
[ "$(id -u)" -eq 0 ] || { echo "test-fresh-install.sh: run as root (debootstrap, chroot)" >&2; exit 1; }
command -v debootstrap >/dev/null || { echo "test-fresh-install.sh: apt install debootstrap" >&2; exit 1; }
mapfile -t debs < <("$root/scripts/package.sh" "$build")
fresh="$(mktemp -d /tmp/sylva-fresh.XXXXXX)"
cleanup() {
  umount "$fresh/dev" 2>/dev/null || true
  umount "$fresh/proc" 2>/dev/null || true
  rm -rf "$fresh"
}
trap cleanup EXIT
echo "test-fresh-install.sh: debootstrap bookworm into $fresh"
debootstrap --variant=minbase bookworm "$fresh" http://deb.debian.org/debian >"$fresh.log" 2>&1 ||
  { tail -5 "$fresh.log" >&2; echo "test-fresh-install.sh: debootstrap failed" >&2; exit 1; }
rm -f "$fresh.log"
mount -t proc proc "$fresh/proc"
mount --bind /dev "$fresh/dev"
cp /etc/resolv.conf "$fresh/etc/resolv.conf"
cp "${debs[@]}" "$fresh/tmp/"
cp -r "$root/examples" "$fresh/tmp/examples"
chroot "$fresh" bash -euo pipefail -c '
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq /tmp/sylva_*.deb /tmp/sylva-dev_*.deb g++ ninja-build >/tmp/apt.log 2>&1 ||
    { tail -20 /tmp/apt.log; exit 1; }
  cd /tmp
  sylva --version
  sylva info | head -3
  sylva render /usr/share/sylva/data/scenes/meadow.json -o /tmp/meadow.png --width 320 --height 180 >/dev/null
  test -s /tmp/meadow.png
  cmake -S /tmp/examples -B /tmp/ex -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="-Wall -Wextra -Werror" >/dev/null
  cmake --build /tmp/ex >/dev/null
  sylva terrain heightmap --seed 3 --size 257 -o /tmp/dem.npy >/dev/null
  /tmp/ex/height_query/height_query /tmp/dem.npy 100 200
  /tmp/ex/terrain_grass/terrain_grass /tmp/grass.png 320 180
  /tmp/ex/tree_gltf/tree_gltf silver-birch 3 /tmp/birch.glb | tail -1
  /tmp/ex/folding_frame/folding_frame
  test -s /tmp/grass.png && test -s /tmp/folding_frame.png && test "$(head -c 4 /tmp/birch.glb)" = glTF
'
echo "test-fresh-install.sh: a fresh Debian 12 installs both packages, renders, and builds and runs the examples"

#!/usr/bin/env bash
# Fetches the real third-party sample data the tests use (see docs/terrain-data.md and the data spec) from Debian
# packages, without installing them: `apt-get download` + `dpkg-deb --fsys-tarfile | tar -x` of single files.
# Files land in data/external/ (git-ignored). Idempotent: files already present are kept and not fetched again.
#
# Usage: scripts/fetch-sample-data.sh          (from anywhere; paths are relative to the repository root)
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dest="${repo_root}/data/external"
mkdir -p "${dest}"

# package | path inside the package | file name under data/external/
entries=(
  "r-cran-terra|usr/lib/R/site-library/terra/ex/elev.tif|elev.tif"
  "python-matplotlib-data|usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz|jacksboro_fault_dem.npz"
  "python-matplotlib-data|usr/share/matplotlib/mpl-data/sample_data/topobathy.npz|topobathy.npz"
  "python3-skimage|usr/lib/python3/dist-packages/skimage/data/chelsea.png|chelsea.png"
  "python3-skimage|usr/lib/python3/dist-packages/skimage/data/astronaut.png|astronaut.png"
  "opencv-doc|usr/share/doc/opencv-doc/examples/data/tree.avi|tree.avi"
  "opencv-doc|usr/share/doc/opencv-doc/examples/data/aloeGT.png|aloeGT.png"
  "opencv-doc|usr/share/doc/opencv-doc/examples/data/aloeL.jpg|aloeL.jpg"
  "opencv-doc|usr/share/doc/opencv-doc/examples/data/aloeR.jpg|aloeR.jpg"
)

work="$(mktemp -d)"
chmod 755 "${work}"
trap 'rm -rf "${work}"' EXIT

apt_updated=0
# Reads the whole policy output first: `apt-cache ... | grep -q` would die of SIGPIPE under pipefail.
has_candidate() {
  local policy
  policy="$(apt-cache policy "$1" 2>/dev/null || true)"
  [[ "${policy}" =~ Candidate:\ [^\(] ]]
}

ensure_candidate() {
  local pkg="$1"
  if has_candidate "${pkg}"; then
    return 0
  fi
  if [[ ${apt_updated} -eq 0 ]]; then
    echo "fetch-sample-data: no apt candidate for ${pkg}; running apt-get update" >&2
    if [[ $(id -u) -eq 0 ]]; then apt-get update -qq; else sudo apt-get update -qq; fi
    apt_updated=1
  fi
  if ! has_candidate "${pkg}"; then
    echo "fetch-sample-data: package ${pkg} is not available from the configured apt sources" >&2
    exit 1
  fi
}

for entry in "${entries[@]}"; do
  IFS='|' read -r pkg inner name <<<"${entry}"
  target="${dest}/${name}"
  if [[ -s "${target}" ]]; then
    echo "present  ${target}"
    continue
  fi
  ensure_candidate "${pkg}"
  pkgdir="${work}/${pkg}"
  mkdir -p "${pkgdir}/root"
  # apt-get download (as root) writes through the unprivileged _apt user; let it into this throw-away dir.
  chmod 777 "${pkgdir}"
  (cd "${pkgdir}" && apt-get download -q "${pkg}" >/dev/null)
  deb="$(find "${pkgdir}" -maxdepth 1 -name "${pkg}_*.deb" | head -n 1)"
  if [[ -z "${deb}" ]]; then
    echo "fetch-sample-data: apt-get download ${pkg} produced no .deb" >&2
    exit 1
  fi
  dpkg-deb --fsys-tarfile "${deb}" | tar -x -C "${pkgdir}/root" "./${inner}"
  # Copy under a temporary name, then rename, so an interrupted run never leaves a partial file behind.
  cp "${pkgdir}/root/${inner}" "${target}.part"
  mv "${target}.part" "${target}"
  echo "fetched  ${target}  (from $(basename "${deb}"))"
done

# npm packages: bark and leaf textures of ez-tree (MIT; oak and willow bark from Poly Haven, CC0). `npm pack`
# fetches the tarball from the registry without installing anything; single files are extracted from it.
npm_entries=(
  "@dgreenheck/ez-tree@1.1.0|package/src/lib/assets/bark|ez-tree/bark|birch_color_1k.jpg birch_normal_1k.jpg oak_color_1k.jpg oak_normal_1k.jpg pine_color_1k.jpg pine_normal_1k.jpg willow_color_1k.jpg willow_normal_1k.jpg"
  "@dgreenheck/ez-tree@1.1.0|package/src/lib/assets/leaves|ez-tree/leaves|ash_color.png aspen_color.png oak_color.png pine_color.png"
)
for entry in "${npm_entries[@]}"; do
  IFS='|' read -r spec inner subdir files <<<"${entry}"
  mkdir -p "${dest}/${subdir}"
  missing=0
  for f in ${files}; do
    [[ -s "${dest}/${subdir}/${f}" ]] || missing=1
  done
  if [[ ${missing} -eq 0 ]]; then
    echo "present  ${dest}/${subdir}/ (${spec})"
    continue
  fi
  if ! command -v npm >/dev/null 2>&1; then
    echo "fetch-sample-data: npm is needed for ${spec} (apt-get install npm)" >&2
    exit 1
  fi
  npmdir="${work}/npm-$(echo "${spec}" | tr '/@' '__')"
  mkdir -p "${npmdir}"
  if [[ -z "$(find "${npmdir}" -maxdepth 1 -name '*.tgz' | head -n 1)" ]]; then
    (cd "${npmdir}" && npm pack --silent "${spec}" >/dev/null)
  fi
  tgz="$(find "${npmdir}" -maxdepth 1 -name '*.tgz' | head -n 1)"
  for f in ${files}; do
    tar -xzf "${tgz}" -C "${npmdir}" "${inner}/${f}"
    cp "${npmdir}/${inner}/${f}" "${dest}/${subdir}/${f}.part"
    mv "${dest}/${subdir}/${f}.part" "${dest}/${subdir}/${f}"
  done
  echo "fetched  ${dest}/${subdir}/  (from ${spec})"
done

echo "sample data in ${dest}:"
for entry in "${entries[@]}"; do
  IFS='|' read -r _ _ name <<<"${entry}"
  printf '  %-28s %10s bytes\n' "${name}" "$(stat -c %s "${dest}/${name}")"
done

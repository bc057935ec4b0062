#!/usr/bin/env bash
# Installs the Node tools the tests use into .cache/node/ (git-ignored): gltf-validator, the Khronos glTF 2.0
# validator that checks exported trees (tests/support/validate-gltf.mjs). Idempotent: nothing is fetched when
# the pinned version is already there. Needs node and npm (Debian: apt-get install nodejs npm).
#
# Usage: scripts/fetch-node-tools.sh          (from anywhere; paths are relative to the repository root)
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dest="${repo_root}/.cache/node"
version="2.0.0-dev.3.10"

installed="${dest}/node_modules/gltf-validator/package.json"
if [ -f "${installed}" ] && grep -q "\"version\": *\"${version}\"" "${installed}"; then
  echo "fetch-node-tools: gltf-validator ${version} present in ${dest}"
  exit 0
fi
for tool in node npm; do
  if ! command -v "${tool}" >/dev/null 2>&1; then
    echo "fetch-node-tools: '${tool}' not found; install Node.js and npm (Debian: apt-get install nodejs npm)" >&2
    exit 1
  fi
done
mkdir -p "${dest}"
if [ ! -f "${dest}/package.json" ]; then
  printf '{\n  "name": "sylva-node-tools",\n  "private": true\n}\n' >"${dest}/package.json"
fi
echo "fetch-node-tools: installing gltf-validator ${version} into ${dest}"
npm install --prefix "${dest}" --no-audit --no-fund --silent "gltf-validator@${version}"
echo "fetch-node-tools: gltf-validator ${version} installed"

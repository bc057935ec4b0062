#!/usr/bin/env bash
# Quick start, command 1: installs what is missing, builds, and renders the demo image(s) headless into out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-debian.sh
scripts/build.sh release sylva
mkdir -p out
./build/release/bin/sylva render --out out/demo.png

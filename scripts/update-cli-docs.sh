#!/usr/bin/env bash
# Regenerates the reference section of docs/cli.md from the built binary's --help (the test CliDocs checks it).
# Usage: scripts/update-cli-docs.sh [PRESET]   (default: release; builds sylva and the CLI tests first)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
scripts/build.sh "$preset" sylva sylva_cli_tests
SYLVA_UPDATE_DOCS=1 "build/$preset/tests/cli/sylva_cli_tests" --gtest_filter='CliDocs.*'
echo "docs/cli.md updated"

#!/usr/bin/env bash
# Builds everything and runs the test suite through ctest (CI runs exactly this).
#   scripts/test.sh [BUILD_DIR]     (default build/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
"$root/scripts/setup.sh" "$build"
cmake --build "$build" --parallel "$(nproc)"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)"

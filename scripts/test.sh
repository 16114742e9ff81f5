#!/usr/bin/env bash
# Builds everything and runs the test suite through ctest (CI runs exactly this). With TESSERA_ASAN=1
# it then builds the suite with ASan + UBSan in BUILD_DIR-asan and runs it again. On 2 cores: about
# 8 minutes for the first part, 25 + 6 for the sanitizer build and run.
#   scripts/test.sh [BUILD_DIR]     (default build/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
"$root/scripts/setup.sh" "$build"
cmake --build "$build" --parallel "$(nproc)"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)"
if [ "${TESSERA_ASAN:-0}" = 1 ]; then
  asan=${build%/}-asan
  "$root/scripts/setup.sh" "$asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DTESSERA_SANITIZE=address;undefined"
  cmake --build "$asan" --parallel "$(nproc)"
  LSAN_OPTIONS="suppressions=$root/tests/lsan.supp:print_suppressions=0" \
    ctest --test-dir "$asan" --output-on-failure -j "$(nproc)"
fi

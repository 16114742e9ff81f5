#!/usr/bin/env bash
# Builds everything and runs the test suite through ctest, then builds the suite again with ASan +
# UBSan (at -O1) in BUILD_DIR-asan and runs it there (CI runs exactly this; its times are in docs/guide.md,
# "Two commands"). TESSERA_ASAN=0 skips the sanitizer part (a quick local run); TSan is scripts/tsan.sh.
#   scripts/test.sh [BUILD_DIR]     (default build/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
"$root/scripts/setup.sh" "$build"
cmake --build "$build" --parallel "$(nproc)"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)"
if [ "${TESSERA_ASAN:-1}" != 0 ]; then
  asan=${build%/}-asan
  echo "test.sh: the suite again under ASan + UBSan in $asan (TESSERA_ASAN=0 skips this)" >&2
  "$root/scripts/setup.sh" "$asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DTESSERA_SANITIZE=address;undefined"
  cmake --build "$asan" --parallel "$(nproc)"
  LSAN_OPTIONS="suppressions=$root/tests/lsan.supp:print_suppressions=0:intercept_tls_get_addr=0" \
    ctest --test-dir "$asan" --output-on-failure -j "$(nproc)"
fi

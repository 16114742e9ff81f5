#!/usr/bin/env bash
# Builds the suite with ThreadSanitizer in BUILD_DIR (default build-tsan/) and runs it: ctest sets
# TSAN_OPTIONS (tests/tsan.supp: oneTBB's own header code only; halt_on_error=1). Not part of CI
# (TSan and ASan cannot share a build, and the 90-minute budget holds one sanitizer pass).
#   scripts/tsan.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build-tsan}
"$root/scripts/setup.sh" "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTESSERA_SANITIZE=thread
cmake --build "$build" --parallel "$(nproc)"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)"

#!/usr/bin/env bash
# Runs one libFuzzer harness for a while: scripts/fuzz.sh TARGET MINUTES [JOBS]
#   TARGET: obj, gltf, maps, factors, scene or tags (tests/fuzz/fuzz_TARGET.cpp)
# Builds the `fuzz` preset (clang, ASan + UBSan) in build-fuzz/ if needed, seeds a working corpus in
# build-fuzz/corpus/TARGET from tests/data (and the seeds of tests/fuzz/seeds), runs libFuzzer for
# MINUTES, and prints the executions, the coverage and any crash. A crash input is copied to
# tests/fuzz/regressions/TARGET/ so that ctest replays it from then on (fix it, then commit it).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
target=${1:?usage: scripts/fuzz.sh obj|gltf|maps|factors|scene|tags MINUTES [JOBS]}
minutes=${2:?usage: scripts/fuzz.sh TARGET MINUTES [JOBS]}
jobs=${3:-1}
case "$target" in obj|gltf|maps|factors|scene|tags) ;; *) echo "fuzz.sh: unknown target '$target'" >&2; exit 2;; esac
command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ is missing (scripts/setup.sh installs clang)" >&2; exit 2; }

[ -f build-fuzz/build.ninja ] || cmake --preset fuzz >/dev/null
cmake --build build-fuzz --target "fuzz_$target" >&2

corpus=build-fuzz/corpus/$target
crashes=build-fuzz/crashes/$target
mkdir -p "$corpus" "$crashes" "tests/fuzz/regressions/$target"
if [ -z "$(ls -A "$corpus")" ]; then
  case "$target" in
    obj) cp tests/data/osd-shapes/*.obj tests/data/sdk-cages/*.obj "$corpus"/ ;;
    gltf) cp tests/data/gltf-cages/*.gltf tests/data/gltf-samples/*.gltf "$corpus"/ ;;
    maps) cp tests/fuzz/seeds/maps/* "$corpus"/ ;;
    factors) cp tests/fuzz/seeds/factors/* "$corpus"/ ;;
    scene) cp golden/suites/scenes/*.json "$corpus"/ ;;
    tags) cp tests/data/osd-shapes/*.obj "$corpus"/ ;;
  esac
fi
dict=()
[ -f "tests/fuzz/$target.dict" ] && dict=(-dict="../tests/fuzz/$target.dict")
log=build-fuzz/fuzz-$target.log
echo "fuzz.sh: $target for $minutes min on $jobs job(s); log $log" >&2
set +e
parallel=()
# libFuzzer's -jobs writes each job's log as fuzz-N.log in the working directory: run in build-fuzz/.
[ "$jobs" -gt 1 ] && parallel=(-jobs="$jobs" -workers="$jobs")
# The one leak inside OpenImageIO (tests/lsan.supp says which) is not Tessera's.
# -malloc_limit_mb above the RSS limit: OpenEXR's header reader allocates whatever size an attribute
# claims (a 504-byte file claiming a 4 GiB attribute: regressions/maps/oom-e52e2dd6...), never touches
# it and fails with one line (0.2 s, 146 MB peak in the normal build). The RSS limit still catches
# memory actually used; libFuzzer's default malloc limit (= the RSS limit) would stop on that virtual
# allocation, and its report would vanish into the map loader's stderr capture.
(cd build-fuzz && ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 \
  LSAN_OPTIONS="suppressions=$root/tests/lsan.supp:print_suppressions=0:intercept_tls_get_addr=0" \
  "tests/fuzz/fuzz_$target" "corpus/$target" "${dict[@]}" -max_total_time=$((minutes * 60)) \
  -rss_limit_mb=2560 -malloc_limit_mb=8192 -timeout=20 -max_len=1048576 -artifact_prefix="crashes/$target/" -print_final_stats=1 \
  "${parallel[@]}") >"$log" 2>&1
status=$?
set -e
if [ "$jobs" -gt 1 ]; then cat build-fuzz/fuzz-[0-9]*.log >>"$log" 2>/dev/null || true; rm -f build-fuzz/fuzz-[0-9]*.log; fi
grep -E "^#[0-9]+.*(DONE|cov:)" "$log" | tail -1 >&2 || true
grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$log" >&2 || true
found=0
for f in "$crashes"/*; do
  [ -f "$f" ] || continue
  [ -f "tests/fuzz/regressions/$target/$(basename "$f")" ] && continue  # found by an earlier run
  cp "$f" "tests/fuzz/regressions/$target/"
  found=$((found + 1))
done
if [ "$found" -gt 0 ]; then
  echo "fuzz.sh: $found new crash input(s) copied to tests/fuzz/regressions/$target/ (see $log)" >&2
  exit 1
fi
echo "fuzz.sh: no crash (exit $status)" >&2

#!/usr/bin/env bash
# The main job: set up, build, and run the most complete thing Tessera does today on its bundled
# default. Until the pipeline and the displaced monster frog land, that is the fixed-function
# tessellator: it checks itself against the D3D11 reference's golden captures, draws debug
# pictures of tessellation patterns, and measures throughput.
#
#   scripts/run.sh [OUT_DIR]      (default out/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out}
"$root/scripts/setup.sh" "$root/build"
cmake --build "$root/build" --parallel "$(nproc)" >&2
bin="$root/build/bin/tessera"
mkdir -p "$out"
"$bin" pattern --domain quad --partitioning fractional_odd --outer 3.5,7.25,2,5 --inner 6.5,4.75 --image "$out/quad_fractional_odd.png"
"$bin" pattern --domain tri --partitioning fractional_even --outer 2.5,6.00005,9 --inner 5.5 --image "$out/tri_fractional_even_fold.png"
"$bin" pattern --domain quad --partitioning integer --outer 64,64,64,64 --inner 64,64 --image "$out/quad_integer_64.png"
"$bin" pattern --domain isoline --partitioning fractional_odd --outer 4,5.5 --image "$out/isoline.png"
"$bin" pattern --domain tri --partitioning integer --outer 3,3,3 --inner 3 --json > "$out/tri_333.json"
"$bin" bench tessellator --seconds 3 | tee "$out/bench_tessellator.txt"
echo "run: pictures, JSON and benchmark results in $out" >&2

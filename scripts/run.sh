#!/usr/bin/env bash
# The main job: set up, build, and run the most complete thing Tessera does today on its bundled
# default. Until the displaced monster frog lands (issue 5), that is the (undisplaced) monster frog cage
# as a Gregory ACC surface and as the exact limit, rendered, tessellated with a crack check, and
# measured against the limit; then the benchmark torus through the whole pipeline (image, D3D11
# statistics, stage times, memory), debug pictures of tessellation patterns and the tessellator's speed.
#
#   scripts/run.sh [OUT_DIR]      (default out/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out}
"$root/scripts/setup.sh" "$root/build"
cmake --build "$root/build" --parallel "$(nproc)" >&2
bin="$root/build/bin/tessera"
mkdir -p "$out"
frog="$root/tests/data/sdk-cages/monsterfrog_mapped_00.obj"
"$bin" render "$frog" --scheme gregory --factor 16 -o "$out/frog_gregory.png" --stats "$out/frog_gregory_stats.json"
"$bin" render "$frog" --scheme exact --factor 8 --view wire-on-shaded --resolution 1280x960 -o "$out/frog_exact_wire.png"
"$bin" tessellate "$frog" --scheme gregory --factor 5.5 --partitioning fractional_odd --vary-factors 1.5 --check-watertight -o "$out/frog_gregory.ply"
"$bin" analyze "$frog" > "$out/frog_analyze.txt"
for scheme in acc gregory; do "$bin" accuracy "$frog" --scheme "$scheme"; done | tee "$out/frog_accuracy.txt"
"$bin" bench torus --factor 16 --frames 5 -o "$out/torus_f16.png" --stats "$out/torus_f16_stats.json" | tee "$out/bench_torus.txt"
"$bin" bench torus --factor 5.5 --partitioning fractional_odd --resolution 960x540 --frames 3 -o "$out/torus_f5.5_odd.png" | tee -a "$out/bench_torus.txt"
"$bin" pattern --domain quad --partitioning fractional_odd --outer 3.5,7.25,2,5 --inner 6.5,4.75 --image "$out/quad_fractional_odd.png"
"$bin" pattern --domain tri --partitioning fractional_even --outer 2.5,6.00005,9 --inner 5.5 --image "$out/tri_fractional_even_fold.png"
"$bin" pattern --domain quad --partitioning integer --outer 64,64,64,64 --inner 64,64 --image "$out/quad_integer_64.png"
"$bin" pattern --domain isoline --partitioning fractional_odd --outer 4,5.5 --image "$out/isoline.png"
"$bin" pattern --domain tri --partitioning integer --outer 3,3,3 --inner 3 --json > "$out/tri_333.json"
"$bin" bench tessellator --seconds 3 | tee "$out/bench_tessellator.txt"
echo "run: frog renders, PLY, accuracy; torus render and statistics; pattern pictures; benchmarks in $out" >&2

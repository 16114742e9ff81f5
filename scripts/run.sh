#!/usr/bin/env bash
# The main job: set up, build, and run the most complete thing Tessera does today on its bundled
# default: the monster frog cage as a Gregory ACC surface displaced by the height in its DDS and shaded
# with the DDS's normal map (1920x1080, factor 16), its crack check with displacement (acc, gregory,
# exact; fractional factors varying per edge), the undisplaced surface rendered, tessellated and
# measured against the limit; then the benchmark torus through the whole pipeline (image, D3D11
# statistics, stage times, memory), debug pictures of tessellation patterns and the tessellator's speed;
# view-dependent LOD with culling, its statistics, factor view, crack check and dolly.
#
#   scripts/run.sh [OUT_DIR]      (default out/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out}
# Only what the main job runs: the tessera command and its modules (the test suite, the Python
# package and the add-on's Blender belong to scripts/test.sh).
"$root/scripts/setup.sh" --main "$root/build"
cmake --build "$root/build" --parallel "$(nproc)" --target tessera >&2
bin="$root/build/bin/tessera"
mkdir -p "$out"
frog="$root/tests/data/sdk-cages/monsterfrog_mapped_00.obj"
# SubD11 reads the height as 2a - 1; 1.2 a - 0.6 is that times 0.6 object units (the frog is 37 wide).
disp=(--displacement "$root/tests/data/sdk-cages/monsterfrog.dds" --displacement-channel A --displacement-scale 1.2 --displacement-bias -0.6)
camera=(--camera-position 48,15,66 --camera-target -3,-2.5,2)
"$bin" render "$frog" --scheme gregory --factor 16 "${disp[@]}" "${camera[@]}" -o "$out/frog_displaced.png" --stats "$out/frog_displaced_stats.json"
"$bin" render "$frog" --scheme gregory --factor 3 "${disp[@]}" "${camera[@]}" --view wire-on-shaded -o "$out/frog_displaced_wire.png"
# View-dependent LOD (8 pixels per segment, fractional_odd) from a camera inside the frog, with culling,
# per-patch statistics, the factor view, and the crack check under the same factors.
near=(--camera-position 20,5,12 --camera-target -3,-2.5,2)
lod=(--lod screen --edge-pixels 8 --partitioning fractional_odd)
"$bin" render "$frog" --scheme gregory "${lod[@]}" "${disp[@]}" "${near[@]}" -o "$out/frog_lod_near.png" --stats "$out/frog_lod_near_stats.json"
"$bin" render "$frog" --scheme gregory "${lod[@]}" "${disp[@]}" "${camera[@]}" --view factors -o "$out/frog_lod_factors.png"
"$bin" tessellate "$frog" --scheme gregory "${lod[@]}" "${disp[@]}" "${near[@]}" --check-watertight | tee "$out/frog_lod_watertight.txt"
"$bin" bench dolly "${disp[@]}" "${camera[@]}" --frames 30 | tee "$out/bench_dolly.txt"
for scheme in acc gregory exact; do
  "$bin" tessellate "$frog" --scheme "$scheme" --factor 5.5 --partitioning fractional_odd --vary-factors 1.5 "${disp[@]}" --check-watertight
done | tee "$out/frog_displaced_watertight.txt"
"$bin" render "$frog" --scheme gregory --factor 16 -o "$out/frog_gregory.png" --stats "$out/frog_gregory_stats.json"
"$bin" render "$frog" --scheme exact --factor 8 --view wire-on-shaded --resolution 1280x960 -o "$out/frog_exact_wire.png"
"$bin" tessellate "$frog" --scheme gregory --factor 5.5 --partitioning fractional_odd --vary-factors 1.5 --check-watertight -o "$out/frog_gregory.ply"
"$bin" analyze "$frog" > "$out/frog_analyze.txt"
# The talk's memory table on the frog (its own map) and on a synthetic cage of the talk's size, each level
# also rendered to measure its real peak memory.
"$bin" analyze "$frog" --memory --measure --displacement "$root/tests/data/sdk-cages/monsterfrog.dds" \
    --displacement-channel A --json > "$out/frog_memory.json"
"$bin" make-cage torus --grid 128x64 -o "$out/torus_128x64.obj"
"$bin" analyze "$out/torus_128x64.obj" --memory --measure | tee "$out/torus_128x64_memory.txt"
for scheme in acc gregory; do "$bin" accuracy "$frog" --scheme "$scheme"; done | tee "$out/frog_accuracy.txt"
"$bin" bench torus --factor 16 --frames 5 -o "$out/torus_f16.png" --stats "$out/torus_f16_stats.json" | tee "$out/bench_torus.txt"
"$bin" bench torus --factor 5.5 --partitioning fractional_odd --resolution 960x540 --frames 3 -o "$out/torus_f5.5_odd.png" | tee -a "$out/bench_torus.txt"
"$bin" pattern --domain quad --partitioning fractional_odd --outer 3.5,7.25,2,5 --inner 6.5,4.75 --image "$out/quad_fractional_odd.png"
"$bin" pattern --domain tri --partitioning fractional_even --outer 2.5,6.00005,9 --inner 5.5 --image "$out/tri_fractional_even_fold.png"
"$bin" pattern --domain quad --partitioning integer --outer 64,64,64,64 --inner 64,64 --image "$out/quad_integer_64.png"
"$bin" pattern --domain isoline --partitioning fractional_odd --outer 4,5.5 --image "$out/isoline.png"
"$bin" pattern --domain tri --partitioning integer --outer 3,3,3 --inner 3 --json > "$out/tri_333.json"
"$bin" bench tessellator --seconds 3 | tee "$out/bench_tessellator.txt"
echo "run: displaced frog render and crack checks; memory tables; frog renders, PLY, accuracy; torus render and statistics; pattern pictures; benchmarks in $out" >&2

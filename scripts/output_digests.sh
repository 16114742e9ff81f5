#!/usr/bin/env bash
# Renders and tessellates a fixed set of assets and prints one SHA-256 per output file: the proof that
# a change meant to keep behaviour (a refactor, a speed-up) keeps every output the same bytes. Run it
# with the build before and after the change and diff the two lists:
#   scripts/output_digests.sh BUILD_DIR > before.txt ... scripts/output_digests.sh BUILD_DIR > after.txt
# The set covers every scheme, the displaced frog (uniform and screen LOD), MSAA, the debug views,
# culling, per-edge factors, glTF skins and morphs, creases, holes, polar fans, n-gons and high valence.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
tessera="$build/tools/cli/tessera"
[ -x "$tessera" ] || tessera="$build/bin/tessera"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
osd="$root/tests/data/osd-shapes"
sdk="$root/tests/data/sdk-cages"
frog="$sdk/monsterfrog_mapped_00.obj"
n=0
run() {  # run NAME ARGS...: one render or tessellation whose output is $out/NAME.*
  local name=$1
  shift
  "$@" >"$out/$name.stdout" 2>/dev/null || echo "$name: exit $?" >&2
  n=$((n + 1))
}
render() { local name=$1; shift; run "$name" "$tessera" render -q --threads 3 --resolution 320x240 -o "$out/$name.png" "$@"; }
tess() { local name=$1; shift; run "$name" "$tessera" tessellate -q --threads 3 -o "$out/$name.ply" "$@"; }

for scheme in flat bspline acc gregory exact pn adaptive; do
  render "frog-$scheme" "$frog" --scheme "$scheme" --factor 6
done
render frog-displaced "$frog" --displacement "$sdk/monsterfrog.dds" --displacement-channel A --factor 12
render frog-displaced-screen "$frog" --displacement "$sdk/monsterfrog.dds" --displacement-channel A --lod screen --cull all
render frog-msaa "$frog" --msaa 4 --factor 5
render frog-vary "$frog" --vary-factors 3 --factor 4
for view in wire-on-shaded factors patch-type cracks cage density; do
  render "frog-view-$view" "$frog" --view "$view" --factor 5
done
for shape in catmark_car catmark_cube_creases1 catmark_cube_corner4 catmark_pole64 catmark_pole8 catmark_hole_test2 \
             catmark_pyramid_creases2 catmark_chaikin1 catmark_nonquads catmark_xord_boundary catmark_helmet \
             catmark_val2_interior catmark_flap; do
  for scheme in gregory bspline exact adaptive; do
    render "$shape-$scheme" "$osd/$shape.obj" --scheme "$scheme" --factor 5
  done
done
for shape in catmark_cube_creases1 catmark_torus_creases0 catmark_quadstrips; do
  render "$shape-acc" "$osd/$shape.obj" --scheme acc --factor 5
done
render dodecahedron-gregory "$root/tests/data/ngon-cages/dodecahedron.obj" --factor 5
render dodecahedron-flat "$root/tests/data/ngon-cages/dodecahedron.obj" --scheme flat --factor 5
render frog-skinned "$root/tests/data/gltf-cages/frog-skinned.gltf" --time 0.5 --factor 5
render frog-morph "$root/tests/data/gltf-cages/frog-morph.gltf" --time 0.5 --factor 5
tess frog-tess "$frog" --factor 7
tess car-tess "$osd/catmark_car.obj" --scheme adaptive --factor 3
tess pole-tess "$osd/catmark_pole64.obj" --factor 4 --vary-factors 2
cd "$out"
sha256sum -- *.png *.ply | sort -k2
echo "$n outputs" >&2

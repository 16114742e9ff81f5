#!/usr/bin/env bash
# Writes the README's example image of each `tessera render --view` into docs/images/ (1280x720) and
# the UV-seams before/after mosaic, a screenshot of `tessera view` and the library examples' images,
# from the bundled monster frog (displaced, but for the culled view). Run after building (scripts/test.sh or scripts/run.sh).
#
#   scripts/readme_images.sh [BUILD_DIR]     (default build/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build}/bin/tessera
out="$root/docs/images"
mkdir -p "$out"
frog="$root/tests/data/sdk-cages/monsterfrog_mapped_00.obj"
disp=(--displacement "$root/tests/data/sdk-cages/monsterfrog.dds" --displacement-channel A
      --displacement-scale 1.2 --displacement-bias -0.6)
mid=(--camera-position 48,15,66 --camera-target -3,-2.5,2 --resolution 1280x720)
lod=(--lod screen --edge-pixels 8 --partitioning fractional_odd)
r() { "$bin" -q render "$frog" --scheme gregory "$@" >/dev/null; }
r "${disp[@]}" "${mid[@]}" "${lod[@]}" --view shaded -o "$out/view-shaded.png"
r "${mid[@]}" --factor 4 --view wireframe -o "$out/view-wireframe.png"
r "${disp[@]}" "${mid[@]}" --factor 6 --partitioning fractional_odd --view wire-on-shaded -o "$out/view-wire-on-shaded.png"
for v in factors density patch-type combination patch-id normals uv displacement cage cracks; do
  r "${disp[@]}" "${mid[@]}" "${lod[@]}" --view "$v" -o "$out/view-$v.png"
done
# Undisplaced acc: the back-patch test proves patches of Bezier nets only, so both colours show.
"$bin" -q render "$frog" --scheme acc --factor 12 --camera-position 20,5,12 --camera-target -3,-2.5,2 \
  --resolution 1280x720 --view culled -o "$out/view-culled.png" >/dev/null
# UV seams, before (raw) and after (blend), with the normal map and derived normals: a 2x2 mosaic.
seams=(--factor 16 --resolution 600x400 --camera-position 14,28,40 --camera-target 0,10,6 --fov 28
       --displacement "$root/tests/data/sdk-cages/monsterfrog.dds" --displacement-channel A)
tmp=$(mktemp -d)
for n in auto derived; do
  for s in raw blend; do r "${seams[@]}" --normal-map "$n" --uv-seams "$s" -o "$tmp/$n-$s.png"; done
done
oiiotool "$tmp/auto-raw.png" "$tmp/auto-blend.png" "$tmp/derived-raw.png" "$tmp/derived-blend.png" \
  --mosaic:pad=4 2x2 --resize 904x604 -o "$out/uv-seams.png"
rm -r "$tmp"
# tessera bake's round trip: the displaced frog tessellated densely, baked back (vector displacement,
# normal map, occlusion) and re-rendered; top: the original (derived normals) and the re-render with the
# baked maps; bottom: the baked vector map (0.5 + 0.8 d), normal map and occlusion.
tmp=$(mktemp -d)
"$bin" -q tessellate "$frog" --factor 24 --displacement "$root/tests/data/sdk-cages/monsterfrog.dds" \
  --displacement-channel A -o "$tmp/dense.ply" >/dev/null
"$bin" -q bake "$frog" --dense "$tmp/dense.ply" --resolution 1024 -o "$tmp/d.exr" --normal-map "$tmp/n.png" \
  --ao "$tmp/ao.png" --ao-rays 64
close=(--factor 16 --resolution 600x400 --camera-position 14,28,40 --camera-target 0,10,6 --fov 28)
r "${close[@]}" --displacement "$root/tests/data/sdk-cages/monsterfrog.dds" --displacement-channel A \
  --normal-map derived -o "$tmp/original.png"
r "${close[@]}" --displacement "$tmp/d.exr" --displacement-channel RGB --normal-map "$tmp/n.png" -o "$tmp/baked.png"
oiiotool "$tmp/d.exr" --addc 0.5 --mulc 0.8 --clamp:min=0:max=1 --resize 400x400 -d uint8 -o "$tmp/d8.png"
oiiotool "$tmp/n.png" --resize 400x400 -d uint8 -o "$tmp/n8.png"
oiiotool "$tmp/ao.png" --ch Y,Y,Y --resize 400x400 -d uint8 -o "$tmp/ao8.png"
oiiotool "$tmp/original.png" "$tmp/baked.png" --mosaic:pad=4 2x1 --resize 1204x400 -o "$tmp/top.png"
oiiotool "$tmp/d8.png" "$tmp/n8.png" "$tmp/ao8.png" --mosaic:pad=2 3x1 --resize 1204x400 --ch R,G,B,A=1.0 -o "$tmp/bottom.png"
oiiotool "$tmp/top.png" "$tmp/bottom.png" --mosaic:pad=4 1x2 -d uint8 -o "$out/bake.png"
rm -r "$tmp"
# docs/assets.md: an open cage's border in the cracks view, a legend beside a z-up asset, an open sheet.
shapes="$root/tests/data/osd-shapes"
"$bin" -q render "$shapes/catmark_hole_test1.obj" --view cracks --resolution 640x480 -o "$out/assets-hole-cracks.png" >/dev/null
"$bin" -q render "$shapes/catmark_pawn.obj" --view factors --resolution 640x480 -o "$out/assets-pawn-factors.png" >/dev/null
"$bin" -q render "$shapes/catmark_gregory_test6.obj" --resolution 640x480 -o "$out/assets-open-sheet.png" >/dev/null
# tessera view's page after the browser test's orbit, view change and pick (needs chromium).
/usr/bin/python3 "$root/tests/viewer_browser_test.py" "$bin" "$root" --screenshot "$out/viewer.png" >/dev/null
# docs/debugging.md: the adaptive patch types, and the cage view's crease colours.
shapes="$root/tests/data/osd-shapes"
"$bin" -q render "$shapes/catmark_single_crease.obj" --scheme adaptive --isolation 4 --view patch-type \
  --resolution 800x600 --camera-position 0.8,-2.2,1.6 --camera-target -0.3,-0.25,0 \
  -o "$out/view-patch-type-adaptive.png" >/dev/null
"$bin" -q render "$shapes/catmark_cubes_semisharp.obj" --scheme exact --view cage --resolution 800x450 \
  -o "$out/view-cage-creases.png" >/dev/null
# docs/reference-renders.md: gregory and exact on four creased shapes (a row each), the glTF frog posed
# and morphed, and --msaa 1 against 8.
tmp=$(mktemp -d)
rows=()
for shape in catmark_cube_creases1 catmark_cube_corner4 catmark_cube_creases0 catmark_chaikin0; do
  for scheme in gregory exact; do
    "$bin" -q render "$shapes/$shape.obj" --scheme "$scheme" --factor 16 --resolution 320x240 -o "$tmp/$shape-$scheme.png" >/dev/null
  done
  rows+=("$tmp/$shape-gregory.png" "$tmp/$shape-exact.png")
done
oiiotool "${rows[@]}" --mosaic:pad=0 2x4 -o "$out/creases-fitted.png"
gltf="$root/tests/data/gltf-cages"
dds=(--displacement "$root/tests/data/sdk-cages/monsterfrog.dds" --displacement-channel A --displacement-scale 1.2
     --displacement-bias -0.6)
"$bin" -q render "$gltf/frog-skinned.gltf" --time 0 "${dds[@]}" --resolution 640x400 -o "$tmp/g0.png" >/dev/null
"$bin" -q render "$gltf/frog-skinned.gltf" --time 1 "${dds[@]}" --resolution 640x400 -o "$tmp/g1.png" >/dev/null
"$bin" -q render "$gltf/frog-morph.gltf" --time 1 "${dds[@]}" --resolution 640x400 -o "$tmp/g2.png" >/dev/null
oiiotool "$tmp/g0.png" "$tmp/g1.png" "$tmp/g2.png" --mosaic:pad=0 3x1 -o "$out/gltf-animation.png"
near=(--camera-position 26,6,30 --camera-target -6,-4,0 --factor 8 --resolution 480x360)
"$bin" -q render "$frog" "${dds[@]}" "${near[@]}" --msaa 1 -o "$tmp/m1.png" >/dev/null
"$bin" -q render "$frog" "${dds[@]}" "${near[@]}" --msaa 8 -o "$tmp/m8.png" >/dev/null
oiiotool "$tmp/m1.png" "$tmp/m8.png" --mosaic:pad=8 2x1 -o "$out/msaa.png"
rm -r "$tmp"
# docs/library.md: the examples' own images, built against an installed tree as a user builds them.
build=$(cd "${1:-$root/build}" && pwd)
tmp=$(mktemp -d)
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
cmake -S "$root/examples" -B "$tmp/examples" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$tmp/prefix" >/dev/null
cmake --build "$tmp/examples" >/dev/null
for e in distance_factors parametric_torus statistics_and_weld; do
  (cd "$tmp" && "$tmp/examples/$e" >/dev/null)
  cp "$tmp/$e.png" "$out/example-${e//_/-}.png"
done
rm -r "$tmp"
# docs/blender.md: Blender's own window, under Xvfb (not a Tessera dependency: apt-get install xvfb).
if command -v Xvfb >/dev/null; then
  "$root/scripts/blender-addon-screenshot.sh" "$build"
else
  echo "readme_images: docs/images/blender-addon*.png kept (no Xvfb for Blender's window)" >&2
fi
echo "readme_images: $(ls "$out" | wc -l) images in $out" >&2

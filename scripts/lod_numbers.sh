#!/usr/bin/env bash
# The numbers of the LOD work, measured on this machine: the displaced frog at 1920x1080 from three
# cameras (triangles, median frame time, patches culled) under screen LOD and uniform factors 16 and
# 32; the dolly's largest vertex move; and the crack check of every scheme x partitioning under
# screen LOD at the three cameras. Slow (minutes): a script, not a test.
#
#   scripts/lod_numbers.sh [BUILD_DIR]     (default build/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build}/bin/tessera
frog="$root/tests/data/sdk-cages/monsterfrog_mapped_00.obj"
disp=(--displacement "$root/tests/data/sdk-cages/monsterfrog.dds" --displacement-channel A
      --displacement-scale 1.2 --displacement-bias -0.6)
target=-3,-2.5,2
declare -A cameras=([near]=20,5,12 [mid]=48,15,66 [far]=120,40,170)
json() { /usr/bin/python3 -c "import json,sys; j=json.load(sys.stdin); print(*[j[k] for k in sys.argv[1:]])" "$@"; }
echo "camera lod triangles median_s patches_culled"
for cam in near mid far; do
  pos=${cameras[$cam]}
  for lod in "--lod screen --partitioning fractional_odd" "--factor 16" "--factor 32"; do
    # shellcheck disable=SC2086
    r=$("$bin" bench frog --cage "$frog" "${disp[@]}" $lod --camera-position "$pos" --camera-target $target \
        --frames 5 --json | json triangles median_s patches_culled)
    echo "$cam '$lod' $r"
  done
done
for p in fractional_odd integer; do
  for frames in 30 60 120; do
    echo "dolly $p $frames frames: $("$bin" bench dolly --cage "$frog" "${disp[@]}" --partitioning $p \
      --camera-position 48,15,66 --camera-target $target --frames $frames --json |
      json largest_move_pixels median_move_pixels)"
  done
done
runs=0 closed=0
for cam in near mid far; do
  for scheme in bspline acc gregory exact pn flat; do
    for p in integer pow2 fractional_odd fractional_even; do
      extra=()
      case $scheme in acc|gregory|exact|bspline) sets=(plain displaced);; *) sets=(plain);; esac
      for set in "${sets[@]}"; do
        [ "$set" = displaced ] && extra=("${disp[@]}") || extra=()
        runs=$((runs + 1))
        if out=$("$bin" tessellate "$frog" --scheme $scheme --partitioning $p --lod screen "${extra[@]}" \
                 --camera-position "${cameras[$cam]}" --camera-target $target --check-watertight --json); then
          closed=$((closed + 1))
        else
          echo "NOT closed: $cam $scheme $p $set: $out"
        fi
      done
    done
  done
done
echo "welds under screen LOD: $closed of $runs closed 2-manifolds"

#!/usr/bin/env bash
# Installs the build tree with `cmake --install` into a temporary prefix, builds
# tests/install_consumer against it with find_package(Tessera), runs it, and checks its answer:
# 6 Gregory patches of a cube at factor 4 make 6 * 2 * 4 * 4 = 192 triangles, welded watertight;
# its PNG comes from the installed image module. Then the library guide's examples (examples/, as
# docs/library.md builds them) against the same tree: each runs with no arguments and writes its PNG.
#   install_consumer.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
for f in bin/tessera lib/tessera/tessera-image-io.so include/tessera/tessellator/tessellator.h lib/cmake/Tessera/TesseraConfig.cmake share/tessera/monsterfrog_mapped_00.obj; do
  [ -e "$work/prefix/$f" ] || { echo "install_consumer: $f was not installed" >&2; exit 1; }
done
if [ -e "$work/prefix/include/tessera/tessellator/domains.h" ]; then
  echo "install_consumer: a private header (tessellator/domains.h) was installed" >&2; exit 1
fi
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S "$src/tests/install_consumer" -B "$work/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
answer=$("$work/build/consumer" "$work/consumer.png")
echo "consumer: $answer"
[ "$answer" = "6 192 watertight" ] || { echo "install_consumer: expected '6 192 watertight'" >&2; exit 1; }
[ -s "$work/consumer.png" ] || { echo "install_consumer: the consumer wrote no image" >&2; exit 1; }
# The installed binary finds its shipped data beside itself, not in the source tree.
"$work/prefix/bin/tessera" bench frog --factor 2 --frames 1 --resolution 64x64 >/dev/null
# The examples of docs/library.md, built as a user builds them, run in an empty folder.
cmake -S "$src/examples" -B "$work/examples" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/examples" >/dev/null
mkdir -p "$work/run"
for example in distance_factors parametric_torus statistics_and_weld; do
  out=$(cd "$work/run" && "$work/examples/$example") || { echo "install_consumer: $example failed: $out" >&2; exit 1; }
  echo "$example: $out"
  [ -s "$work/run/$example.png" ] || { echo "install_consumer: $example wrote no $example.png" >&2; exit 1; }
done
grep -q "watertight" <<<"$(cd "$work/run" && "$work/examples/statistics_and_weld")" ||
  { echo "install_consumer: statistics_and_weld's surface is not watertight" >&2; exit 1; }

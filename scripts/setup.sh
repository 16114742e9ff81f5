#!/usr/bin/env bash
# Installs every Debian (bookworm) package Tessera needs, if missing, and configures the build.
# Idempotent: installs nothing when everything is there. Run as root (or with sudo available).
#
#   scripts/setup.sh [BUILD_DIR] [extra cmake args...]     (default BUILD_DIR: build)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
shift || true

packages=(
  build-essential cmake ninja-build pkg-config git python3 bc
  libglm-dev libopenimageio-dev openimageio-tools libtinygltf-dev catch2 libosd-dev libtbb-dev
  libcli11-dev libfmt-dev libspdlog-dev nlohmann-json3-dev
  # The Python package and Dask batches (python/), and idiff for tessera diff's agreement test.
  pybind11-dev python3-dev python3-numpy python3-distributed
  # Mesa llvmpipe and libepoxy: the oracle and benchmark peer in ../shared/bench.
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libepoxy-dev
  # tessera view: its HTTP server, and the headless browser its test drives.
  libcpp-httplib-dev chromium chromium-driver python3-selenium
  # tessera bake's ray casting, and tessera optimize's vertex and face ordering.
  libembree-dev libmeshoptimizer-dev
  # clang and its libFuzzer runtime: the `fuzz` preset (scripts/fuzz.sh).
  clang
  # The Blender add-on (python/blender/) and its headless test.
  blender
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "$@" >&2
else
  cmake -S "$root" -B "$build" "$@" >/dev/null
fi

#!/usr/bin/env bash
# Installs the Debian (bookworm) packages Tessera needs, if missing, and configures the build.
# Idempotent: installs nothing when everything is there. Run as root (or with sudo available).
#
#   scripts/setup.sh [--main] [BUILD_DIR] [extra cmake args...]     (default BUILD_DIR: build)
#
# --main (scripts/run.sh): only what the `tessera` command needs, and a new build directory is
# configured without the test suite and the Python package. Without it (scripts/test.sh): everything,
# the tests' browser, Blender, clang and Dask included, and the suite and the package switched on.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
main=0
if [ "${1:-}" = "--main" ]; then main=1; shift; fi
build=${1:-$root/build}
shift || true

packages=(
  build-essential cmake ninja-build pkg-config git python3 bc
  libglm-dev libopenimageio-dev openimageio-tools libtinygltf-dev libosd-dev libtbb-dev
  libcli11-dev libfmt-dev libspdlog-dev nlohmann-json3-dev
  # tessera view's HTTP server; tessera bake's ray casting; tessera optimize's vertex and face ordering.
  libcpp-httplib-dev libembree-dev libmeshoptimizer-dev
)
if [ "$main" = 0 ]; then
  packages+=(
    catch2
    # The Python package and Dask batches (python/), and idiff for tessera diff's agreement test.
    pybind11-dev python3-dev python3-numpy python3-distributed
    # Mesa llvmpipe and libepoxy: the oracle and benchmark peer in ../shared/bench.
    libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libepoxy-dev
    # The headless browser the viewer's and the report's tests drive.
    chromium chromium-driver python3-selenium
    # clang and its libFuzzer runtime: the `fuzz` preset (scripts/fuzz.sh).
    clang
    # The Blender add-on (python/blender/) and its headless test.
    blender
  )
fi
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
# The main job's build leaves the suite and the package out; the full setup switches them (back) on.
parts=(-DTESSERA_BUILD_TESTS=ON -DTESSERA_BUILD_PYTHON=ON)
[ "$main" = 1 ] && parts=(-DTESSERA_BUILD_TESTS=OFF -DTESSERA_BUILD_PYTHON=OFF)
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "${parts[@]}" "$@" >&2
elif [ "$main" = 1 ]; then
  cmake -S "$root" -B "$build" "$@" >/dev/null  # an existing build keeps its parts
else
  cmake -S "$root" -B "$build" "${parts[@]}" "$@" >/dev/null
fi

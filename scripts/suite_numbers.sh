#!/usr/bin/env bash
# The numbers of the CI-comparison workflow: a 50-scene suite (the displaced frog from 50 cameras on an
# orbit, screen LOD, 320x180) made with --print-scene and blessed with check --update, then timed with
# `tessera check` (2 threads) and `python3 -m tessera.batch` on a LocalCluster of 1 and 2 workers (one
# render thread each), and the start-up cost of a scene (the CLI's process start and cage load).
#
#   scripts/suite_numbers.sh [BUILD_DIR]     (default build/; writes into a temporary directory)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
bin=$build/bin/tessera
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
frog="$root/tests/data/sdk-cages/monsterfrog_mapped_00.obj"
disp=(--displacement "$root/tests/data/sdk-cages/monsterfrog.dds" --displacement-channel A
      --displacement-scale 1.2 --displacement-bias -0.6)
mkdir -p "$work/scenes"
cases=""
for i in $(seq 0 49); do
  a=$(echo "$i * 0.1256637" | bc -l)
  x=$(echo "s($a) * 60" | bc -l); z=$(echo "c($a) * 60" | bc -l)
  "$bin" -q render "$frog" "${disp[@]}" --lod screen --partitioning fractional_odd --resolution 320x180 \
    --camera-position "$x,15,$z" --camera-target -3,-2.5,2 --print-scene "$work/scenes/s$i.json"
  cases+="${cases:+,}{\"name\": \"s$i\", \"scene\": \"scenes/s$i.json\", \"compare\": \"exact\", \"checks\": [\"triangles\", \"ds_hash\"]}"
done
echo "{\"tessera_suite\": 1, \"name\": \"orbit50\", \"golden\": \"golden\", \"cases\": [$cases]}" > "$work/suite.json"
"$bin" -q check "$work/suite.json" --update -o "$work/bless" >/dev/null 2>&1
t() { local s e; s=$(date +%s.%N); "$@" >/dev/null; e=$(date +%s.%N); echo "$e - $s" | bc -l; }
echo "tessera check (2 cores):          $(t "$bin" -q check "$work/suite.json" -o "$work/r1") s"
export PYTHONPATH=$build/python
echo "tessera.batch --local 1:          $(t /usr/bin/python3 -m tessera.batch "$work/suite.json" --local 1 -q -o "$work/r2" 2>/dev/null) s"
echo "tessera.batch --local 2:          $(t /usr/bin/python3 -m tessera.batch "$work/suite.json" --local 2 -q -o "$work/r3" 2>/dev/null) s"
echo "one scene through the CLI:        $(t "$bin" -q render --scene "$work/scenes/s0.json" -o "$work/one.png") s"
echo "the CLI's start (--version):      $(t "$bin" --version) s"
for r in r1 r2 r3; do
  /usr/bin/python3 -c "import json,sys; s=json.load(open('$work/$r/summary.json')); print('$r', s['counts'], 'case seconds', round(s['seconds'], 2))"
done

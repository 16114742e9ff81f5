#!/usr/bin/env bash
# Differential check of Tessera's tessellator against the D3D11 reference running inside Mesa's
# llvmpipe. A benchmark-style check, not a test: it needs Mesa and ../shared/bench/tessref.cpp.
#
#   tools/oracle/run_oracle.sh [COUNT] [SEED]      (default 4000 cases, seed 2026)
#
# Env: TESSERA_BIN (default build/bin/tessera), TESSREF_SRC (default ../shared/bench/tessref.cpp),
#      WORK (scratch directory, default a fresh temporary one).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
count=${1:-4000}
seed=${2:-2026}
bin=${TESSERA_BIN:-$root/build/bin/tessera}
src=${TESSREF_SRC:-$root/../shared/bench/tessref.cpp}
work=${WORK:-$(mktemp -d)}
[ -x "$bin" ] || { echo "run_oracle: $bin not built (run scripts/test.sh or cmake --build build)" >&2; exit 2; }
[ -f "$src" ] || { echo "run_oracle: oracle source $src not found (set TESSREF_SRC)" >&2; exit 2; }
if ! pkg-config --exists epoxy 2>/dev/null; then
  echo "run_oracle: needs Mesa and libepoxy: apt-get install -y libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libepoxy-dev" >&2
  exit 2
fi
g++ -O2 -o "$work/tessref" "$src" -lepoxy
python3 "$here/gen_cases.py" "$count" "$seed" > "$work/cases.txt"
start=$(date +%s.%N)
"$work/tessref" < "$work/cases.txt" > "$work/reference.dump" 2> "$work/tessref.log"
echo "run_oracle: llvmpipe produced $(grep -c '^case ' "$work/reference.dump") cases in $(echo "$(date +%s.%N) - $start" | bc) s (dump in $work)" >&2
"$bin" oracle-compare "$work/reference.dump" "${@:3}"

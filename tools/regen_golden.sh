#!/usr/bin/env bash
# The one tool that writes golden/. Regenerates the tessellator's reference data from Mesa's
# llvmpipe (the D3D11 reference tessellator runs inside it):
#   golden/tessellator/oracle_digests.txt  digests of 600 random and edge cases (seed 7)
#   golden/tessellator/oracle_small.dump   full captures of tools/oracle/small_cases.txt
# Needs what tools/oracle/run_oracle.sh needs. Review the diff before committing.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
bin=${TESSERA_BIN:-$root/build/bin/tessera}
src=${TESSREF_SRC:-$root/../shared/bench/tessref.cpp}
g++ -O2 -o "$work/tessref" "$src" -lepoxy
python3 "$root/tools/oracle/gen_cases.py" 600 7 > "$work/cases.txt"
"$work/tessref" < "$work/cases.txt" > "$work/digest.dump" 2>/dev/null
"$bin" oracle-compare "$work/digest.dump" --write-golden "$root/golden/tessellator/oracle_digests.txt"
grep -v '^#' "$root/tools/oracle/small_cases.txt" | "$work/tessref" > "$work/small.dump" 2>/dev/null
"$bin" oracle-compare "$work/small.dump"
{
  echo "# Full captures of the D3D11 reference tessellator (Mesa llvmpipe, tools/oracle/small_cases.txt)."
  echo "# Written only by tools/regen_golden.sh. Format: shared/bench/tessref.cpp's output."
  cat "$work/small.dump"
} > "$root/golden/tessellator/oracle_small.dump.tmp"
mv "$root/golden/tessellator/oracle_small.dump.tmp" "$root/golden/tessellator/oracle_small.dump"
rm -rf "$work"

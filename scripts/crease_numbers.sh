#!/usr/bin/env bash
# The crease numbers of the per-face schemes, measured on this machine:
#  1. accuracy (max and rms distance, fraction of the bounding-box diagonal; mean and max normal
#     error, degrees) of every scheme against the exact limit on every creased OpenSubdiv shape in
#     tests/data/osd-shapes (creases or corner tags), the bishop included;
#  2. the adaptive scheme's isolation levels 1..6: the worst accuracy over those shapes, the patch
#     count and frame time on a creased asset (the bishop) and on the frog, against gregory.
# Slow (minutes): a script, not a test. Markdown tables on stdout.
#
#   scripts/crease_numbers.sh [BUILD_DIR]     (default build/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build}/bin/tessera
exec /usr/bin/python3 - "$bin" "$root" <<'PY'
import glob, json, os, subprocess, sys
bin, root = sys.argv[1], sys.argv[2]
shapes = sorted(p for p in glob.glob(os.path.join(root, "tests/data/osd-shapes/catmark_*.obj"))
                if any(l.startswith(("t crease", "t corner")) for l in open(p)))

def run(args):
    r = subprocess.run([bin, "-q"] + args, capture_output=True, text=True)
    if r.returncode != 0:
        return None
    return json.loads(r.stdout)

def accuracy(shape, scheme):
    return run(["accuracy", shape, "--json", "--scheme"] + scheme.split())

schemes = ["adaptive --isolation 6", "adaptive", "gregory", "acc", "bspline", "pn", "flat"]
print("| shape | " + " | ".join(schemes) + " |")
print("|---|" + "---|" * len(schemes))
worst = {}
for shape in shapes:
    cells = []
    for s in schemes:
        a = accuracy(shape, s)
        if a is None:
            cells.append("refused")
            continue
        cells.append("%.1e / %.1f°" % (a["max_relative"], a["mean_normal_degrees"]))
    print("| %s | %s |" % (os.path.basename(shape)[:-4], " | ".join(cells)))
print("\ncells: max distance (of the diagonal) / mean normal error; `adaptive` is --isolation 4 (the default)\n")

bishop = os.path.join(root, "tests/data/osd-shapes/catmark_bishop.obj")
frog = os.path.join(root, "tests/data/sdk-cages/monsterfrog_mapped_00.obj")
def bench(cage, scheme):
    b = run(["bench", "frog", "--cage", cage, "--frames", "5", "--factor", "16", "--json", "--scheme"] + scheme.split())
    return b
print("| isolation | worst max distance (creased shapes) | bishop patches | bishop ms | frog patches | frog ms |")
print("|---|---|---|---|---|---|")
for level in range(1, 7):
    s = "adaptive --isolation %d" % level
    w = max(accuracy(p, s)["max_relative"] for p in shapes)
    b, f = bench(bishop, s), bench(frog, s)
    print("| %d | %.1e | %d | %.1f | %d | %.1f |" % (level, w, b["adaptive"]["patches"], 1000 * b["median_s"],
                                                   f["adaptive"]["patches"], 1000 * f["median_s"]))
for s in ["gregory", "exact"]:
    b, f = bench(bishop, s), bench(frog, s)
    print("| %s | | %s | %s | %d | %.1f |" % (s, "refused" if b is None else "-", "refused" if b is None else "%.1f" % (1000 * b["median_s"]),
                                             f["triangles"], 1000 * f["median_s"]))
print("\nframes: 1920x1080, factor 16, median of 5, %s thread(s); gregory/exact rows give the frog's triangles in the patches column" %
      (run(["bench", "frog", "--frames", "1", "--json"]) or {}).get("threads", "?"))
PY

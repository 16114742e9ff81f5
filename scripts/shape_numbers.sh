#!/usr/bin/env bash
# Every OpenSubdiv Catmull-Clark shape in tests/data/osd-shapes through every smooth scheme: per shape
# and scheme, the largest distance to the exact limit (fraction of the bounding-box diagonal), the
# folded samples (defined limit normal, more than 90 degrees off), the mean normal error, the patch
# count and one frame's time (bench frog, 640x360, factor 8, one thread, median of 3). Shapes run in
# parallel, one process per core; the times are per process, so compare them within one run only.
# Slow (minutes): a script, not a test. Markdown on stdout; with --json FILE, every number as JSON.
#
#   scripts/shape_numbers.sh [BUILD_DIR] [--json FILE] [--schemes "gregory,adaptive --isolation 6,..."]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build
if [[ $# -gt 0 && $1 != --* ]]; then build=$1; shift; fi
exec /usr/bin/python3 - "$build/bin/tessera" "$root" "$@" <<'PY'
import concurrent.futures, glob, json, os, subprocess, sys, tempfile
bin, root, args = sys.argv[1], sys.argv[2], sys.argv[3:]
out_json = args[args.index("--json") + 1] if "--json" in args else None
schemes = (args[args.index("--schemes") + 1] if "--schemes" in args else "gregory,acc,bspline,adaptive,exact").split(",")
shapes = sorted(glob.glob(os.path.join(root, "tests/data/osd-shapes/catmark_*.obj")))

def run(argv, parse=True):
    r = subprocess.run([bin, "-q"] + argv, capture_output=True, text=True)
    if r.returncode != 0:
        return {"error": r.stderr.strip()}
    return json.loads(r.stdout) if parse else {}

def measure(shape, scheme):
    a = run(["accuracy", shape, "--json", "--scheme"] + scheme.split())
    if "error" in a:
        return {"error": a["error"]}
    with tempfile.TemporaryDirectory() as d:
        stats = os.path.join(d, "s.json")
        run(["tessellate", shape, "--scheme"] + scheme.split() + ["--factor", "4", "--stats", stats], parse=False)
        patches = json.load(open(stats))["totals"]["patches"] if os.path.exists(stats) else None
    b = run(["bench", "frog", "--cage", shape, "--scheme"] + scheme.split() + ["--frames", "3", "--factor", "8",
             "--threads", "1", "--resolution", "640x360", "--json"])
    return {"max_relative": a["max_relative"], "folded_samples": a["folded_samples"],
            "mean_normal_degrees": a["mean_normal_degrees"], "max_normal_degrees_defined": a["max_normal_degrees_defined"],
            "patches": patches, "frame_ms": 1000 * b["median_s"] if "median_s" in b else None}

jobs = [(s, k) for s in shapes for k in schemes]
with concurrent.futures.ThreadPoolExecutor(os.cpu_count()) as pool:
    results = dict(zip(jobs, pool.map(lambda j: measure(*j), jobs)))

print("| shape | " + " | ".join(schemes) + " |")
print("|---|" + "---|" * len(schemes))
for s in shapes:
    cells = []
    for k in schemes:
        r = results[(s, k)]
        cells.append("refused" if "error" in r else "%.1e / %d / %.1f° / %s / %.1f" % (
            r["max_relative"], r["folded_samples"], r["mean_normal_degrees"], r["patches"], r["frame_ms"] or 0))
    print("| %s | %s |" % (os.path.basename(s)[:-4], " | ".join(cells)))
print("\ncells: largest distance (of the diagonal) / folded samples / mean normal error / patches / frame ms\n")
print("| scheme | shapes drawn | refused | folded samples (shapes) | distance > 2e-2 (shapes) | worst distance |")
print("|---|---|---|---|---|---|")
for k in schemes:
    ok = [(s, results[(s, k)]) for s in shapes if "error" not in results[(s, k)]]
    folded = [s for s, r in ok if r["folded_samples"] > 0]
    far = [s for s, r in ok if r["max_relative"] > 2e-2]
    worst = max(ok, key=lambda x: x[1]["max_relative"])
    print("| %s | %d | %d | %d (%d) | %d | %.1e (%s) |" % (k, len(ok), len(shapes) - len(ok),
          sum(r["folded_samples"] for _, r in ok), len(folded), len(far), worst[1]["max_relative"],
          os.path.basename(worst[0])[:-4]))
if out_json:
    json.dump({os.path.basename(s)[:-4]: {k: results[(s, k)] for k in schemes} for s in shapes},
              open(out_json, "w"), indent=1)
PY

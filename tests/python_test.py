#!/usr/bin/python3
"""The `tessera` Python package: render() gives the bytes `tessera render --scene` writes (as an
H x W x 4 array), diff() gives idiff's verdict, load_cage() the cage, and errors arrive as
tessera.InputError / tessera.UsageError. Usage: python_test.py TESSERA_BIN SOURCE_DIR.
"""
import os
import subprocess
import sys
import tempfile

import numpy

import tessera

TESSERA, SOURCE = sys.argv[1], sys.argv[2]
scene = os.path.join(SOURCE, "golden", "suites", "scenes", "frog-acc-wire.json")
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


with tempfile.TemporaryDirectory() as tmp:
    image = tessera.render(scene, threads=1)
    check(image.shape == (180, 320, 4) and image.dtype == numpy.uint8, "render: 180 x 320 x 4 uint8")
    check(numpy.array_equal(image, tessera.render(scene, threads=2)), "the same array for 1 and 2 threads")
    cli = os.path.join(tmp, "cli.png")
    subprocess.run([TESSERA, "-q", "render", "--scene", scene, "-o", cli], check=True, capture_output=True)
    py = os.path.join(tmp, "py.png")
    tessera.render_to_file(scene, py)
    check(open(cli, "rb").read() == open(py, "rb").read(), "render_to_file writes the CLI's bytes")
    d = tessera.diff(cli, py, exact=True)
    check(d["verdict"] == "pass" and d["identical"] and d["hash_a"] == d["hash_b"], "diff: identical, one hash")
    other = os.path.join(SOURCE, "golden", "suites", "views", "frog-pn-factors.png")
    d = tessera.diff(cli, other)
    check(d["verdict"] == "failure" and d["exit_code"] == 2 and d["over_fail"] > 0, "diff: a failure with counts")
    cage = tessera.load_cage(os.path.join(SOURCE, "tests", "data", "sdk-cages", "cube.obj"))
    check(cage["positions"].shape == (8, 3) and len(cage["face_sizes"]) == 6, "load_cage: the cube's 8 vertices, 6 faces")
    try:
        tessera.render(os.path.join(tmp, "missing.json"))
        check(False, "a missing scene raises")
    except tessera.InputError as e:
        check("missing.json" in str(e) and isinstance(e, RuntimeError), "a missing scene: InputError naming it")
    try:
        tessera.render(scene, threads=-1)
        check(False, "threads=-1 raises")
    except tessera.UsageError as e:
        check(isinstance(e, ValueError), "threads=-1: UsageError (a ValueError)")

sys.exit(1 if failures else 0)

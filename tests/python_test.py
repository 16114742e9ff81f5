#!/usr/bin/python3
"""The `tessera` Python package: render() gives the image `tessera render` writes (as an H x W x 4
array, from a scene file, a scene dict or an asset with scene fields as keywords), diff() gives idiff's verdict, load_cage() the cage, and errors arrive as
tessera.InputError / tessera.UsageError. Usage: python_test.py TESSERA_BIN SOURCE_DIR.
"""
import os
import struct
import subprocess
import sys
import tempfile
import zlib

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
    # The array is the image the CLI writes, legend and all: the PNG decoded (by OpenImageIO's reader,
    # through idiff-compatible diff, whose exact mode compares the decoded pixels).
    arr_png = os.path.join(tmp, "array.png")
    def write_png(path, a):
        h, w, _ = a.shape
        raw = b"".join(b"\x00" + a[y].tobytes() for y in range(h))
        chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
        with open(path, "wb") as f:
            f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
                    + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))

    write_png(arr_png, image)
    check(tessera.diff(cli, arr_png, exact=True)["identical"], "render(): the CLI's image, pixel for pixel")
    # An asset with scene fields as keywords: the CLI's image for the same options, a debug view's legend
    # included.
    shape = os.path.join(SOURCE, "tests", "data", "osd-shapes", "catmark_pawn.obj")
    kw = os.path.join(tmp, "kw.png")
    subprocess.run([TESSERA, "-q", "render", shape, "--view", "factors", "--factor", "3", "--resolution", "160x120",
                    "-o", kw], check=True, capture_output=True)
    a = tessera.render(shape, view="factors", factor=3, resolution=[160, 120])
    # The same path written again within the second: diff reads the file as it is now (OpenImageIO's
    # shared cache, keyed by name and modification time, would hand back the first image).
    write_png(arr_png, a)
    d = tessera.diff(kw, arr_png, exact=True)
    check(a.shape == (120, 160, 4) and d["identical"],
          "render(asset, view=..., factor=..., resolution=...): the CLI's image with its legend "
          f"({d['over_fail']} pixels differ, the first at {d['max_pixel']}; {d['error']})")
    b = tessera.render({"tessera_scene": 1, "asset": shape, "view": "factors", "factor": 3, "resolution": [160, 120]})
    check(numpy.array_equal(a, b), "render(dict): the same image as keywords")
    c = tessera.render(scene, resolution=[160, 90])
    check(c.shape == (90, 160, 4), "a scene file with a keyword over one of its fields")
    try:
        tessera.render(shape, shceme="exact")
        check(False, "a misspelt keyword raises")
    except tessera.InputError as e:
        check("shceme" in str(e), "a misspelt keyword: InputError naming it")
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

    # UDIM: a tile set named with <UDIM> (one tile 1001 here) draws the single map's image; a missing
    # tile is an InputError naming it.
    import shutil
    frog = os.path.join(SOURCE, "tests", "data", "sdk-cages", "monsterfrog_mapped_00.obj")
    dds = os.path.join(SOURCE, "tests", "data", "sdk-cages", "monsterfrog.dds")
    shutil.copyfile(dds, os.path.join(tmp, "frog.1001.dds"))
    single = tessera.render(frog, displacement={"map": dds, "channel": "A"}, factor=4, resolution=[160, 120])
    tiled = tessera.render(frog, displacement={"map": os.path.join(tmp, "frog.<UDIM>.dds"), "channel": "A"},
                           factor=4, resolution=[160, 120])
    check(numpy.array_equal(single, tiled), "UDIM: tile 1001 of a <UDIM> set draws the single map's image")
    try:
        tessera.render(frog, displacement={"map": os.path.join(tmp, "none.<UDIM>.dds"), "channel": "A"})
        check(False, "a missing UDIM tile raises")
    except tessera.InputError as e:
        check("1001" in str(e), "UDIM: a missing tile is an InputError naming it")

sys.exit(1 if failures else 0)

#!/usr/bin/env python3
"""The Blender add-on (python/blender/tessera_blender) in headless Blender: installed from its zip as
the README says, then blender_addon_cases.py drives its operators. Exit 77 (skipped, with the reason)
only where Blender is absent (scripts/setup.sh installs it).

    blender_addon_test.py TESSERA_BINARY SOURCE_DIR
"""
import os
import shutil
import subprocess
import sys
import tempfile

tessera, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
blender = shutil.which("blender")
if blender is None:
    print("skipped: no blender on PATH (scripts/setup.sh installs Debian's blender)")
    sys.exit(77)
with tempfile.TemporaryDirectory(prefix="tessera-blender-test-") as tmp:
    # The README's install: the zip of the add-on's folder, made with Python's zipfile.
    addon = os.path.join(source, "python", "blender")
    archive = os.path.join(tmp, "tessera_blender.zip")
    subprocess.run(["/usr/bin/python3", "-m", "zipfile", "-c", archive, "tessera_blender/"], cwd=addon, check=True)
    env = dict(os.environ, BLENDER_USER_SCRIPTS=os.path.join(tmp, "scripts"),
               BLENDER_USER_CONFIG=os.path.join(tmp, "config"))
    env.pop("TESSERA", None)
    cases = os.path.join(source, "tests", "blender_addon_cases.py")
    r = subprocess.run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", cases, "--",
                        tessera, archive, os.path.join(tmp, "out")], env=env, capture_output=True, text=True,
                       timeout=900)
    lines = [l for l in (r.stdout + r.stderr).splitlines() if l.startswith(("CASE", "FAIL", "Traceback", "  ", "Error"))
             or "Error" in l]
    print("\n".join(lines))
    sys.exit(r.returncode)

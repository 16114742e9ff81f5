"""Tessera from Python: load a cage or scene, render to a NumPy array, compare images, run golden
suite cases -- the same functions the `tessera` CLI runs, so the bytes are the CLI's.

    import tessera
    image = tessera.render("scene.json")            # H x W x 4 uint8 (RGBA): the PNG the CLI writes
    image = tessera.render("cage.obj", scheme="exact", view="factors", resolution=[640, 480])
    tessera.render_to_file("scene.json", "out.png")  # as `tessera render --scene scene.json -o out.png`
    tessera.diff("a.png", "b.png", fail=0.004)       # idiff 2.4's verdict and metrics, as a dict
    cage = tessera.load_cage("cage.obj")             # positions, face_sizes, face_vertices (OBJ or glTF;
                                                     # time=T poses an animated glTF)

Errors: tessera.InputError (a file or its contents; a RuntimeError) and tessera.UsageError (a bad
value; a ValueError), each one line as the CLI prints it. `python3 -m tessera.batch` runs a golden
suite on Dask workers (tessera/batch.py).
"""
from ._tessera import (  # noqa: F401  (the package's API)
    InputError,
    UsageError,
    __version__,
    diff,
    load_cage,
    render,
    render_to_file,
    run_case,
    suite_cases,
    suite_name,
    write_check_reports,
)

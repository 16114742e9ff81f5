#!/usr/bin/python3
"""Checks the layout rules of ARCHITECTURE.md on the source tree:

1. dependencies point one way: a folder includes project headers only from the folders its layer
   may use (tessellator <- pipeline <- shaders_cpp <- tools), and
2. a library's own headers are its own: a header not listed in its folder's
   tessera_public_headers(...) call is included from that folder only (tests excepted: they test
   internals), and
3. no Catch test case's name starts with '-' (ctest would pass it to the test binary as an option),
4. the viewer and the Python module use the scene library (tools/scene), never the command line
   (tools/cli), and
5. no source file sits loose at the top of shaders_cpp/ or tools/: every module is in a room, and
6. a file opens only its folder's namespaces (NAMESPACES): the tessellator `tessera::ts`, the pipeline
   and the shaders' shared vocabulary `tessera`, a shaders room's own names `tessera::<room>`, each
   tools room its own (`tessera::scene`, `tessera::viewer`, `tessera::cli`, ...); any of them may
   hold a `detail` namespace,
7. no function in shaders_cpp/, tools/scene/ or tools/viewer/ is over 150 lines (function_lengths.py counts them); in
   pipeline/ a longer one (a SIMD kernel) says why in the comment above it, with the words "kept whole",
8. ARCHITECTURE.md is at most 150 lines.

Usage: layout_check.py SOURCE_DIR. Prints each violation as FILE:LINE: message; exit 1 if any.
"""
import os
import re
import sys

import function_lengths

MAX_FUNCTION_LINES = 150
MAX_ARCHITECTURE_LINES = 150

# folder -> folders whose headers it may include (itself always)
SHADERS = ["tessellator", "pipeline", "shaders_cpp/image_io", "shaders_cpp/cage", "shaders_cpp/animation",
           "shaders_cpp/gltf", "shaders_cpp/subdiv", "shaders_cpp/displacement", "shaders_cpp/lod"]
BELOW_TOOLS = SHADERS + ["shaders_cpp/optimize", "shaders_cpp/render", "shaders_cpp/debug", "shaders_cpp/bake",
                         "tools/verify", "tools/measure"]
ALLOWED = {
    "tessellator": [],
    "pipeline": ["tessellator"],
    "shaders_cpp/image_io": ["tessellator", "pipeline"],
    "shaders_cpp/cage": [],
    "shaders_cpp/animation": [],
    "shaders_cpp/gltf": ["shaders_cpp/cage", "shaders_cpp/animation"],
    "shaders_cpp/subdiv": ["tessellator", "shaders_cpp/cage"],
    "shaders_cpp/displacement": ["tessellator", "pipeline", "shaders_cpp/image_io", "shaders_cpp/cage",
                                 "shaders_cpp/subdiv"],
    "shaders_cpp/optimize": ["shaders_cpp/cage"],
    "shaders_cpp/lod": ["tessellator", "pipeline", "shaders_cpp/cage", "shaders_cpp/subdiv"],
    "shaders_cpp/render": SHADERS,
    "shaders_cpp/debug": SHADERS + ["shaders_cpp/render"],
    "shaders_cpp/bake": SHADERS + ["shaders_cpp/render"],
    "tools/verify": ["tessellator", "shaders_cpp/image_io"],  # images through the codec
    # A scheme's accuracy is measured on what it draws: the render path, as any caller runs it.
    "tools/measure": SHADERS + ["shaders_cpp/render"],
    # The scene library, and the viewer and the Python module over it: never the command line.
    "tools/scene": BELOW_TOOLS,
    "tools/viewer": BELOW_TOOLS + ["tools/scene"],
    "python": BELOW_TOOLS + ["tools/scene"],
    "tools/cli": BELOW_TOOLS + ["tools/scene", "tools/viewer"],
}
# folder -> the namespaces its files may open (and their ::detail). A shaders room declares the
# vocabulary the rooms share in `tessera` and the names only it uses in `tessera::<room>`.
NAMESPACES = {
    "tessellator": ["tessera::ts", "tessera::ts::hlsl", "tessera"],  # tessera: check.h, used by every layer
    "pipeline": ["tessera", "tessera::simd"],
    "tools/verify": ["tessera::verify", "tessera::oracle"],
    "tools/measure": ["tessera::measure"],
    "tools/scene": ["tessera::scene"],
    "tools/viewer": ["tessera::viewer"],
    "tools/cli": ["tessera::cli"],
    "python": [],
}
for _room in ALLOWED:
    if _room.startswith("shaders_cpp/"):
        NAMESPACES[_room] = ["tessera", "tessera::" + _room.split("/")[1]]
NAMESPACE = re.compile(r"^namespace\s+(tessera[\w:]*)\s*\{")
# Folders that hold only subfolders (and scripts): a source file at their top is a loose module.
ROOMS_ONLY = ["shaders_cpp", "tools"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
PUBLIC = re.compile(r"tessera_public_headers\(\s*\S+\s+([^)]*)\)", re.S)


def public_headers(root, folder):
    path = os.path.join(root, folder, "CMakeLists.txt")
    if not os.path.exists(path):
        return set()
    text = open(path).read()
    names = set()
    for m in PUBLIC.finditer(text):
        for token in m.group(1).split():
            if token.startswith("${"):  # a glob of every header: all public
                return {h for h in os.listdir(os.path.join(root, folder)) if h.endswith(".h")}
            names.add(token)
    return names


def main():
    root = sys.argv[1]
    public = {f: public_headers(root, f) for f in ALLOWED}
    errors = []
    for folder in list(ALLOWED) + ["tests"]:
        directory = os.path.join(root, folder)
        for name in sorted(os.listdir(directory)):
            if not name.endswith((".h", ".cpp")):
                continue
            path = os.path.join(directory, name)
            for number, line in enumerate(open(path, encoding="utf-8"), 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                target = m.group(1)
                where = f"{folder}/{name}:{number}"
                target_folder = os.path.dirname(target)
                if not target_folder:
                    if folder != "tests" and not os.path.exists(os.path.join(directory, target)):
                        errors.append(f"{where}: \"{target}\" is not in {folder}/")
                    elif folder != "tests":
                        errors.append(f"{where}: include \"{folder}/{target}\" with its folder")
                    continue
                if target_folder not in ALLOWED:
                    errors.append(f"{where}: \"{target}\" is in no library folder")
                    continue
                if not os.path.exists(os.path.join(root, target)):
                    errors.append(f"{where}: \"{target}\" does not exist")
                    continue
                if folder == "tests" or target_folder == folder:
                    continue
                if target_folder not in ALLOWED[folder]:
                    errors.append(f"{where}: {folder} may not depend on {target_folder} (\"{target}\")")
                elif os.path.basename(target) not in public[target_folder]:
                    errors.append(f"{where}: \"{target}\" is private to {target_folder}")
    for folder, names in NAMESPACES.items():
        allowed = set(names) | {n + "::detail" for n in names}
        directory = os.path.join(root, folder)
        for name in sorted(os.listdir(directory)):
            if not name.endswith((".h", ".cpp", ".cpp.in")):
                continue
            for number, line in enumerate(open(os.path.join(directory, name), encoding="utf-8"), 1):
                m = NAMESPACE.match(line)
                if m and m.group(1) not in allowed:
                    errors.append(f"{folder}/{name}:{number}: namespace {m.group(1)} is not {folder}'s "
                                  f"({', '.join(names) or 'none'})")
    for folder in ["shaders_cpp", "tools/scene", "tools/viewer", "pipeline"]:
        for path in function_lengths.sources([os.path.join(root, folder)]):
            lines = None
            for name, first, last in function_lengths.functions(path):
                if last - first + 1 <= MAX_FUNCTION_LINES:
                    continue
                if folder == "pipeline":
                    lines = lines or open(path, encoding="utf-8").read().split("\n")
                    if "kept whole" in "\n".join(lines[max(0, first - 16):first - 1]).lower():
                        continue
                rel = os.path.relpath(path, root)
                errors.append(f"{rel}:{first}: {name} is {last - first + 1} lines (at most {MAX_FUNCTION_LINES})")
    architecture = open(os.path.join(root, "ARCHITECTURE.md"), encoding="utf-8").read().count("\n")
    if architecture > MAX_ARCHITECTURE_LINES:
        errors.append(f"ARCHITECTURE.md: {architecture} lines (at most {MAX_ARCHITECTURE_LINES})")
    # Test case names ctest cannot carry: catch_discover_tests reads a leading '-' as an option, and a
    # ';' splits the name (CMake's list separator), so ctest runs a spec matching nothing.
    case = re.compile(r'TEST_CASE\(\s*"([^"]*)"')
    for name in sorted(os.listdir(os.path.join(root, "tests"))):
        if name.endswith(".cpp"):
            text = open(os.path.join(root, "tests", name), encoding="utf-8").read()
            for m in case.finditer(text):
                if m.group(1).startswith("-"):
                    errors.append(f"tests/{name}: the test case \"{m.group(1)}\" starts with '-' (ctest reads it as an option)")
                if ";" in m.group(1):
                    errors.append(f"tests/{name}: the test case \"{m.group(1)}\" has a ';' (ctest cuts the name there)")
    for folder in ROOMS_ONLY:
        for name in sorted(os.listdir(os.path.join(root, folder))):
            if name.endswith((".h", ".cpp")):
                errors.append(f"{folder}/{name}: a module loose at the top of {folder}/ (give it a folder)")
    for e in errors:
        print(e)
    print(f"layout_check: {len(errors)} violation(s)", file=sys.stderr)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())

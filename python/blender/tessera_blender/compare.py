"""Tessera's exact limit surface against Blender's own subdivision of the same cage.

- At the cage's vertices: Blender's level-6 mesh starts with the cage's vertices, on the limit surface
  when the modifier's Use Limit Surface is on (its default); Tessera's exact limit at a vertex is its
  patches' corner there (`tessera tessellate --scheme exact`, each point's face and (u, v) in the PLY).
- Everywhere: every vertex of Blender's mesh against Tessera's exact surface tessellated at factor 64
  (the nearest point on its triangles, mathutils' BVH tree).
Distances are given over the bounding-box diagonal of Blender's mesh.
"""

import math

import numpy as np
from mathutils.bvhtree import BVHTree

# What the tests hold Blender's limit surface to (the tolerances).
CAGE_TOLERANCE = 1e-5
MESH_TOLERANCE = 1e-4


def read_ply(path):
    """Tessera's binary PLY: vertex records (x y z nx ny nz face u v) and triangles."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    if "format binary_little_endian 1.0" not in header:
        raise ValueError("%s: not a little-endian binary PLY" % path)
    counts, props, element = {}, {"vertex": []}, None
    for line in header:
        w = line.split()
        if w[:1] == ["element"]:
            element = w[1]
            counts[element] = int(w[2])
        elif w[:1] == ["property"] and element == "vertex":
            props["vertex"].append((w[2], {"float": "<f4", "int": "<i4", "double": "<f8"}[w[1]]))
    vertex = np.dtype(props["vertex"])
    vertices = np.frombuffer(data, dtype=vertex, count=counts["vertex"], offset=end)
    start = end + vertex.itemsize * counts["vertex"]
    face = np.dtype([("n", "u1"), ("i", "<i4", (3,))])
    faces = np.frombuffer(data, dtype=face, count=counts.get("face", 0), offset=start)
    if len(faces) and not np.all(faces["n"] == 3):
        raise ValueError("%s: faces that are not triangles" % path)
    return vertices, faces["i"]


def limit_at_cage_vertices(vertices, cage_faces, hint):
    """Tessera's point at each cage vertex: a quad's corner (u, v) in {0, 1}^2, a triangle's barycentric
    corner; a vertex only n-gons have takes the fan corner nearest `hint` (Blender's point there)."""
    n = len(hint)
    out = np.full((n, 3), np.nan)
    xyz = np.stack([vertices["x"], vertices["y"], vertices["z"]], axis=1).astype(np.float64)
    face, u, v = vertices["face"], vertices["u"], vertices["v"]
    corner = ((u == 0) | (u == 1)) & ((v == 0) | (v == 1))
    candidates = {}
    for i in np.nonzero(corner)[0]:
        f = int(face[i])
        verts = cage_faces[f]
        if len(verts) == 4:
            k = {(0.0, 0.0): 0, (1.0, 0.0): 1, (1.0, 1.0): 2, (0.0, 1.0): 3}[(float(u[i]), float(v[i]))]
        elif len(verts) == 3:
            k = {(0.0, 0.0): 0, (1.0, 0.0): 1, (0.0, 1.0): 2}.get((float(u[i]), float(v[i])))
            if k is None:
                continue
        else:
            if u[i] == 0 and v[i] == 0:
                for c in verts:
                    candidates.setdefault(c, []).append(xyz[i])
            continue
        out[verts[k]] = xyz[i]
    for c, points in candidates.items():
        if np.isnan(out[c, 0]):
            p = np.array(points)
            out[c] = p[np.argmin(np.linalg.norm(p - hint[c], axis=1))]
    return out


def worst(distances, diagonal, tolerance, names, limit=10):
    """The entries above `tolerance` (relative), largest first, at most `limit` of them."""
    rel = distances / diagonal
    order = np.argsort(-rel)
    return [{"vertex": int(names[i]), "relative": float(rel[i])} for i in order[:limit] if rel[i] > tolerance]


def compare(cage, blender_positions, ply_path, blender_vertex_names):
    """The report: Blender's level-6 mesh (positions in the cage's frame, its first vertices the cage's)
    against Tessera's exact surface in the PLY."""
    vertices, triangles = read_ply(ply_path)
    b = np.asarray(blender_positions, dtype=np.float64)
    lo, hi = b.min(axis=0), b.max(axis=0)
    diagonal = float(np.linalg.norm(hi - lo)) or 1.0
    n = len(cage.positions)
    # Blender numbers the subdivided mesh's first vertices as the coarse ones it uses.
    at_cage = b[np.array(cage.blender_vertex)] if len(b) > max(cage.blender_vertex) else b[:n]
    tessera_at_cage = limit_at_cage_vertices(vertices, cage.faces, at_cage)
    d_cage = np.linalg.norm(tessera_at_cage - at_cage, axis=1)
    missing = np.isnan(d_cage)
    d_cage = np.where(missing, 0.0, d_cage)
    xyz = np.stack([vertices["x"], vertices["y"], vertices["z"]], axis=1).astype(np.float64)
    tree = BVHTree.FromPolygons(xyz.tolist(), triangles.tolist(), all_triangles=True, epsilon=0.0)
    d_mesh = np.empty(len(b))
    for i, p in enumerate(b):
        hit = tree.find_nearest(p)
        d_mesh[i] = hit[3] if hit[0] is not None else math.inf
    report = {
        "diagonal": diagonal,
        "cage_vertices": {
            "count": int(n - missing.sum()),
            "max": float(d_cage.max()),
            "max_relative": float(d_cage.max() / diagonal),
            "mean_relative": float(d_cage.mean() / diagonal),
            "tolerance": CAGE_TOLERANCE,
            "over": worst(d_cage, diagonal, CAGE_TOLERANCE, blender_vertex_names),
        },
        "mesh": {
            "count": int(len(b)),
            "max": float(d_mesh.max()),
            "max_relative": float(d_mesh.max() / diagonal),
            "rms_relative": float(math.sqrt(float(np.mean(d_mesh * d_mesh))) / diagonal),
            "tolerance": MESH_TOLERANCE,
            "over": worst(d_mesh, diagonal, MESH_TOLERANCE, np.arange(len(b))),
        },
    }
    report["ok"] = not report["cage_vertices"]["over"] and not report["mesh"]["over"]
    return report

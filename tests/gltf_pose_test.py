#!/usr/bin/python3
"""glTF poses checked against an evaluator written here from the glTF 2.0 spec, sharing nothing with
Tessera's reader or its animation code: JSON and buffers parsed with the standard library and NumPy,
node TRS with LINEAR (slerp) samplers, skins with inverse bind matrices, morph weights, then welded on
exact position bits (first occurrence first). tessera.load_cage(path, time=T) must agree within float
round-off. Usage: gltf_pose_test.py SOURCE_DIR.
"""
import base64
import json
import os
import sys

import numpy

import tessera

SOURCE = sys.argv[1]
failures = []

COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
TYPES = {5120: numpy.int8, 5121: numpy.uint8, 5122: numpy.int16, 5123: numpy.uint16, 5125: numpy.uint32,
         5126: numpy.float32}


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def load(path):
    doc = json.load(open(path))
    buffers = [base64.b64decode(b["uri"].split(",", 1)[1]) for b in doc["buffers"]]

    def accessor(i):
        a = doc["accessors"][i]
        view = doc["bufferViews"][a["bufferView"]]
        n = COMPONENTS[a["type"]]
        dtype = numpy.dtype(TYPES[a["componentType"]])
        stride = view.get("byteStride", n * dtype.itemsize)
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        raw = buffers[view["buffer"]]
        rows = [numpy.frombuffer(raw, dtype, n, start + k * stride) for k in range(a["count"])]
        out = numpy.array(rows, dtype=numpy.float64)
        if a.get("normalized"):
            out /= numpy.iinfo(dtype).max
        return out

    return doc, accessor


def quat_matrix(q):
    x, y, z, w = q
    return numpy.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def slerp(a, b, s):
    a, b = numpy.array(a), numpy.array(b)
    d = numpy.dot(a, b)
    if d < 0:
        b, d = -b, -d
    if d > 0.9995:
        q = a + s * (b - a)
    else:
        theta = numpy.arccos(d)
        q = (numpy.sin((1 - s) * theta) * a + numpy.sin(s * theta) * b) / numpy.sin(theta)
    return q / numpy.linalg.norm(q)


def sample(times, values, t, rotation):
    if t <= times[0]:
        return values[0]
    if t >= times[-1]:
        return values[-1]
    k = numpy.searchsorted(times, t, side="right") - 1
    s = (t - times[k]) / (times[k + 1] - times[k])
    return slerp(values[k], values[k + 1], s) if rotation else values[k] + s * (values[k + 1] - values[k])


def pose(path, t):
    doc, accessor = load(path)
    nodes = [dict(n) for n in doc["nodes"]]
    for anim in doc.get("animations", [])[:1]:
        for ch in anim["channels"]:
            smp = anim["samplers"][ch["sampler"]]
            times = accessor(smp["input"])[:, 0]
            values = accessor(smp["output"])
            path_ = ch["target"]["path"]
            if path_ == "weights":
                values = values.reshape(len(times), -1)
            nodes[ch["target"]["node"]][path_] = sample(times, values, t, path_ == "rotation")
    parent = {c: i for i, n in enumerate(doc["nodes"]) for c in n.get("children", [])}

    def world(i):
        n = nodes[i]
        m = numpy.eye(4)
        m[:3, :3] = quat_matrix(n.get("rotation", [0, 0, 0, 1])) @ numpy.diag(n.get("scale", [1, 1, 1]))
        m[:3, 3] = n.get("translation", [0, 0, 0])
        return world(parent[i]) @ m if i in parent else m

    out = []
    for i, n in enumerate(nodes):
        if "mesh" not in n:
            continue
        mesh = doc["meshes"][n["mesh"]]
        weights = n.get("weights", mesh.get("weights", []))
        for prim in mesh["primitives"]:
            p = accessor(prim["attributes"]["POSITION"])
            bits = p.astype(numpy.float32).view(numpy.uint32)
            for k, target in enumerate(prim.get("targets", [])):
                p = p + weights[k] * accessor(target["POSITION"])
            h = numpy.hstack([p, numpy.ones((len(p), 1))])
            if "skin" in n:
                skin = doc["skins"][n["skin"]]
                ibm = accessor(skin["inverseBindMatrices"]).reshape(-1, 4, 4).transpose(0, 2, 1)
                joints = [world(j) @ ibm[k] for k, j in enumerate(skin["joints"])]
                js, ws = accessor(prim["attributes"]["JOINTS_0"]), accessor(prim["attributes"]["WEIGHTS_0"])
                ws = ws / ws.sum(axis=1, keepdims=True)
                q = numpy.zeros((len(p), 4))
                for c in range(4):
                    q += ws[:, c:c + 1] * numpy.einsum("vij,vj->vi", numpy.array([joints[int(j)] for j in js[:, c]]), h)
            else:
                q = h @ world(i).T
            seen = {}
            for v in range(len(p)):
                key = tuple(int(b) for b in bits[v])
                if key not in seen:
                    seen[key] = v
                    out.append(q[v, :3])
    return numpy.array(out)


assets = [("tests/data/gltf-cages/frog-skinned.gltf", [0.0, 0.4, 1.0, 1.7, 3.0]),
          ("tests/data/gltf-cages/frog-morph.gltf", [0.25, 1.0, 1.5]),
          ("tests/data/gltf-samples/SimpleSkin.gltf", [0.5, 1.7, 3.2]),
          ("tests/data/gltf-samples/SimpleMorph.gltf", [0.5, 1.5, 3.5])]
for name, times in assets:
    path = os.path.join(SOURCE, name)
    for t in times:
        expected = pose(path, t)
        got = tessera.load_cage(path, time=t)["positions"].astype(numpy.float64)
        diagonal = numpy.linalg.norm(expected.max(axis=0) - expected.min(axis=0))
        same_shape = got.shape == expected.shape
        error = numpy.abs(got - expected).max() / diagonal if same_shape else numpy.inf
        check(same_shape and error < 1e-6, "%s at t = %g: %d control points, largest error %.2g of the diagonal"
              % (os.path.basename(name), t, len(got), error))

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)

"""The active object's cage as Blender's Subdivision Surface modifier sees it, written for Tessera.

What the modifier subdivides is the mesh evaluated up to it, not including it (armature, shape keys and
the modifiers before it applied: animation stays at control-point rate). Its tags follow Blender's own
conversion to OpenSubdiv (source/blender/blenkernel/intern/subdiv_converter_mesh.c and subdiv_inline.h
of Blender 3.4):

- edge and vertex creases c in [0, 1] become sharpness 10 c^2 (BKE_subdiv_crease_to_sharpness_f);
  the vertices of loose edges are infinitely sharp;
- boundary smoothing ALL is OpenSubdiv's VTX_BOUNDARY_EDGE_ONLY, PRESERVE_CORNERS EDGE_AND_CORNER;
- UV smoothing NONE is FVAR_LINEAR_ALL, PRESERVE_CORNERS CORNERS_ONLY, ..._AND_JUNCTIONS CORNERS_PLUS1,
  ..._JUNCTIONS_AND_CONCAVE CORNERS_PLUS2, PRESERVE_BOUNDARIES BOUNDARIES, SMOOTH_ALL NONE;
- loop UVs at one vertex within STD_UV_CONNECT_LIMIT (1e-4) of each other are one UV vertex.

The active material's displacement (a Displacement node fed by an Image Texture, tiled images as UDIM
sets) becomes the scene's displacement map.

Coordinates are world space turned from Blender's Z-up to glTF's Y-up ((x, y, z) -> (x, z, -y)), as
Blender's glTF exporter does, so that Tessera's default up is the scene's and a GLB it writes imports
back in place.
"""

import math
import os
import re

import bpy
from mathutils import Vector

INFINITE = 10.0  # OpenSubdiv's Sdc::Crease::SHARPNESS_INFINITE
UV_CONNECT_LIMIT = 1e-4

# OpenSubdiv's shape-file codes (t interpolateboundary, t facevaryinginterpolateboundary) as Tessera reads them.
BOUNDARY_CODE = {"ALL": 2, "PRESERVE_CORNERS": 1}  # edge_only, edge_and_corner
FVAR_CODE = {
    "SMOOTH_ALL": 0,  # FVAR_LINEAR_NONE
    "PRESERVE_CORNERS": 1,  # CORNERS_ONLY
    "PRESERVE_CORNERS_AND_JUNCTIONS": 2,  # CORNERS_PLUS1
    "PRESERVE_CORNERS_JUNCTIONS_AND_CONCAVE": 3,  # CORNERS_PLUS2
    "PRESERVE_BOUNDARIES": 4,  # BOUNDARIES
    "NONE": 5,  # ALL
}


def crease_to_sharpness(c):
    """Blender's crease as OpenSubdiv's sharpness (BKE_subdiv_crease_to_sharpness_f)."""
    return min(10.0 * c * c, INFINITE)


def to_y_up(v):
    return (v[0], v[2], -v[1])


def from_y_up(v):
    return (v[0], -v[2], v[1])


def subsurf_modifier(ob):
    """The first Subdivision Surface modifier that is on (viewport or render), or None."""
    for i, m in enumerate(ob.modifiers):
        if m.type == "SUBSURF" and (m.show_viewport or m.show_render):
            return i, m
    return None, None


class Cage:
    """A polygon cage: world positions (Y-up), faces as vertex index lists, tags, UVs."""

    def __init__(self):
        self.positions = []  # [(x, y, z)]
        self.faces = []  # [[v, ...]]
        self.face_uvs = []  # [[vt, ...]] or []
        self.uvs = []  # [(u, v)]
        self.creases = []  # [(a, b, sharpness)]
        self.corners = []  # [(v, sharpness)]
        self.boundary = None  # OpenSubdiv code or None
        self.fvar = None
        self.blender_vertex = []  # cage vertex -> the Blender vertex index it came from
        self.subdivided = False  # whether a Catmull-Clark Subdivision Surface modifier asked for the surface
        self.mirrored = False  # faces reversed for a negative object scale
        self.uv_map = ""

    def obj_text(self, header):
        out = ["# " + line for line in header]
        out += ["v %r %r %r" % p for p in self.positions]
        out += ["vt %r %r" % t for t in self.uvs]
        for f, face in enumerate(self.faces):
            if self.uvs:
                out.append("f " + " ".join("%d/%d" % (v + 1, t + 1) for v, t in zip(face, self.face_uvs[f])))
            else:
                out.append("f " + " ".join(str(v + 1) for v in face))
        out += ["t crease 2/1/0 %d %d %r" % c for c in self.creases]
        out += ["t corner 1/1/0 %d %r" % c for c in self.corners]
        if self.boundary is not None:
            out.append("t interpolateboundary 1/0/0 %d" % self.boundary)
        if self.fvar is not None:
            out.append("t facevaryinginterpolateboundary 1/0/0 %d" % self.fvar)
        return "\n".join(out) + "\n"


def _mesh_cage(ob, me, mod):
    """Cage from an evaluated mesh `me` of `ob` (mod: the Subdivision Surface modifier or None)."""
    cage = Cage()
    world = ob.matrix_world
    used = sorted({v for p in me.polygons for v in p.vertices})
    index = {v: i for i, v in enumerate(used)}
    cage.blender_vertex = used
    cage.positions = [to_y_up(world @ me.vertices[v].co) for v in used]
    # A mirrored object (negative scale) turns its faces inside out in world space: reversed, they face
    # out again, as Blender draws them.
    mirrored = world.to_3x3().determinant() < 0.0
    order = (lambda seq: list(reversed(seq))) if mirrored else list
    cage.faces = [order([index[v] for v in p.vertices]) for p in me.polygons]
    cage.mirrored = mirrored
    cage.subdivided = mod is not None and mod.subdivision_type == "CATMULL_CLARK"
    if not cage.subdivided:
        return cage
    cage.boundary = BOUNDARY_CODE.get(mod.boundary_smooth)
    uv_layer = me.uv_layers.active
    if uv_layer is not None:
        cage.uv_map = uv_layer.name
        cage.fvar = FVAR_CODE.get(mod.uv_smooth)
        per_vertex = {}  # Blender vertex -> [(u, v, vt)]
        for p in me.polygons:
            row = []
            for li in p.loop_indices:
                v = me.loops[li].vertex_index
                u, w = uv_layer.data[li].uv
                known = per_vertex.setdefault(v, [])
                for (ku, kw, kt) in known:
                    if abs(ku - u) <= UV_CONNECT_LIMIT and abs(kw - w) <= UV_CONNECT_LIMIT:
                        row.append(kt)
                        break
                else:
                    known.append((u, w, len(cage.uvs)))
                    row.append(len(cage.uvs))
                    cage.uvs.append((u, w))
            cage.face_uvs.append(order(row))
    if mod.use_creases:
        for e in me.edges:
            a, b = e.vertices
            if e.crease > 0.0 and a in index and b in index:
                cage.creases.append((index[a], index[b], crease_to_sharpness(e.crease)))
        sharp = {}
        if len(me.vertex_creases):
            for v, d in enumerate(me.vertex_creases[0].data):
                if d.value > 0.0 and v in index:
                    sharp[index[v]] = crease_to_sharpness(d.value)
        face_edges = {tuple(sorted(k)) for p in me.polygons for k in p.edge_keys}
        for e in me.edges:  # loose edges make their vertices infinitely sharp, as Blender's converter does
            if tuple(sorted(e.vertices)) not in face_edges:
                for v in e.vertices:
                    if v in index:
                        sharp[index[v]] = INFINITE
        cage.corners = sorted(sharp.items())
    return cage


def modifiers_after(ob):
    """The names of the modifiers after the Subdivision Surface modifier that are on: Tessera's surface
    leaves them out."""
    at, mod = subsurf_modifier(ob)
    if mod is None:
        return []
    return [m.name for m in ob.modifiers[at + 1:] if m.show_viewport or m.show_render]


def evaluated_cage(context, ob):
    """The cage of `ob`: its mesh evaluated up to its Subdivision Surface modifier (excluded), or, with
    none, the whole evaluated mesh (Cage.subdivided False)."""
    if ob is None or ob.type != "MESH":
        raise ValueError("the active object is not a mesh (%s)" % ("nothing is active" if ob is None else ob.type))
    at, mod = subsurf_modifier(ob)
    saved = []
    if mod is not None:
        for m in ob.modifiers[at:]:
            saved.append((m, m.show_viewport))
            m.show_viewport = False
    try:
        dg = context.evaluated_depsgraph_get()
        dg.update()
        ev = ob.evaluated_get(dg)
        me = ev.to_mesh(preserve_all_data_layers=True, depsgraph=dg)
        try:
            if not me.polygons:
                raise ValueError("%s has no faces to subdivide" % ob.name)
            return _mesh_cage(ob, me, mod)
        finally:
            ev.to_mesh_clear()
    finally:
        for m, shown in saved:
            m.show_viewport = shown
        context.evaluated_depsgraph_get().update()


def camera_settings(scene, target_hint):
    """The scene camera as Tessera's: position, target, up (Y-up), vertical field of view in degrees,
    and resolution; None without a camera. Raises ValueError for what Tessera cannot draw."""
    cam = scene.camera
    r = scene.render
    width = max(1, round(r.resolution_x * r.resolution_percentage / 100))
    height = max(1, round(r.resolution_y * r.resolution_percentage / 100))
    if cam is None:
        return None, (width, height)
    if cam.type != "CAMERA":
        raise ValueError("the scene camera %s is not a camera object" % cam.name)
    data = cam.data
    if data.type != "PERSP":
        raise ValueError("the scene camera %s is %s; Tessera renders perspective cameras" % (cam.name, data.type.lower()))
    m = cam.matrix_world
    rot = m.to_3x3().normalized()
    position = m.translation.copy()
    forward = (rot @ Vector((0.0, 0.0, -1.0))).normalized()
    up = (rot @ Vector((0.0, 1.0, 0.0))).normalized()
    distance = (Vector(target_hint) - position).dot(forward)
    target = position + forward * (distance if distance > 1e-6 else 1.0)
    fit = data.sensor_fit
    horizontal = fit == "HORIZONTAL" or (fit == "AUTO" and width >= height)
    sensor = data.sensor_height if fit == "VERTICAL" else data.sensor_width
    half = math.atan(sensor / (2.0 * data.lens))
    if horizontal:
        half = math.atan(math.tan(half) * height / width)
    camera = {
        "position": list(to_y_up(position)),
        "target": list(to_y_up(target)),
        "up": list(to_y_up(up)),
        "fov": math.degrees(2.0 * half),
    }
    return camera, (width, height)


def _udim_path(image):
    """The file path of `image` for Tessera: absolute, a tiled image's tile number as the <UDIM> token."""
    path = bpy.path.abspath(image.filepath_raw or image.filepath)
    if image.source == "TILED" and "<UDIM>" not in path.upper():
        # A tiled image's path may name one of its tiles (name.1001.png): the tile number becomes the token.
        path = re.sub(r"(?<![0-9])(1[0-9]{3})(?=[^0-9/\\]*$)", "<UDIM>", path, count=1)
    return os.path.normpath(path)


def material_displacement(ob):
    """The displacement of `ob`'s active material as Tessera's scene settings, or None; raises ValueError
    for a displacement Tessera cannot read. Blender's Displacement node moves a point along its normal by
    (height - midlevel) * scale; its height read from an Image Texture node (a tiled image: UDIM) is
    Tessera's map, scale * texel + bias with bias = -midlevel * scale. World space: the scale times the
    object's (uniform) scale."""
    mat = ob.active_material
    if mat is None or not mat.use_nodes or mat.node_tree is None:
        return None
    nodes = mat.node_tree.nodes
    output = next((n for n in nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output), None)
    if output is None or not output.inputs["Displacement"].is_linked:
        return None
    node = output.inputs["Displacement"].links[0].from_node
    if node.type != "DISPLACEMENT":
        raise ValueError("%s: the material output's Displacement comes from a %s node; Tessera reads a Displacement "
                         "node fed by an Image Texture" % (mat.name, node.bl_label))
    height = node.inputs["Height"]
    if not height.is_linked or height.links[0].from_node.type != "TEX_IMAGE":
        raise ValueError("%s: the Displacement node's Height is not an Image Texture" % mat.name)
    link = height.links[0]
    image = link.from_node.image
    if image is None:
        raise ValueError("%s: the displacement Image Texture has no image" % mat.name)
    if image.packed_file is not None or image.source not in ("FILE", "TILED"):
        raise ValueError("%s: the displacement image %s is not a file on disk (unpack or save it)" % (mat.name, image.name))
    if node.space != "OBJECT":
        raise ValueError("%s: the Displacement node is in %s space; Tessera reads object space" % (mat.name, node.space))
    scale = node.inputs["Scale"].default_value * abs(ob.matrix_world.to_3x3().determinant()) ** (1.0 / 3.0)
    midlevel = node.inputs["Midlevel"].default_value
    return {
        "map": _udim_path(image),
        "channel": "A" if link.from_socket.name == "Alpha" else "R",
        "scale": scale,
        "bias": -midlevel * scale,
    }

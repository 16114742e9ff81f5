"""Run inside headless Blender by blender_addon_test.py: `blender -b --factory-startup --python
blender_addon_cases.py -- TESSERA ADDON_ZIP OUT_DIR`. An assertion fails the run (exit 1)."""
import json
import math
import os
import subprocess
import sys

import addon_utils
import bmesh
import bpy

tessera, archive, out = sys.argv[sys.argv.index("--") + 1:][:3]
os.makedirs(out, exist_ok=True)

bpy.ops.preferences.addon_install(filepath=archive)
addon_utils.enable("tessera_blender", default_set=True)
prefs = bpy.context.preferences.addons["tessera_blender"].preferences
prefs.tessera_path = tessera  # found through the preference (neither $TESSERA nor PATH has it)
scene = bpy.context.scene
settings = scene.tessera
scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 320, 240, 100
settings.output_dir = out
for o in list(bpy.data.objects):
    if o.type == "MESH":
        bpy.data.objects.remove(o)


def check(condition, what):
    if not condition:
        raise AssertionError(what + " | last report: " + settings.last_report)
    print("CASE ok:", what)


def cancelled(op):
    """Runs an operator that must refuse: Blender turns its ERROR report into a RuntimeError for a
    script (in the UI it is a report in the status bar); returns the message."""
    try:
        op()
    except RuntimeError as e:
        return str(e)
    raise AssertionError("the operator did not refuse | last report: " + settings.last_report)


def activate(ob):
    bpy.context.view_layer.objects.active = ob
    for o in bpy.context.view_layer.objects:
        o.select_set(o == ob)


def vertex_crease(ob, index, value):
    bm = bmesh.new()
    bm.from_mesh(ob.data)
    layer = bm.verts.layers.crease.verify()
    bm.verts.ensure_lookup_table()
    bm.verts[index][layer] = value
    bm.to_mesh(ob.data)
    bm.free()


def compare(ob, name):
    activate(ob)
    path = os.path.join(out, name + ".json")
    check(bpy.ops.tessera.compare(filepath=path) == {"FINISHED"}, name + ": compare runs")
    with open(path) as f:
        r = json.load(f)
    print("CASE", name, "cage", r["cage_vertices"]["max_relative"], "mesh", r["mesh"]["max_relative"])
    check(r["cage_vertices"]["max_relative"] <= 1e-5, name + ": Tessera's limit at the cage's vertices within 1e-5")
    check(r["mesh"]["max_relative"] <= 1e-4, name + ": Blender's level-6 vertices within 1e-4 of Tessera's surface")
    check(r["cage_vertices"]["count"] == len(ob.data.vertices), name + ": every cage vertex compared")
    return r


def render_equals_scene(ob, name):
    """tessera.render's image is tessera render --scene of the scene file it wrote, byte for byte."""
    activate(ob)
    image = os.path.join(out, name + ".png")
    check(bpy.ops.tessera.render(filepath=image) == {"FINISHED"}, name + ": render runs")
    result = json.loads(settings.last_result)
    again = os.path.join(out, name + "-again.png")
    subprocess.run([tessera, "-q", "render", "--scene", result["scene"], "-o", again], check=True)
    with open(image, "rb") as a, open(again, "rb") as b:
        check(a.read() == b.read(), name + ": the add-on's image is tessera render --scene of its scene file")
    check(any(i.filepath == image for i in bpy.data.images), name + ": the image is loaded in Blender")
    with open(result["scene"]) as f:
        return json.load(f), result


# A creased cube: edges at crease 1.0 and 0.5, one vertex crease.
bpy.ops.mesh.primitive_cube_add()
cube = bpy.context.active_object
cube.name = "CreasedCube"
for i, e in enumerate(cube.data.edges):
    e.crease = (1.0, 0.5, 0.0)[i % 3]
vertex_crease(cube, 0, 0.8)
cube.modifiers.new("Subdivision", "SUBSURF")
compare(cube, "cube")
sc, res = render_equals_scene(cube, "cube")
with open(res["cage"]) as f:
    obj = f.read()
check(obj.count("t crease 2/1/0") == 8 and "t corner 1/1/0 0 6.4" in obj, "cube: creases and the corner exported")
check("t crease 2/1/0 " in obj and " 10.0\n" in obj, "cube: crease 1.0 is sharpness 10 (10 c^2)")
check(sc["source"]["object"] == "CreasedCube" and sc["source"]["frame"] == scene.frame_current,
      "cube: the scene file records the object and frame")
check(sc["camera"]["fov"] > 0 and sc["resolution"] == [320, 240], "cube: the scene camera and resolution")
# The scheme's warning reaches Blender: pn draws the creases smooth.
settings.scheme = "pn"
activate(cube)
bpy.ops.tessera.render()
check("draws the cage's" in settings.last_report and "smooth" in settings.last_report,
      "cube: a scheme that drops tags says so in Blender")
settings.scheme = "exact"
# tessellate: the triangles come back as a new object.
before = set(bpy.data.objects)
check(bpy.ops.tessera.tessellate() == {"FINISHED"}, "cube: tessellate runs")
new = [o for o in bpy.data.objects if o not in before]
check(len(new) == 1 and new[0].type == "MESH" and len(new[0].data.polygons) > 1000,
      "cube: the tessellation is a new mesh object")
bpy.data.objects.remove(new[0])

# A creased cylinder with a UV map (n-gon caps).
bpy.ops.mesh.primitive_cylinder_add(vertices=12, location=(4, 0, 0))
cyl = bpy.context.active_object
cyl.name = "Cylinder"
for e in cyl.data.edges:
    z0, z1 = (cyl.data.vertices[v].co.z for v in e.vertices)
    if z0 == z1:
        e.crease = 0.7
mod = cyl.modifiers.new("Subdivision", "SUBSURF")
check(mod.uv_smooth == "PRESERVE_BOUNDARIES", "cylinder: Blender's default UV smoothing")
compare(cyl, "cylinder")
sc, res = render_equals_scene(cyl, "cylinder")
with open(res["cage"]) as f:
    obj = f.read()
check(obj.count("\nvt ") > 0 and "t facevaryinginterpolateboundary 1/0/0 4" in obj,
      "cylinder: its UV map and UV smoothing (BOUNDARIES) exported")
check("t interpolateboundary 1/0/0 2" in obj, "cylinder: boundary smoothing ALL is edge_only")

# An armature-bent bar at two frames: the cage at control-point rate, posed before the modifier.
bpy.ops.mesh.primitive_cube_add(location=(0, 6, 0))
bar = bpy.context.active_object
bar.name = "Bar"
bm = bmesh.new()
bm.from_mesh(bar.data)
bmesh.ops.subdivide_edges(bm, edges=[e for e in bm.edges if abs(e.verts[0].co.x - e.verts[1].co.x) > 1.0], cuts=5)
for v in bm.verts:
    v.co.x *= 3.0
bm.to_mesh(bar.data)
bm.free()
bpy.ops.object.armature_add(location=(-3, 6, 0))
arm = bpy.context.active_object
bpy.ops.object.mode_set(mode="EDIT")
root = arm.data.edit_bones[0]
root.head, root.tail = (0, 0, 0), (3, 0, 0)
tip = arm.data.edit_bones.new("Tip")
tip.head, tip.tail, tip.parent = (3, 0, 0), (6, 0, 0), root
bpy.ops.object.mode_set(mode="OBJECT")
names = [b.name for b in arm.data.bones]
g0, g1 = bar.vertex_groups.new(name=names[0]), bar.vertex_groups.new(name="Tip")
for v in bar.data.vertices:
    w = min(1.0, max(0.0, (v.co.x + 1.0) / 2.0))  # the bend around x = 0 (the bones' joint)
    g0.add([v.index], 1.0 - w, "REPLACE")
    g1.add([v.index], w, "REPLACE")
bar.modifiers.new("Armature", "ARMATURE").object = arm
bar.modifiers.new("Subdivision", "SUBSURF")
pose = arm.pose.bones["Tip"]
pose.rotation_mode = "XYZ"
for frame, angle in ((1, 0.0), (10, 50.0)):
    pose.rotation_euler = (0.0, 0.0, math.radians(angle))
    pose.keyframe_insert("rotation_euler", frame=frame)
cages = []
for frame in (1, 10):
    scene.frame_set(frame)
    r = compare(bar, "bar-f%d" % frame)
    check(r["frame"] == frame, "bar: frame %d compared" % frame)
    sc, res = render_equals_scene(bar, "bar-f%d" % frame)
    check(sc["source"]["frame"] == frame, "bar: the scene file records frame %d" % frame)
    with open(res["cage"]) as f:
        cages.append(f.read())
check(cages[0] != cages[1], "bar: the cage is posed per frame (before the modifier)")

# A mirrored object (negative scale): its faces are reversed so that they face out in world space, and
# Blender's subdivision still agrees; a modifier after the Subdivision Surface is said to be left out.
bpy.ops.mesh.primitive_cube_add(location=(0, -12, 0))
mirrored = bpy.context.active_object
mirrored.name = "Mirrored"
mirrored.scale = (-1.0, 1.0, 1.0)
mirrored.data.edges[0].crease = 0.6
mirrored.modifiers.new("Subdivision", "SUBSURF")
mirrored.modifiers.new("Displace", "DISPLACE")
compare(mirrored, "mirrored")
check("Displace" in settings.last_report and "left out" in settings.last_report,
      "mirrored: the modifier after the Subdivision Surface is said to be left out")
with open(json.loads(settings.last_result)["cage"]) as f:
    first = next(l for l in f if l.startswith("f "))
poly = mirrored.data.polygons[0].vertices
check([int(t.split("/")[0]) - 1 for t in first.split()[1:]] == list(reversed(poly)), "mirrored: the faces are reversed")
mirrored.modifiers["Subdivision"].subdivision_type = "SIMPLE"
check("Simple" in cancelled(bpy.ops.tessera.compare), "a Simple modifier: compare refuses, naming it")

# A displaced grid whose UVs span two UDIM tiles (u in [0, 2]): the material's Displacement node fed by
# a tiled image becomes the scene's <UDIM> map, and the render is the CLI's.
bpy.ops.mesh.primitive_grid_add(x_subdivisions=8, y_subdivisions=4, size=2, location=(0, 0, 0))
grid = bpy.context.active_object
grid.name = "UdimGrid"
uv_layer = grid.data.uv_layers.active  # the grid's own UV map, the one exported
for loop in grid.data.loops:
    co = grid.data.vertices[loop.vertex_index].co
    uv_layer.data[loop.index].uv = (co.x + 1.0, (co.y + 1.0) / 2.0)
grid.modifiers.new("Subdivision", "SUBSURF")
for tile, frequency in ((1001, 2.0), (1002, 5.0)):
    img = bpy.data.images.new("bump.%d" % tile, 32, 32)
    px = []
    for y in range(32):
        for x in range(32):
            h = 0.5 + 0.5 * math.sin(frequency * x / 32.0 * math.pi) * math.cos(frequency * y / 32.0 * math.pi)
            px += [h, h, h, 1.0]
    img.pixels = px
    img.filepath_raw = os.path.join(out, "bump.%d.png" % tile)
    img.file_format = "PNG"
    img.save()
tiled = bpy.data.images.load(os.path.join(out, "bump.1001.png"))
tiled.source = "TILED"
mat = bpy.data.materials.new("Displaced")
mat.use_nodes = True
nodes = mat.node_tree.nodes
tex, disp = nodes.new("ShaderNodeTexImage"), nodes.new("ShaderNodeDisplacement")
tex.image = tiled
disp.inputs["Scale"].default_value, disp.inputs["Midlevel"].default_value = 0.3, 0.5
mat.node_tree.links.new(tex.outputs["Color"], disp.inputs["Height"])
output = next(n for n in nodes if n.type == "OUTPUT_MATERIAL")
mat.node_tree.links.new(disp.outputs["Displacement"], output.inputs["Displacement"])
grid.data.materials.append(mat)
sc, res = render_equals_scene(grid, "udim")
d = sc.get("displacement", {})
check(d.get("map", "").endswith("bump.<UDIM>.png") and d.get("channel") == "R",
      "udim: the tiled image is the scene's <UDIM> map")
with open(res["cage"]) as f:
    us = [float(l.split()[1]) for l in f if l.startswith("vt ")]
check(min(us) == 0.0 and max(us) == 2.0, "udim: the exported UVs span tiles 1001 and 1002")
check(abs(d["scale"] - 0.3) < 1e-6 and abs(d["bias"] + 0.15) < 1e-6, "udim: scale and bias from the Displacement node")
mat.node_tree.links.remove(disp.inputs["Height"].links[0])
check("Image Texture" in cancelled(bpy.ops.tessera.render), "udim: a Height that is not an image is one report")
bpy.data.objects.remove(grid)

# Bad cases are reports, not tracebacks.
bpy.ops.mesh.primitive_uv_sphere_add(location=(0, -6, 0))
plain = bpy.context.active_object
check(bpy.ops.tessera.render() == {"FINISHED"} and "no Subdivision Surface modifier" in settings.last_report,
      "no modifier: renders, and says so")
with open(json.loads(settings.last_result)["scene"]) as f:
    check(json.load(f)["scheme"] == "flat", "no modifier: the cage is rendered as it is (flat)")
check("nothing to compare" in cancelled(bpy.ops.tessera.compare) and "nothing to compare" in settings.last_report,
      "no modifier: compare says there is nothing to compare")
activate(cube)
prefs.tessera_path = "/nonexistent/tessera"
saved_path = os.environ.get("PATH", "")
os.environ["PATH"] = "/nonexistent"
check("tessera not found" in cancelled(bpy.ops.tessera.render) and "tessera not found" in settings.last_report
      and "$TESSERA (unset)" in settings.last_report and "Preferences" in settings.last_report,
      "tessera not found: says where it looked and how to set it")
os.environ["PATH"] = saved_path
prefs.tessera_path = tessera
scene.camera.data.type = "ORTHO"
check("perspective" in cancelled(bpy.ops.tessera.render) and "perspective" in settings.last_report,
      "an orthographic camera: one report")
scene.camera.data.type = "PERSP"
print("CASE all passed")

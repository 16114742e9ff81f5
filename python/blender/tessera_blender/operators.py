"""The add-on's operators: tessera.render, tessera.tessellate, tessera.compare.

Each exports the active object's cage (cage_export.py) with a scene file beside it, runs the tessera
command line and reports in Blender: errors as ERROR reports (never a traceback), the command's
warnings (a tag or face the scheme cannot honour, ...) as WARNING reports, the result as INFO. The last
report is also kept in the scene's Tessera settings (`last_report`), for scripts.
"""

import json
import os
import tempfile

import bpy
from bpy.props import IntProperty, StringProperty

from . import cage_export, compare
from .tessera_cli import TesseraError, find_tessera, run


def _settings(context):
    return context.scene.tessera


def _output_dir(context):
    d = _settings(context).output_dir
    if d:
        d = bpy.path.abspath(d)
    else:
        d = os.path.join(tempfile.gettempdir(), "tessera-blender")
    os.makedirs(d, exist_ok=True)
    return d


def _stem(context, ob, filepath, suffix=""):
    """The files' directory and name stem: beside `filepath` when given, else the output directory."""
    if filepath:
        path = bpy.path.abspath(filepath)
        directory = os.path.dirname(os.path.abspath(path)) or "."
        os.makedirs(directory, exist_ok=True)
        return directory, os.path.splitext(os.path.basename(path))[0]
    safe = bpy.path.clean_name(ob.name)
    return _output_dir(context), "%s_f%d%s" % (safe, context.scene.frame_current, suffix)


def _application():
    return "Blender %s" % bpy.app.version_string


class _Export:
    """The cage written as OBJ and its scene file: what all three operators start from."""

    def __init__(self, context, ob, directory, stem):
        s = _settings(context)
        self.cage = cage_export.evaluated_cage(context, ob)
        self.warnings = []
        at, mod = cage_export.subsurf_modifier(ob)
        if mod is None:
            self.warnings.append("%s has no Subdivision Surface modifier: rendering its mesh as it is (--scheme flat)"
                                 % ob.name)
        elif not self.cage.subdivided:
            self.warnings.append("%s's Subdivision Surface modifier is Simple: its surface is the cage itself "
                                 "(--scheme flat)" % ob.name)
        after = cage_export.modifiers_after(ob)
        if after:
            self.warnings.append("the modifiers after %s's Subdivision Surface are left out: %s" %
                                 (ob.name, ", ".join(after)))
        self.obj_path = os.path.join(directory, stem + ".obj")
        self.scene_path = os.path.join(directory, stem + ".tessera.json")
        source = {"application": _application(), "object": ob.name, "frame": context.scene.frame_current}
        if bpy.data.filepath:
            source["file"] = bpy.data.filepath
        header = ["Tessera cage from %s: object %s, frame %d (Y-up world space)" %
                  (_application(), ob.name, context.scene.frame_current)]
        with open(self.obj_path, "w") as f:
            f.write(self.cage.obj_text(header))
        xs = [p for p in self.cage.positions]
        centre = [sum(p[i] for p in xs) / len(xs) for i in range(3)]
        camera, (width, height) = cage_export.camera_settings(context.scene, cage_export.from_y_up(centre))
        if camera is None:
            self.warnings.append("the scene has no camera: Tessera frames the object")
        scene = {
            "tessera_scene": 1,
            "asset": os.path.basename(self.obj_path),
            "scheme": s.scheme if self.cage.subdivided else "flat",
            "factor": s.factor,
            "lod": {"mode": s.lod, "edge_pixels": s.edge_pixels},
            "resolution": [width, height],
            "view": s.view,
            "msaa": int(s.msaa),
            "source": source,
        }
        if s.scheme == "adaptive":
            scene["isolation"] = s.isolation
        if camera is not None:
            scene["camera"] = camera
        displacement = cage_export.material_displacement(ob) if self.cage.subdivided else None
        if displacement is not None:
            scene["displacement"] = displacement
        self.scene = scene
        with open(self.scene_path, "w") as f:
            json.dump(scene, f, indent=2)
            f.write("\n")


class _TesseraOperator:
    filepath: StringProperty(name="File", description="Where to write the result (default: the output directory)",
                             subtype="FILE_PATH", default="")

    @classmethod
    def poll(cls, context):
        return context.active_object is not None

    def say(self, context, level, message):
        """A report in Blender, also kept (every report of this run, one per line) in last_report."""
        self.report({level}, message)
        s = _settings(context)
        s.last_report = (s.last_report + "\n" if s.last_report else "") + "%s: %s" % (level, message)

    def execute(self, context):
        _settings(context).last_report = ""
        ob = context.active_object
        try:
            addon = context.preferences.addons.get(__package__)
            tessera = find_tessera(addon.preferences.tessera_path if addon else "")
            return self.work(context, ob, tessera)
        except (TesseraError, ValueError, OSError) as e:
            self.say(context, "ERROR", str(e))
            return {"CANCELLED"}

    def warn_all(self, context, lines):
        for line in lines:
            self.say(context, "WARNING", line)


class TESSERA_OT_render(_TesseraOperator, bpy.types.Operator):
    """Render the active object's subdivision surface with Tessera from the scene camera"""

    bl_idname = "tessera.render"
    bl_label = "Render with Tessera"

    def work(self, context, ob, tessera):
        directory, stem = _stem(context, ob, self.filepath)
        image = bpy.path.abspath(self.filepath) if self.filepath else os.path.join(directory, stem + ".png")
        export = _Export(context, ob, directory, stem)
        self.warn_all(context, export.warnings)
        warnings, _ = run(tessera, ["render", "--scene", export.scene_path, "-o", image])
        self.warn_all(context, warnings)
        img = bpy.data.images.load(image, check_existing=True)
        img.reload()
        _show_image(context, img)
        _settings(context).last_result = json.dumps({"image": image, "scene": export.scene_path,
                                                     "cage": export.obj_path})
        self.say(context, "INFO", "Tessera rendered %s (%s) to %s" % (ob.name, export.scene["scheme"], image))
        return {"FINISHED"}


class TESSERA_OT_tessellate(_TesseraOperator, bpy.types.Operator):
    """Tessellate the active object's subdivision surface with Tessera and import the triangles as a new object"""

    bl_idname = "tessera.tessellate"
    bl_label = "Tessellate with Tessera"

    def work(self, context, ob, tessera):
        s = _settings(context)
        directory, stem = _stem(context, ob, self.filepath, "_tessellated")
        glb = os.path.join(directory, stem + ".glb")
        export = _Export(context, ob, directory, stem)
        self.warn_all(context, export.warnings)
        args = ["tessellate", export.obj_path, "--scheme", export.scene["scheme"], "--factor", repr(s.factor),
                "--lod", s.lod, "--edge-pixels", repr(s.edge_pixels), "-o", glb]
        if s.scheme == "adaptive":
            args += ["--isolation", str(s.isolation)]
        camera = export.scene.get("camera")
        if camera is not None:
            args += ["--camera-position", ",".join(repr(x) for x in camera["position"]),
                     "--camera-target", ",".join(repr(x) for x in camera["target"]),
                     "--camera-up", ",".join(repr(x) for x in camera["up"]), "--fov", repr(camera["fov"]),
                     "--resolution", "%dx%d" % tuple(export.scene["resolution"])]
        warnings, _ = run(tessera, args)
        self.warn_all(context, warnings)
        before = set(bpy.data.objects)
        _import_glb(glb)
        new = [o for o in bpy.data.objects if o not in before]
        for o in new:
            o.name = "%s (tessera %s)" % (ob.name, export.scene["scheme"])
        _settings(context).last_result = json.dumps({"glb": glb, "objects": [o.name for o in new]})
        self.say(context, "INFO", "Tessera tessellated %s into %s" % (ob.name, ", ".join(o.name for o in new)))
        return {"FINISHED"}


class TESSERA_OT_compare(_TesseraOperator, bpy.types.Operator):
    """Compare Tessera's exact limit surface with Blender's own subdivision (level 6) of the active object"""

    bl_idname = "tessera.compare"
    bl_label = "Compare with Blender's subdivision"

    # Blender's limit surface is exact only at its highest quality (the adaptive isolation level):
    # at its default of 3 a vertex crease of 0.8 (sharpness 6.4) is 3e-3 of the diagonal off the limit,
    # at 10 the cube with creases and a vertex crease agrees with Tessera's to 6e-8.
    quality: IntProperty(name="Quality", description="Blender's subdivision quality for the comparison (the "
                         "modifier's own is restored after)", default=10, min=1, max=10)

    def work(self, context, ob, tessera):
        directory, stem = _stem(context, ob, self.filepath, "_compare")
        report_path = bpy.path.abspath(self.filepath) if self.filepath else os.path.join(directory, stem + ".json")
        at, mod = cage_export.subsurf_modifier(ob)
        if mod is None:
            raise ValueError("%s has no Subdivision Surface modifier: nothing to compare" % ob.name)
        if mod.subdivision_type != "CATMULL_CLARK":
            raise ValueError("%s's Subdivision Surface modifier is Simple: Tessera's exact surface is "
                             "Catmull-Clark's; nothing to compare" % ob.name)
        export = _Export(context, ob, directory, stem)
        self.warn_all(context, export.warnings)
        ply = os.path.join(directory, stem + ".exact.ply")
        warnings, _ = run(tessera, ["tessellate", export.obj_path, "--scheme", "exact", "--factor", "64", "-o", ply])
        self.warn_all(context, warnings)
        positions = _blender_level6(context, ob, at, mod, self.quality)
        report = compare.compare(export.cage, positions, ply, export.cage.blender_vertex)
        report.update({"object": ob.name, "frame": context.scene.frame_current, "application": _application(),
                       "cage": export.obj_path, "use_limit_surface": mod.use_limit_surface,
                       "quality": self.quality, "modifier_quality": mod.quality})
        with open(report_path, "w") as f:
            json.dump(report, f, indent=2)
            f.write("\n")
        _settings(context).last_result = json.dumps(report)
        c, m = report["cage_vertices"], report["mesh"]
        text = ("%s against Blender's level 6: cage vertices max %.2e, mesh max %.2e of the diagonal (%s)" %
                (ob.name, c["max_relative"], m["max_relative"], report_path))
        if report["ok"]:
            self.say(context, "INFO", text)
        else:
            over = ["cage vertex %d: %.2e" % (o["vertex"], o["relative"]) for o in c["over"]]
            over += ["mesh vertex %d: %.2e" % (o["vertex"], o["relative"]) for o in m["over"]]
            hint = "" if mod.use_limit_surface else " (Use Limit Surface is off: Blender's vertices are not on the limit)"
            self.say(context, "WARNING", text + "; apart: " + ", ".join(over[:10]) + hint)
        return {"FINISHED"}


def _import_glb(path):
    """Blender's glTF importer. Debian's Blender 3.4.1 importer calls numpy.bool, which NumPy 1.24 (Debian
    bookworm's) removed: the alias it meant (the builtin bool) is restored for the import only."""
    import numpy

    missing = "bool" not in numpy.__dict__
    if missing:
        numpy.bool = bool
    try:
        bpy.ops.import_scene.gltf(filepath=path)
    finally:
        if missing:
            del numpy.bool


def _blender_level6(context, ob, at, mod, quality):
    """Blender's mesh of `ob` subdivided by `mod` at level 6 and `quality` (the modifiers after it off),
    Y-up world."""
    saved = [(m, m.show_viewport) for m in ob.modifiers[at + 1:]]
    levels, shown, own_quality = mod.levels, mod.show_viewport, mod.quality
    try:
        for m, _ in saved:
            m.show_viewport = False
        mod.levels, mod.show_viewport, mod.quality = 6, True, quality
        dg = context.evaluated_depsgraph_get()
        dg.update()
        ev = ob.evaluated_get(dg)
        me = ev.to_mesh()
        try:
            world = ob.matrix_world
            return [cage_export.to_y_up(world @ v.co) for v in me.vertices]
        finally:
            ev.to_mesh_clear()
    finally:
        mod.levels, mod.show_viewport, mod.quality = levels, shown, own_quality
        for m, s in saved:
            m.show_viewport = s
        context.evaluated_depsgraph_get().update()


def _show_image(context, image):
    """Shows `image` in an Image Editor of the current screen, if there is a screen (not in background)."""
    screen = getattr(context, "screen", None)
    if screen is None or bpy.app.background:
        return
    areas = [a for a in screen.areas if a.type == "IMAGE_EDITOR"]
    if not areas:
        try:
            bpy.ops.render.view_show("INVOKE_DEFAULT")
        except RuntimeError:
            return
        for window in context.window_manager.windows:
            areas += [a for a in window.screen.areas if a.type == "IMAGE_EDITOR"]
    for a in areas[:1]:
        a.spaces.active.image = image


classes = (TESSERA_OT_render, TESSERA_OT_tessellate, TESSERA_OT_compare)

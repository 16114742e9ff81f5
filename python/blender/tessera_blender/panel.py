"""The add-on's settings (per scene), preferences and its panel (Properties > Object, and the 3D
Viewport's sidebar)."""

import bpy
from bpy.props import EnumProperty, FloatProperty, IntProperty, StringProperty

SCHEMES = [
    ("exact", "Exact", "OpenSubdiv's limit surface"),
    ("gregory", "Gregory", "one Gregory ACC patch per face (the fast default)"),
    ("adaptive", "Adaptive", "OpenSubdiv's feature-adaptive patches"),
    ("bspline", "B-spline", "B-spline patches where regular, Gregory elsewhere"),
    ("acc", "ACC", "approximate Catmull-Clark (quads only)"),
    ("pn", "PN", "PN triangles and quads"),
    ("flat", "Flat", "the cage itself"),
]
VIEWS = [(v, v.replace("-", " ").capitalize(), "tessera render --view " + v) for v in
         ("shaded", "wireframe", "wire-on-shaded", "factors", "density", "patch-type", "combination", "patch-id",
          "normals", "uv", "cage", "cracks", "culled")]


class TesseraSettings(bpy.types.PropertyGroup):
    scheme: EnumProperty(name="Scheme", items=SCHEMES, default="exact")
    isolation: IntProperty(name="Isolation", description="adaptive: the isolation level", default=4, min=1, max=10)
    lod: EnumProperty(name="Factors", items=[("uniform", "Uniform", "one factor on every edge"),
                                             ("screen", "Screen", "each edge's projected size over Edge pixels")],
                      default="uniform")
    factor: FloatProperty(name="Factor", description="tessellation factor (uniform)", default=16.0, min=1.0, max=64.0)
    edge_pixels: FloatProperty(name="Edge pixels", description="screen: target pixels per segment", default=8.0,
                               min=0.5, max=256.0)
    view: EnumProperty(name="View", items=VIEWS, default="shaded")
    msaa: EnumProperty(name="MSAA", items=[(str(n), "%dx" % n, "%d samples per pixel" % n) for n in (1, 2, 4, 8, 16)],
                       default="1")
    output_dir: StringProperty(name="Output", description="where cages, scenes and images go (default: a "
                               "temporary directory)", subtype="DIR_PATH", default="")
    last_report: StringProperty(name="Last report", default="")
    last_result: StringProperty(name="Last result (JSON)", default="")


class TesseraPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__
    tessera_path: StringProperty(name="Tessera executable", description="the tessera command line (else $TESSERA, "
                                 "else PATH)", subtype="FILE_PATH", default="")

    def draw(self, context):
        self.layout.prop(self, "tessera_path")


class _TesseraPanel:
    bl_label = "Tessera"

    @classmethod
    def poll(cls, context):
        return context.active_object is not None and context.active_object.type == "MESH"

    def draw(self, context):
        s = context.scene.tessera
        col = self.layout.column()
        col.prop(s, "scheme")
        if s.scheme == "adaptive":
            col.prop(s, "isolation")
        col.prop(s, "lod")
        col.prop(s, "factor" if s.lod == "uniform" else "edge_pixels")
        col.prop(s, "view")
        col.prop(s, "msaa")
        col.prop(s, "output_dir")
        row = col.row(align=True)
        row.operator("tessera.render", icon="RENDER_STILL")
        row.operator("tessera.tessellate", icon="MESH_GRID")
        col.operator("tessera.compare", icon="ARROW_LEFTRIGHT")
        if s.last_report:
            box = col.box()
            for line in s.last_report.splitlines()[-6:]:
                box.label(text=line)


class TESSERA_PT_object(_TesseraPanel, bpy.types.Panel):
    """In Properties > Object."""

    bl_idname = "TESSERA_PT_object"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "object"


class TESSERA_PT_view3d(_TesseraPanel, bpy.types.Panel):
    """In the 3D Viewport's sidebar (N), tab Tessera."""

    bl_idname = "TESSERA_PT_view3d"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Tessera"


classes = (TesseraSettings, TesseraPreferences, TESSERA_PT_object, TESSERA_PT_view3d)

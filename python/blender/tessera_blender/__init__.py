"""Tessera inside Blender: render, tessellate and check the active object's subdivision surface.

Install: Edit > Preferences > Add-ons > Install..., the zip of this folder (README: "Blender add-on");
the panel is in Properties > Object > Tessera and the 3D Viewport's sidebar (N). Scripts: bpy.ops.tessera.render(filepath=...),
bpy.ops.tessera.tessellate(), bpy.ops.tessera.compare(filepath=...).
"""

bl_info = {
    "name": "Tessera",
    "author": "Tessera",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Object > Tessera; 3D Viewport > Sidebar > Tessera",
    "description": "Render, tessellate and compare the active object's subdivision surface with Tessera",
    "category": "Render",
}

import bpy  # noqa: E402

from . import operators, panel  # noqa: E402

_classes = panel.classes + operators.classes


def register():
    for c in _classes:
        bpy.utils.register_class(c)
    bpy.types.Scene.tessera = bpy.props.PointerProperty(type=panel.TesseraSettings)


def unregister():
    del bpy.types.Scene.tessera
    for c in reversed(_classes):
        bpy.utils.unregister_class(c)

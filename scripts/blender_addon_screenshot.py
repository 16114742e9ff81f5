"""The README's Blender add-on pictures: Blender's UI with the Tessera panel, the viewport and the
image tessera.render made, on the default cube creased (edges at 1.0 and 0.5, a vertex at 0.8).
Blender draws its UI only on a display: run under Xvfb by scripts/blender-addon-screenshot.sh."""
import math
import os
import sys

ROOT, TESSERA, OUT = sys.argv[sys.argv.index("--") + 1:][:3]
sys.path.insert(0, os.path.join(ROOT, "python", "blender"))
import bpy, bmesh
import tessera_blender
tessera_blender.register()
os.environ["TESSERA"] = TESSERA
ob = bpy.data.objects["Cube"]
for i, e in enumerate(ob.data.edges):
    e.crease = (1.0, 0.5, 0.0)[i % 3]
bm = bmesh.new(); bm.from_mesh(ob.data); cl = bm.verts.layers.crease.verify(); bm.verts.ensure_lookup_table(); bm.verts[0][cl] = 0.8; bm.to_mesh(ob.data); bm.free()
ob.modifiers.new("Subdivision", "SUBSURF").levels = 3
sc = bpy.context.scene
sc.tessera.output_dir = OUT
sc.tessera.view = "wire-on-shaded"
sc.tessera.factor = 12
sc.render.resolution_x, sc.render.resolution_y = 800, 600
bpy.context.view_layer.objects.active = ob
ob.select_set(True)
W = lambda: bpy.context.window_manager.windows[0]

def guard(f):
    def g():
        try:
            return f()
        except Exception as e:
            import traceback; traceback.print_exc()
            bpy.ops.wm.quit_blender()
    return g

@guard
def step1():
    win = W(); screen = win.screen
    view = [a for a in screen.areas if a.type == "VIEW_3D"][0]
    with bpy.context.temp_override(window=win, screen=screen, area=view):
        bpy.ops.screen.area_split(direction="VERTICAL", factor=0.27)
    bpy.app.timers.register(step2, first_interval=0.5)

@guard
def step2():
    win = W(); screen = win.screen
    views = sorted([a for a in screen.areas if a.type == "VIEW_3D"], key=lambda a: a.x)
    views[0].type = "PROPERTIES"
    with bpy.context.temp_override(window=win, screen=screen, area=views[1]):
        bpy.ops.screen.area_split(direction="VERTICAL", factor=0.5)
    bpy.app.timers.register(step3, first_interval=0.5)

@guard
def step3():
    win = W(); screen = win.screen
    with bpy.context.temp_override(window=win, screen=screen):
        bpy.ops.tessera.render(filepath=os.path.join(OUT, "blender-addon-render.png"))
    img = bpy.data.images.load(os.path.join(OUT, "blender-addon-render.png"), check_existing=True)
    views = sorted([a for a in screen.areas if a.type == "VIEW_3D"], key=lambda a: a.x)
    views[-1].type = "IMAGE_EDITOR"
    views[-1].spaces.active.image = img
    for a in screen.areas:
        if a.type == "PROPERTIES" and a.x < 50:
            a.spaces.active.context = "OBJECT"
        if a.type == "VIEW_3D":
            a.spaces.active.region_3d.view_distance = 8.0
    bpy.app.timers.register(step4, first_interval=1.0)

@guard
def step4():
    win = W()
    for a in win.screen.areas:
        if a.type == "IMAGE_EDITOR":
            for r in a.regions:
                if r.type == "WINDOW":
                    with bpy.context.temp_override(window=win, area=a, region=r):
                        bpy.ops.image.view_all(fit_view=True)
    bpy.app.timers.register(save, first_interval=1.0)

@guard
def save():
    win = W()
    with bpy.context.temp_override(window=win, screen=win.screen):
        bpy.ops.screen.screenshot(filepath=os.path.join(OUT, "blender-addon.png"))
    bpy.ops.wm.quit_blender()

bpy.app.timers.register(step1, first_interval=2.0)

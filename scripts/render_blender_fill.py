# SPDX-License-Identifier: AGPL-3.0-or-later
"""Renders docs/blender-fill-holes.png: a mesh before and after the add-on's
mesh.dot_fill_holes, in Blender, headless (Workbench engine, software GL).

    blender -b --factory-startup --python scripts/render_blender_fill.py -- \\
        [--server build/server/dot-server] \\
        [--addon-zip build/client/blender/dot_blender_addon.zip] \\
        [--output docs/blender-fill-holes.png]

The add-on is loaded from the zip the build made (unpacked into a
temporary script directory, so the user's Blender setup is not touched);
dot-server runs on a free 127.0.0.1 port while the script works. Left: a
bumpy sphere with four holes cut out; right: the same after Fill Holes
(stage fair), the new faces in orange.
"""
import argparse
import math
import os
import socket
import subprocess
import sys
import tempfile
import time
import zipfile

import addon_utils
import bmesh
import bpy
from mathutils import Vector

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
ap = argparse.ArgumentParser()
ap.add_argument("--server", default=os.path.join(ROOT, "build/server/dot-server"))
ap.add_argument("--addon-zip", default=os.path.join(
    ROOT, "build/client/blender/dot_blender_addon.zip"))
ap.add_argument("--output", default=os.path.join(ROOT, "docs/blender-fill-holes.png"))
args = ap.parse_args(argv)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def enable_addon():
    scripts = tempfile.mkdtemp(prefix="dot-render-")
    with zipfile.ZipFile(args.addon_zip) as z:
        z.extractall(os.path.join(scripts, "addons"))
    bpy.context.preferences.filepaths.script_directory = scripts
    bpy.utils.refresh_script_paths()  # puts its addons/ on sys.path
    addon_utils.modules(refresh=True)
    assert addon_utils.enable("dot", default_set=True), "add-on not enabled"


def bumpy_sphere():
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=5, radius=1)
    obj = bpy.context.active_object
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    for v in bm.verts:
        p = v.co
        v.co = p * (1 + 0.12 * math.sin(4 * p.x) * math.sin(3 * p.y + 1)
                    + 0.08 * math.sin(5 * p.z + 2 * p.x))
    holes = [(Vector((0.35, -0.75, 0.45)), 0.32), (Vector((-0.6, -0.7, -0.1)), 0.22),
             (Vector((0.8, -0.45, -0.35)), 0.18), (Vector((-0.1, -0.45, 0.9)), 0.25)]
    doomed = [f for f in bm.faces if any(
        (f.calc_center_median() - c).length < r for c, r in holes)]
    bmesh.ops.delete(bm, geom=doomed, context='FACES')
    bm.to_mesh(obj.data)
    bm.free()
    for p in obj.data.polygons:
        p.use_smooth = True
    return obj


def material(name, color):
    m = bpy.data.materials.new(name)
    m.diffuse_color = (*color, 1)
    return m


def main():
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    enable_addon()
    address = f"127.0.0.1:{free_port()}"
    server = subprocess.Popen([args.server, "--listen", address,
                               "--metrics-port", "0", "--log-level", "warn"])
    try:
        prefs = bpy.context.preferences.addons["dot"].preferences
        prefs.server_address = address
        for _ in range(600):  # until the port accepts (at most 30 s)
            try:
                socket.create_connection(("127.0.0.1", int(address.split(":")[1])),
                                         timeout=1).close()
                break
            except OSError:
                time.sleep(0.05)
        before = bumpy_sphere()
        before.name = "before"
        before.data.materials.append(material("surface", (0.62, 0.66, 0.72)))
        before.data.materials.append(material("patch", (0.95, 0.5, 0.15)))
        after = before.copy()
        after.data = before.data.copy()
        after.name = "after"
        bpy.context.scene.collection.objects.link(after)
        faces_before = len(after.data.polygons)
        for o in bpy.context.view_layer.objects:
            o.select_set(False)
        after.select_set(True)
        bpy.context.view_layer.objects.active = after
        result = bpy.ops.mesh.dot_fill_holes(stage='FAIR')
        assert result == {'FINISHED'}, result
        for p in after.data.polygons[faces_before:]:
            p.material_index = 1
            p.use_smooth = True
        before.location.x, after.location.x = -1.25, 1.25
    finally:
        server.terminate()
        server.wait(timeout=30)

    scene = bpy.context.scene
    scene.render.engine = 'BLENDER_WORKBENCH'
    shading = scene.display.shading
    shading.light = 'STUDIO'
    shading.color_type = 'MATERIAL'
    shading.show_cavity = True
    shading.show_backface_culling = False
    scene.display.render_aa = '8'
    scene.render.resolution_x, scene.render.resolution_y = 960, 440
    scene.render.film_transparent = False
    scene.world = scene.world or bpy.data.worlds.new("world")
    scene.world.color = (1, 1, 1)
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    camera.data.type = 'ORTHO'
    camera.data.ortho_scale = 5.0
    camera.location = (0, -8, 1.2)
    camera.rotation_euler = (math.radians(82), 0, 0)
    scene.camera = camera
    scene.render.image_settings.file_format = 'PNG'
    scene.render.image_settings.color_mode = 'RGB'
    scene.render.image_settings.compression = 100
    scene.render.filepath = args.output
    bpy.ops.render.render(write_still=True)
    print(f"wrote {args.output} ({os.path.getsize(args.output)} bytes)")


main()

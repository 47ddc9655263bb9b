# SPDX-License-Identifier: AGPL-3.0-or-later
"""The `dot` Blender add-on, headless, against a real dot-server on
loopback.

    blender -b --factory-startup --python-exit-code 1 \\
        --python tests/blender/test_addon.py -- \\
        --server build/server/dot-server \\
        --addon-zip build/client/blender/dot_blender_addon.zip

Installs the add-on from the zip the build made (into BLENDER_USER_SCRIPTS
when set: ctest points it into the build tree), starts dot-server on a free
127.0.0.1 port, builds meshes with holes, selected boundary loops and
curves, runs each operator and checks the geometry with bmesh: closed where
filled and open exactly where not asked, edge-manifold, faces wound like
their neighbours, no duplicate vertices, no intersecting faces. Any
failure raises, so Blender exits 1.
"""
import argparse
import dataclasses
import math
import os
import socket
import subprocess
import sys
import time
import traceback

import addon_utils
import bmesh
import bpy
from mathutils import Vector
from mathutils.bvhtree import BVHTree
from mathutils.kdtree import KDTree

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
ap = argparse.ArgumentParser()
ap.add_argument("--server", required=True)
ap.add_argument("--addon-zip", required=True)
ARGS = ap.parse_args(argv)

# The Python client tests' meshes (numpy only).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                os.pardir, "python"))
import shapes  # noqa: E402


# -- harness -----------------------------------------------------------------

def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server():
    address = f"127.0.0.1:{free_port()}"
    process = subprocess.Popen(
        [ARGS.server, "--listen", address, "--metrics-port", "0",
         "--log-level", "error", "--drain-seconds", "1", "--threads", "2"],
        stdout=subprocess.DEVNULL)
    deadline = time.monotonic() + 30
    while True:  # until the port accepts (at most 30 s)
        try:
            with socket.create_connection(("127.0.0.1", int(address.split(":")[1])),
                                          timeout=1):
                return process, address
        except OSError:
            if process.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError("dot-server did not start")
            time.sleep(0.05)


def prefs():
    return bpy.context.preferences.addons["dot"].preferences


def clear_scene():
    if bpy.context.object and bpy.context.object.mode != 'OBJECT':
        bpy.ops.object.mode_set(mode='OBJECT')
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    for m in list(bpy.data.meshes):
        bpy.data.meshes.remove(m)
    for c in list(bpy.data.curves):
        bpy.data.curves.remove(c)


def activate(obj):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def object_bmesh(obj):
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    return bm


def check_mesh(obj, boundary_edges=0):
    """Edge-manifold, consistently wound, no duplicate vertices, no
    degenerate or intersecting faces; `boundary_edges` left open."""
    bm = object_bmesh(obj)
    try:
        boundary = sum(1 for e in bm.edges if e.is_boundary)
        assert boundary == boundary_edges, \
            f"{boundary} boundary edges, expected {boundary_edges}"
        assert not [e for e in bm.edges if len(e.link_faces) > 2], \
            "an edge of more than two faces"
        assert not [e for e in bm.edges if not e.link_faces], "a loose edge"
        flipped = [e for e in bm.edges
                   if len(e.link_faces) == 2 and not e.is_contiguous]
        assert not flipped, f"{len(flipped)} edges between faces wound apart"
        kd = KDTree(len(bm.verts))
        for v in bm.verts:
            kd.insert(v.co, v.index)
        kd.balance()
        dup = [v.index for v in bm.verts if len(kd.find_range(v.co, 1e-9)) > 1]
        assert not dup, f"duplicate vertices {dup[:5]}"
        assert min(f.calc_area() for f in bm.faces) > 1e-12, "a degenerate face"
        tree = BVHTree.FromBMesh(bm)
        overlaps = tree.overlap(tree)
        assert not overlaps, f"intersecting faces {overlaps[:5]}"
        return len(bm.verts), len(bm.faces)
    finally:
        bm.free()


def counts(obj):
    bm = object_bmesh(obj)
    try:
        return (len(bm.verts), len(bm.faces),
                sum(1 for e in bm.edges if e.is_boundary))
    finally:
        bm.free()


def delete_faces(obj, where):
    bm = object_bmesh(obj)
    doomed = [f for f in bm.faces if where(f.calc_center_median())]
    bmesh.ops.delete(bm, geom=doomed, context='FACES')
    bm.to_mesh(obj.data)
    bm.free()
    return len(doomed)


def select_boundary_edges(obj, where):
    """Edit Mode: exactly the boundary edges whose midpoint satisfies
    `where` selected."""
    bm = bmesh.from_edit_mesh(obj.data)
    for f in bm.faces:
        f.select_set(False)
    for e in bm.edges:
        e.select_set(False)
    for v in bm.verts:
        v.select_set(False)
    bm.select_mode = {'EDGE'}
    for e in bm.edges:
        if e.is_boundary and where((e.verts[0].co + e.verts[1].co) / 2):
            e.select_set(True)
    bm.select_flush_mode()
    bmesh.update_edit_mesh(obj.data)


def boundary_midpoints(obj):
    """The midpoints of the open border's edges, rounded: which holes are
    open, comparable before and after a fill (the rims' vertices keep their
    coordinates)."""
    bm = object_bmesh(obj)
    try:
        return sorted(tuple(round(c, 9) for c in (e.verts[0].co + e.verts[1].co) / 2)
                      for e in bm.edges if e.is_boundary)
    finally:
        bm.free()


class Recording:
    """Records the calls the add-on makes of one method of its client
    (arguments and answer), to check what the server was asked."""

    def __init__(self, method):
        import dot
        self.client = dot.connection.client(prefs())
        self.method = method
        self.calls = []

    def __enter__(self):
        real = getattr(self.client, self.method)

        def record(*args, **kwargs):
            answer = real(*args, **kwargs)
            self.calls.append((args, kwargs, answer))
            return answer
        setattr(self.client, self.method, record)
        return self

    def __exit__(self, *exc):
        delattr(self.client, self.method)  # the class's method again


def expect_report(call, *words):
    """The operator must fail with a Blender report (RuntimeError from
    bpy.ops), never a Python traceback."""
    try:
        call()
    except RuntimeError as e:
        text = str(e)
        assert "Traceback" not in text, text
        for w in words:
            assert w in text, f"{w!r} not in {text!r}"
        return text
    raise AssertionError(f"no error report; expected {words}")


def cyclic_poly_curve(name, points):
    """A curve object of one cyclic POLY spline through `points`, linked
    and active."""
    data = bpy.data.curves.new(name, 'CURVE')
    data.dimensions = '3D'
    spline = data.splines.new('POLY')
    spline.points.add(len(points) - 1)
    for point, co in zip(spline.points, points):
        point.co = (*co, 1)
    spline.use_cyclic_u = True
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    activate(obj)
    return obj


def mesh_object(name, vertices, edges=(), faces=()):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(v) for v in vertices], list(edges), list(faces))
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    activate(obj)
    return obj


def protected_polygon():
    """10 random vertices (the Python tests' polygon): DOT splits 4 of its
    edges when asked to protect them."""
    import numpy as np
    rng = np.random.default_rng(1)
    return np.round(rng.uniform(-1, 1, (10, 3)), 2)


# -- tests ---------------------------------------------------------------

def test_operators_are_registered_with_one_undo_step():
    for idname in ("dot_fill_loops", "dot_triangulate_loops", "dot_fill_holes",
                   "dot_triangulate_curve", "dot_surface_curves"):
        cls = getattr(bpy.types, "MESH_OT_" + idname)
        assert {'REGISTER', 'UNDO'} <= set(cls.bl_options), idname
        assert hasattr(bpy.ops.mesh, idname)
    import dot
    assert "vendor" in dot.connection.dot_client.__name__, \
        "the add-on must use its vendored dot_client"


def test_fill_holes_object_mode():
    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12)
    sphere = bpy.context.active_object
    removed = delete_faces(sphere, lambda c: c.z > 0.85)  # around the pole
    removed += delete_faces(sphere, lambda c: c.x > 0.75 and abs(c.z) < 0.3)
    v0, f0, b0 = counts(sphere)
    assert removed > 0 and b0 > 0
    assert bpy.ops.mesh.dot_fill_holes() == {'FINISHED'}
    v1, f1 = check_mesh(sphere, boundary_edges=0)
    assert v1 > v0, "the fair stage adds vertices"
    assert f1 > f0


def test_fill_holes_gives_new_faces_uvs_and_colours():
    """New faces take their UVs and colours from their neighbours (blended
    from the hole's rim by the server): no face collapses to a point in UV
    space, and a colour that follows the position keeps following it."""
    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16)
    sphere = bpy.context.active_object
    mesh = sphere.data
    colour = mesh.color_attributes.new("Col", 'FLOAT_COLOR', 'CORNER')
    for loop in mesh.loops:
        co = mesh.vertices[loop.vertex_index].co
        colour.data[loop.index].color = (0.5 + 0.5 * co.x, 0.5 + 0.5 * co.y,
                                         0.5 + 0.5 * co.z, 1.0)
    # A hole away from the UV map's seam and poles.
    removed = delete_faces(sphere, lambda c: c.y < -0.7 and abs(c.z) < 0.35)
    assert removed > 0
    before = {f.index for f in sphere.data.polygons}
    assert bpy.ops.mesh.dot_fill_holes() == {'FINISHED'}
    check_mesh(sphere, boundary_edges=0)
    bm = object_bmesh(sphere)
    try:
        uv = bm.loops.layers.uv.active
        col = bm.loops.layers.float_color["Col"]
        rim = [l[uv].uv.copy() for e in bm.edges for f in e.link_faces
               for l in f.loops if f.index in before]
        new = [f for f in bm.faces if f.calc_center_median().y < -0.6 and
               abs(f.calc_center_median().z) < 0.35 and len(f.verts) == 3]
        assert len(new) > 10, len(new)
        lo = [min(p[k] for p in rim) for k in (0, 1)]
        hi = [max(p[k] for p in rim) for k in (0, 1)]
        flat = 0
        for f in new:
            a, b, c = (l[uv].uv for l in f.loops)
            area = abs((b - a).cross(c - a)) / 2
            flat += area < 1e-7
            for p in (a, b, c):
                assert lo[0] - 1e-5 <= p.x <= hi[0] + 1e-5 and \
                    lo[1] - 1e-5 <= p.y <= hi[1] + 1e-5, (p, lo, hi)
            for l in f.loops:
                want = [0.5 + 0.5 * x for x in l.vert.co]
                got = l[col][:3]
                assert max(abs(g - w) for g, w in zip(got, want)) < 0.1, \
                    (got, want)
        assert flat == 0, f"{flat} of {len(new)} new faces are flat in UV"
    finally:
        bm.free()


def test_select_holes_selects_the_rims_fill_holes_would_fill():
    """The listing (FillHoles dry run): nothing filled, exactly the rims of
    the holes within the limits selected, their count and sizes reported."""
    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12)
    sphere = bpy.context.active_object
    delete_faces(sphere, lambda c: c.z > 0.85)  # a 24-edge hole at the pole
    delete_faces(sphere, lambda c: c.x > 0.9 and abs(c.z) < 0.2)  # small
    v0, f0, b0 = counts(sphere)
    bpy.ops.object.mode_set(mode='EDIT')
    try:
        with Recording("list_holes") as listing:
            assert bpy.ops.mesh.dot_select_holes(max_hole_edges=12) \
                == {'FINISHED'}
        ((_, kwargs, report),) = listing.calls
        assert report.loops == 2 and report.skipped == 1, report
        bm = bmesh.from_edit_mesh(sphere.data)
        chosen = [e for e in bm.edges if e.select]
        assert chosen and len(chosen) < b0
        assert all(e.is_boundary and e.verts[0].co.x > 0.8 for e in chosen)
        assert bpy.ops.mesh.dot_select_holes() == {'FINISHED'}
        bm = bmesh.from_edit_mesh(sphere.data)
        assert sum(e.select for e in bm.edges) == b0
        assert all(e.is_boundary for e in bm.edges if e.select)
    finally:
        bpy.ops.object.mode_set(mode='OBJECT')
    assert counts(sphere) == (v0, f0, b0), "nothing was filled"


def test_fill_holes_fills_every_selected_mesh():
    """Object Mode with several meshes selected: each one's holes are
    filled, one FillHoles call after another over the one connection."""
    clear_scene()
    spheres = []
    for x in (-3.0, 3.0):
        bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8,
                                             location=(x, 0, 0))
        sphere = bpy.context.active_object
        delete_faces(sphere, lambda c: c.z > 0.8)
        spheres.append(sphere)
    activate(spheres[0])
    for o in spheres:
        o.select_set(True)
    assert all(counts(o)[2] > 0 for o in spheres)
    with Recording("fill_patches") as fills:
        assert bpy.ops.mesh.dot_fill_holes() == {'FINISHED'}
    assert len(fills.calls) == 2
    for o in spheres:
        check_mesh(o, boundary_edges=0)


def test_fill_holes_merges_split_vertices_first():
    """A mesh imported with split vertices (OBJ/STL exporters write seams
    twice): before, the add-on sent it as it was and holes through a seam
    failed ("vertex 15 repeats vertex 2"); dotctl, which repairs, filled
    them all."""
    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12)
    sphere = bpy.context.active_object
    delete_faces(sphere, lambda c: c.z > 0.85)
    delete_faces(sphere, lambda c: c.x > 0.75 and abs(c.z) < 0.3)
    bm = object_bmesh(sphere)
    seam = [e for e in bm.edges
            if abs(e.verts[0].co.y) < 1e-6 and abs(e.verts[1].co.y) < 1e-6
            and e.verts[0].co.x < 0 and not e.is_boundary]
    bmesh.ops.split_edges(bm, edges=seam)  # coincident vertices along y=0
    bm.to_mesh(sphere.data)
    bm.free()
    v0, _, b0 = counts(sphere)
    assert seam and b0 > 0
    assert bpy.ops.mesh.dot_fill_holes() == {'FINISHED'}
    v1, _ = check_mesh(sphere, boundary_edges=0)  # the seam merged, holes filled


def test_fill_holes_edit_mode_options():
    clear_scene()
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=20, y_subdivisions=20,
                                    size=2)
    grid = bpy.context.active_object
    delete_faces(grid, lambda c: abs(c.x) < 0.3 and abs(c.y) < 0.3)
    v0, f0, b0 = counts(grid)
    bpy.ops.object.mode_set(mode='EDIT')
    # Too small a limit: nothing to fill, nothing changed.
    assert bpy.ops.mesh.dot_fill_holes(max_hole_edges=4, skip_longest=True) \
        == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    assert counts(grid) == (v0, f0, b0)
    bpy.ops.object.mode_set(mode='EDIT')
    assert bpy.ops.mesh.dot_fill_holes(stage='TRIANGULATE', skip_longest=True,
                                       preset='MINIMAL_AREA') == {'FINISHED'}
    bm = bmesh.from_edit_mesh(grid.data)
    selected = sum(1 for f in bm.faces if f.select)
    bpy.ops.object.mode_set(mode='OBJECT')
    v1, f1 = check_mesh(grid, boundary_edges=4 * 20)  # the rim stays open
    assert v1 == v0, "the triangulate stage adds no vertex"
    assert selected == f1 - f0 > 0, "the new faces are selected"


def test_fill_loops_presets_and_stages():
    clear_scene()
    bpy.ops.mesh.primitive_cylinder_add(vertices=24, end_fill_type='NOTHING')
    cyl = bpy.context.active_object
    v0, f0, b0 = counts(cyl)
    assert b0 == 48
    bpy.ops.object.mode_set(mode='EDIT')
    select_boundary_edges(cyl, lambda c: c.z > 0)
    assert bpy.ops.mesh.dot_fill_loops(preset='MINIMAL_AREA') == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    v1, f1 = check_mesh(cyl, boundary_edges=24)
    assert (v1, f1) == (v0, f0 + 22)
    bpy.ops.object.mode_set(mode='EDIT')
    select_boundary_edges(cyl, lambda c: c.z < 0)
    assert bpy.ops.mesh.dot_fill_loops(preset='SMOOTH', stage='FAIR') \
        == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    v2, f2 = check_mesh(cyl, boundary_edges=0)
    assert v2 >= v1 and f2 > f1


def test_fill_loops_follow_normals_and_triangulate_custom_weights():
    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8)
    sphere = bpy.context.active_object
    delete_faces(sphere, lambda c: c.z > 0.5)
    delete_faces(sphere, lambda c: c.z < -0.5)
    bpy.ops.object.mode_set(mode='EDIT')
    select_boundary_edges(sphere, lambda c: c.z > 0)
    assert bpy.ops.mesh.dot_fill_loops(preset='FOLLOW_NORMALS') == {'FINISHED'}
    select_boundary_edges(sphere, lambda c: c.z < 0)
    assert bpy.ops.mesh.dot_triangulate_loops(
        preset='CUSTOM', area=1, squared_dihedral=0.5, search_space='DELAUNAY') \
        == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    check_mesh(sphere, boundary_edges=0)


def test_triangulate_loops_one_surface_bridges_two_rims():
    """A sphere's band (both caps removed): its two rims joined into one
    tube through the inside, wound like the band, closing it into a
    torus (Euler characteristic 0, no boundary left)."""
    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8)
    sphere = bpy.context.active_object
    delete_faces(sphere, lambda c: c.z > 0.5)
    delete_faces(sphere, lambda c: c.z < -0.5)
    v0, f0, b0 = counts(sphere)
    bpy.ops.object.mode_set(mode='EDIT')
    select_boundary_edges(sphere, lambda c: True)
    assert bpy.ops.mesh.dot_triangulate_loops(one_surface=True) \
        == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    v1, f1 = check_mesh(sphere, boundary_edges=0)
    assert v1 == v0 and f1 == f0 + b0  # an annulus: a face per rim edge
    bm = object_bmesh(sphere)
    try:
        assert len(bm.verts) - len(bm.edges) + len(bm.faces) == 0
    finally:
        bm.free()

    # Three loops into one surface (bridges first): the top, +x and -x
    # holes joined by one surface through the inside; the +y hole stays.
    sphere = sphere_with_four_holes()
    bm = object_bmesh(sphere)
    try:
        open_y = sum(1 for e in bm.edges if e.is_boundary and
                     (e.verts[0].co + e.verts[1].co).y / 2 > 0.8)
    finally:
        bm.free()
    bpy.ops.object.mode_set(mode='EDIT')
    select_boundary_edges(sphere, lambda c: c.z > 0.8 or abs(c.x) > 0.8)
    assert bpy.ops.mesh.dot_triangulate_loops(one_surface=True) \
        == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    check_mesh(sphere, boundary_edges=open_y)
    bm = object_bmesh(sphere)
    try:
        # A sphere with four holes (-2) and a surface of three (-1), glued.
        assert len(bm.verts) - len(bm.edges) + len(bm.faces) == -3
    finally:
        bm.free()

    # One loop is not several: refused by name, nothing changed.
    sphere = sphere_with_four_holes()
    bpy.ops.object.mode_set(mode='EDIT')
    select_boundary_edges(sphere, lambda c: c.z > 0.8)
    expect_report(lambda: bpy.ops.mesh.dot_triangulate_loops(one_surface=True),
                  "One Surface joins two or more loops; 1 is selected")
    bpy.ops.object.mode_set(mode='OBJECT')


def sphere_with_four_holes():
    """A UV sphere with four holes: at the top, and around +x, -x and +y
    on the equator."""
    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16)
    sphere = bpy.context.active_object
    delete_faces(sphere, lambda c: c.z > 0.9)
    delete_faces(sphere, lambda c: c.x > 0.85)
    delete_faces(sphere, lambda c: c.x < -0.85)
    delete_faces(sphere, lambda c: c.y > 0.85)
    return sphere


def test_fill_loops_fills_exactly_the_selected_loops():
    """Two of four holes selected: at every stage exactly those two are
    closed (FillHoles with loops_through, answered with patches), the
    other two stay open as they were."""
    chosen = lambda c: c.z > 0.8 or c.x > 0.8  # noqa: E731
    for stage in ('TRIANGULATE', 'REFINE', 'FAIR'):
        sphere = sphere_with_four_holes()
        v0, f0, b0 = counts(sphere)
        before = boundary_midpoints(sphere)
        left = [m for m in before if not chosen(Vector(m))]
        assert len(left) < len(before) and left, (len(left), len(before))
        bpy.ops.object.mode_set(mode='EDIT')
        select_boundary_edges(sphere, chosen)
        with Recording("fill_patches") as fills:
            assert bpy.ops.mesh.dot_fill_loops(stage=stage) == {'FINISHED'}
        # The server was asked for the two loops alone, one vertex each,
        # and filled just those.
        ((_, kwargs, answer),) = fills.calls
        options = kwargs["options"]
        assert len(options.loops_through) == 2, options
        assert options.stage == stage.lower() and options.no_repair
        assert (answer.report.loops, answer.report.filled,
                answer.report.skipped) == (4, 2, 2), stage
        assert len(answer.patches) == 2
        bm = bmesh.from_edit_mesh(sphere.data)
        selected = sum(1 for f in bm.faces if f.select)
        bpy.ops.object.mode_set(mode='OBJECT')
        v1, f1 = check_mesh(sphere, boundary_edges=len(left))
        assert boundary_midpoints(sphere) == left, stage
        assert selected == f1 - f0 > 0, (stage, selected, f1 - f0)
        if stage == 'TRIANGULATE':
            assert v1 == v0, "the triangulate stage adds no vertex"
        else:
            assert v1 > v0, stage


def test_fill_loops_names_a_loop_by_a_vertex_of_its_own():
    """Two holes touching at a corner: the corner is on both loops, so the
    add-on names the selected loop by another of its vertices, and the
    server fills that hole alone."""
    clear_scene()
    v, f = shapes.grid_with_holes(10, [(2, 4, 2, 4), (4, 6, 4, 6)])
    grid = mesh_object("pinched", [tuple(p) for p in v],
                       faces=[tuple(int(i) for i in t) for t in f])
    in_a = lambda c: 1.9 < c.x < 4.1 and 1.9 < c.y < 4.1  # noqa: E731
    left = [m for m in boundary_midpoints(grid) if not in_a(Vector(m))]
    bpy.ops.object.mode_set(mode='EDIT')
    select_boundary_edges(grid, in_a)
    with Recording("fill_patches") as fills:
        assert bpy.ops.mesh.dot_fill_loops(stage='REFINE') == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    ((_, kwargs, answer),) = fills.calls
    (named,) = kwargs["options"].loops_through
    assert named != 4 * 10 + 4, "the shared corner names both loops"
    assert answer.report.filled == 1
    assert [h.pinched for h in answer.report.holes].count(True) == 2
    assert boundary_midpoints(grid) == left
    # The add-on keeps only patches of selected loops, whatever comes back.
    import dot
    from dot import geometry
    hole = dot.connection.dot_client.HolePatch
    import numpy as np
    on_a = hole(0, 100, np.zeros((0, 3)), np.array([[22, 23, 32]], np.int32))
    on_b = hole(1, 100, np.zeros((0, 3)), np.array([[44, 45, 54]], np.int32))
    loop_a = [22, 23, 24, 34, 44, 43, 42, 32]
    assert geometry.patches_of_loops([on_a, on_b], [loop_a], 100) == ([on_a], 1)


def bumpy_grid(quads=False):
    """tests/python/shapes.bumpy_grid_with_hole as a Blender mesh, in
    triangles or in quads (two triangles per cell): its hole needs edge
    protection, which splits a face beside it."""
    v, f = shapes.bumpy_grid_with_hole()
    faces = [tuple(int(i) for i in t) for t in f]
    if quads:  # (a, a+1, a+n+1) and (a, a+n+1, a+n) make the cell's quad
        half = len(faces) // 2
        faces = [(a, b, c, faces[half + k][2])
                 for k, (a, b, c) in enumerate(faces[:half])]
    return mesh_object("bumpy", [tuple(p) for p in v], faces=faces)


def test_fill_loops_rebuilds_the_faces_edge_protection_splits():
    for quads in (False, True):
        for stage in ('TRIANGULATE', 'FAIR'):
            clear_scene()
            grid = bumpy_grid(quads)
            v0, f0, b0 = counts(grid)
            assert (v0, b0) == (100, 36 + 16)
            bpy.ops.object.mode_set(mode='EDIT')
            select_boundary_edges(  # the hole, not the rim
                grid, lambda c: 0.5 < c.x < 8.5 and 0.5 < c.y < 8.5)
            assert bpy.ops.mesh.dot_fill_loops(stage=stage) == {'FINISHED'}
            bpy.ops.object.mode_set(mode='OBJECT')
            v1, f1 = check_mesh(grid, boundary_edges=36)  # the rim stays
            what = f"quads={quads} {stage}"
            if stage == 'TRIANGULATE':
                # One vertex inserted on a boundary edge, shared by the patch
                # and the face across, which was rebuilt around it.
                assert v1 == 101, what
            else:
                assert v1 > 101, what
            bm = object_bmesh(grid)
            try:
                bm.verts.ensure_lookup_table()
                inserted = bm.verts[100]
                assert len(inserted.link_faces) >= 3, what
                assert not inserted.is_boundary, what
            finally:
                bm.free()


def test_fill_loops_reports_what_it_cannot_fill():
    clear_scene()
    p = protected_polygon()
    n = len(p)
    # A fan from a far apex: every patch over its rim crosses the fan.
    cone = mesh_object("cone", list(map(tuple, p)) + [(0.0, 0.0, 6.0)],
                       faces=[(n, (i + 1) % n, i) for i in range(n)])
    before = counts(cone)
    bpy.ops.object.mode_set(mode='EDIT')
    select_boundary_edges(cone, lambda c: True)
    expect_report(lambda: bpy.ops.mesh.dot_fill_loops(), "nothing was filled",
                  "failed", "intersects")
    bpy.ops.object.mode_set(mode='OBJECT')
    assert counts(cone) == before
    # Loose edges are no hole: Triangulate Loops is the operator for them.
    wire = mesh_object("wire", list(map(tuple, p)),
                       edges=[(i, (i + 1) % n) for i in range(n)])
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    expect_report(lambda: bpy.ops.mesh.dot_fill_loops(),
                  "use Triangulate Loops (DOT)")
    bpy.ops.object.mode_set(mode='OBJECT')
    assert counts(wire) == (n, 0, 0)


def test_triangulate_loops_protect_edges_splits_the_neighbours():
    clear_scene()
    p = protected_polygon()
    n = len(p)
    apex = (0.0, 0.0, 6.0)
    # A fan from a far apex: its open rim is the polygon.
    cone = mesh_object("cone", list(map(tuple, p)) + [apex],
                       faces=[(n, (i + 1) % n, i) for i in range(n)])
    bpy.ops.object.mode_set(mode='EDIT')
    select_boundary_edges(cone, lambda c: True)
    expect_report(lambda: bpy.ops.mesh.dot_triangulate_loops(
        preset='MINIMAL_AREA', search_space='DELAUNAY'), "no triangulation")
    assert bpy.ops.mesh.dot_triangulate_loops(
        preset='MINIMAL_AREA', search_space='DELAUNAY', protect_edges=True) \
        == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    bm = object_bmesh(cone)
    try:
        assert len(bm.verts) == n + 1 + 4, len(bm.verts)
        assert not [e for e in bm.edges if e.is_boundary or e.is_wire]
        assert not [e for e in bm.edges if len(e.link_faces) != 2]
        assert all(e.is_contiguous for e in bm.edges)
        # Fan faces beside the split edges took the inserted vertices (DOT
        # split two edges: one once, one three times).
        assert sum(len(f.verts) - 3 for f in bm.faces) == 4
        assert sorted(len(f.verts) for f in bm.faces)[-2:] == [4, 6]
    finally:
        bm.free()
    # Two loops of loose edges joined into one surface, with edge
    # protection splitting both loops' closing edges (and the second loop
    # reversed by the solver): every split lands on its own loop.
    q = [(x + 0.3, y + 0.2, z + 3.0) for x, y, z in reversed(list(map(tuple, p)))]
    tube = mesh_object("tube", list(map(tuple, p)) + q,
                       edges=[(i, (i + 1) % n) for i in range(n)] +
                       [(n + i, n + (i + 1) % n) for i in range(n)])
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    assert bpy.ops.mesh.dot_triangulate_loops(
        preset='MINIMAL_AREA', search_space='DELAUNAY', protect_edges=True,
        one_surface=True) == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    v, f = check_mesh(tube, boundary_edges=len(tube.data.vertices))
    assert v > 2 * n and f == v, (v, f)  # an annulus: a face per vertex
    # A loop of loose edges (no faces) fills too.
    wire = mesh_object("wire", list(map(tuple, p)),
                       edges=[(i, (i + 1) % n) for i in range(n)])
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    assert bpy.ops.mesh.dot_triangulate_loops(
        preset='SMOOTH', search_space='DELAUNAY', protect_edges=True) \
        == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    v, f = check_mesh(wire, boundary_edges=n + 4)
    assert (v, f) == (n + 4, n + 4 - 2)


def test_loop_operators_need_a_loop():
    clear_scene()
    bpy.ops.mesh.primitive_cylinder_add(vertices=12, end_fill_type='NOTHING')
    cyl = bpy.context.active_object
    bpy.ops.object.mode_set(mode='EDIT')
    for op in (bpy.ops.mesh.dot_fill_loops, bpy.ops.mesh.dot_triangulate_loops):
        select_boundary_edges(cyl, lambda c: False)
        expect_report(op, "select closed loops")
        # Half a loop is no loop.
        select_boundary_edges(cyl, lambda c: c.z > 0 and c.x > 0)
        expect_report(op, "select closed loops")
    bpy.ops.object.mode_set(mode='OBJECT')


def saddle(n):
    return [(math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n),
             0.5 * math.cos(6 * math.pi * i / n)) for i in range(n)]


def check_disk(obj, inserted=0):
    v, f = check_mesh(obj, boundary_edges=counts(obj)[0])
    assert f == v - 2, (v, f)


def test_triangulate_curve_bezier_poly_and_polyline():
    clear_scene()
    bpy.ops.curve.primitive_bezier_circle_add(radius=1)
    curve = bpy.context.active_object
    curve.location = (1, 2, 3)
    for i, bp in enumerate(curve.data.splines[0].bezier_points):
        dz = 0.4 * (-1) ** i
        bp.co.z += dz
        bp.handle_left.z += dz
        bp.handle_right.z += dz
    assert bpy.ops.mesh.dot_triangulate_curve() == {'FINISHED'}
    surface = bpy.context.active_object
    assert surface is not curve and surface.type == 'MESH'
    assert "DOT surface" in surface.name
    assert surface.matrix_world == curve.matrix_world
    check_disk(surface)
    assert counts(surface)[0] == 4 * curve.data.splines[0].resolution_u

    # A cyclic POLY spline.
    poly = cyclic_poly_curve("poly", saddle(40))
    spline = poly.data.splines[0]
    assert bpy.ops.mesh.dot_triangulate_curve(preset='MINIMAL_AREA') \
        == {'FINISHED'}
    check_disk(bpy.context.active_object)
    assert counts(bpy.context.active_object)[0] == 40

    # Two closed splines, one above the other: One Surface lofts a tube
    # (an annulus: as many faces as vertices, no edge used twice).
    data = bpy.data.curves.new("rims", 'CURVE')
    data.dimensions = '3D'
    for z, r in ((0.0, 1.0), (1.0, 0.7)):
        rim = data.splines.new('POLY')
        rim.points.add(23)
        for k, p in enumerate(rim.points):
            a = 2 * math.pi * k / 24
            p.co = (r * math.cos(a), r * math.sin(a), z + 0.05 * math.sin(3 * a), 1)
        rim.use_cyclic_u = True
    rims = bpy.data.objects.new("rims", data)
    bpy.context.scene.collection.objects.link(rims)
    activate(rims)
    assert bpy.ops.mesh.dot_triangulate_curve(one_surface=True) == {'FINISHED'}
    tube = bpy.context.active_object
    assert counts(tube)[:2] == (48, 48)
    bm = object_bmesh(tube)
    try:
        assert sum(1 for e in bm.edges if e.is_boundary) == 48
        assert all(len(e.link_faces) <= 2 for e in bm.edges)
    finally:
        bm.free()
    activate(rims)
    assert bpy.ops.mesh.dot_triangulate_curve() == {'FINISHED'}  # two caps
    assert counts(bpy.context.active_object)[1] == 2 * 22

    # Open: refused, as a report.
    spline.use_cyclic_u = False
    activate(poly)
    expect_report(lambda: bpy.ops.mesh.dot_triangulate_curve(),
                  "no closed curve")

    # A polyline mesh (edges only), two loops: two patches in one object.
    a, b = saddle(30), [(x + 3, y, z) for x, y, z in saddle(20)]
    mesh_object("polyline", a + b, edges=[
        (i, (i + 1) % 30) for i in range(30)] + [
        (30 + i, 30 + (i + 1) % 20) for i in range(20)])
    assert bpy.ops.mesh.dot_triangulate_curve(preset='CUSTOM', area=1,
                                              squared_dihedral=1) \
        == {'FINISHED'}
    v, f = check_mesh(bpy.context.active_object, boundary_edges=50)
    assert (v, f) == (50, 46)


CUBE_CORNERS = [(x, y, z) for x in (0.0, 1.0) for y in (0.0, 1.0)
                for z in (0.0, 1.0)]


def cube_edges_curve(name, segments=4, jitter=0.0):
    """A curve object whose splines are the unit cube's 12 edges, each a
    POLY spline of `segments` pieces with its own end points; `jitter`
    moves every other spline's first point off its corner by that much."""
    data = bpy.data.curves.new(name, 'CURVE')
    data.dimensions = '3D'
    edges = [(a, b) for a in range(8) for b in range(a + 1, 8)
             if sum(abs(p - q) for p, q in
                    zip(CUBE_CORNERS[a], CUBE_CORNERS[b])) == 1]
    for k, (a, b) in enumerate(edges):
        spline = data.splines.new('POLY')
        spline.points.add(segments)  # segments + 1 points
        for i, point in enumerate(spline.points):
            t = i / segments
            co = [(1 - t) * u + t * w
                  for u, w in zip(CUBE_CORNERS[a], CUBE_CORNERS[b])]
            if i == 0 and k % 2:
                co[0] += jitter
            point.co = (*co, 1)
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    activate(obj)
    return obj


def test_surface_curves_turns_a_cube_of_splines_into_a_closed_box():
    clear_scene()
    # Spline ends 1e-8 apart still meet: the server welds them (the
    # default Weld Distance, 1e-4, as Blender's Merge by Distance).
    curve = cube_edges_curve("cube_edges", segments=4, jitter=1e-8)
    curve.location = (1, 2, 3)
    with Recording("surface_network") as rec:
        assert bpy.ops.mesh.dot_surface_curves() == {'FINISHED'}
    (args, kwargs, answer), = rec.calls
    assert len(args[0]) == 12 * 5, "every spline's points, as evaluated"
    assert sorted(len(line) for line in args[1]) == [5] * 12, \
        "a polyline per spline"
    assert abs(kwargs["options"].weld_distance - 1e-4) < 1e-9
    assert answer.report.merged_vertices == 16  # 3 spline ends per corner
    assert answer.report.surfaced == 6 and answer.report.closed
    surface = bpy.context.active_object
    assert surface is not curve and surface.type == 'MESH'
    assert surface.name == "cube_edges_surface"
    assert surface.matrix_world == curve.matrix_world
    check_mesh(surface, boundary_edges=0)
    bm = object_bmesh(surface)
    try:
        assert all(len(e.link_faces) == 2 for e in bm.edges), "not closed"
        assert len(bm.verts) - len(bm.edges) + len(bm.faces) == 2
        assert len(bm.verts) > 8 + 12 * 3, "refined and faired"
        kd = KDTree(len(bm.verts))
        for v in bm.verts:
            kd.insert(v.co, v.index)
        kd.balance()
        for corner in CUBE_CORNERS:
            assert kd.find(corner)[2] < 1e-7, f"no vertex at {corner}"
    finally:
        bm.free()
    # The triangulate stage adds no vertex; Skip Longest Cycle leaves one
    # square open (its 16 edges).
    activate(curve)
    assert bpy.ops.mesh.dot_surface_curves(stage='TRIANGULATE') \
        == {'FINISHED'}
    assert counts(bpy.context.active_object)[:1] == (8 + 12 * 3,)
    check_mesh(bpy.context.active_object, boundary_edges=0)
    activate(curve)
    assert bpy.ops.mesh.dot_surface_curves(
        stage='TRIANGULATE', skip_longest=True, preset='MINIMAL_AREA') \
        == {'FINISHED'}
    check_mesh(bpy.context.active_object, boundary_edges=16)


def test_surface_curves_welds_strokes_that_nearly_meet():
    clear_scene()
    # Every other stroke starts 0.003 off its corner, and the strokes are
    # sampled every 0.02: with a weld of 0.05 only their free ends move
    # (a weld of every point that close would collapse them). Unwelded,
    # a moved end touches the stroke beside it: refused, naming them.
    curve = cube_edges_curve("strokes", segments=50, jitter=0.003)
    expect_report(lambda: bpy.ops.mesh.dot_surface_curves(
        stage='TRIANGULATE', weld_distance=0), "curves cross", "polyline")
    activate(curve)
    with Recording("surface_network") as rec:
        assert bpy.ops.mesh.dot_surface_curves(
            stage='TRIANGULATE', weld_distance=0.05) == {'FINISHED'}
    (args, kwargs, answer), = rec.calls
    assert answer.report.merged_vertices == 16
    assert answer.report.closed and answer.report.surfaced == 6
    surface = bpy.context.active_object
    check_mesh(surface, boundary_edges=0)
    assert counts(surface)[0] == 8 + 12 * 49, "every stroke point kept"


def test_surface_curves_of_an_edges_only_mesh_shares_its_junctions():
    clear_scene()
    # The cube's 12 edges as a wire mesh whose corners are shared, each
    # edge in 10 pieces: one polyline per edge between corners. Its ends
    # meet already, so a Weld Distance wider than the pieces welds nothing.
    vertices, edges = list(CUBE_CORNERS), []
    for a in range(8):
        for b in range(a + 1, 8):
            p, q = CUBE_CORNERS[a], CUBE_CORNERS[b]
            if sum(abs(x - y) for x, y in zip(p, q)) != 1:
                continue
            chain = [a]
            for i in range(1, 10):
                chain.append(len(vertices))
                vertices.append(tuple(x + i / 10 * (y - x)
                                      for x, y in zip(p, q)))
            chain.append(b)
            edges += zip(chain, chain[1:])
    mesh_object("wire_cube", vertices, edges=edges)
    with Recording("surface_network") as rec:
        assert bpy.ops.mesh.dot_surface_curves(
            stage='TRIANGULATE', weld_distance=0.25) == {'FINISHED'}
    (args, kwargs, answer), = rec.calls
    assert len(args[0]) == 8 + 12 * 9 and len(args[1]) == 12
    assert sorted(len(line) for line in args[1]) == [11] * 12
    assert answer.report.merged_vertices == 0
    assert answer.report.closed and answer.report.surfaced == 6
    check_mesh(bpy.context.active_object, boundary_edges=0)


def test_surface_curves_leaves_out_segments_of_zero_length():
    clear_scene()
    # A cyclic square whose last point repeats its first, and a point
    # drawn twice on a side: edges of zero length, left out (the server
    # welds their ends), even with Weld Distance 0.
    cyclic_poly_curve("square", [(0, 0, 0), (1, 0, 0), (1, 0.5, 0),
                                 (1, 0.5, 0), (1, 1, 0), (0, 1, 0),
                                 (0, 0, 0)])
    with Recording("surface_network") as rec:
        assert bpy.ops.mesh.dot_surface_curves(
            stage='TRIANGULATE', weld_distance=0) == {'FINISHED'}
    (args, kwargs, answer), = rec.calls
    assert answer.report.merged_vertices == 2
    assert answer.report.surfaced == 1
    check_mesh(bpy.context.active_object, boundary_edges=5)


def test_surface_curves_circle_on_a_lid_is_an_island_or_a_hole():
    clear_scene()
    curve = cube_edges_curve("lid", segments=3)
    circle = curve.data.splines.new('POLY')
    circle.points.add(23)  # 24 points
    for i, point in enumerate(circle.points):
        a = 2 * math.pi * i / 24
        point.co = (0.5 + 0.3 * math.cos(a), 0.5 + 0.3 * math.sin(a), 1, 1)
    circle.use_cyclic_u = True
    with Recording("surface_network") as rec:
        assert bpy.ops.mesh.dot_surface_curves() == {'FINISHED'}
    (args, kwargs, answer), = rec.calls
    assert kwargs["options"].islands == "inset"
    assert answer.report.closed and answer.report.surfaced == 7
    assert sorted(len(p.loops) for p in answer.report.patches) == \
        [1] * 6 + [2]
    check_mesh(bpy.context.active_object, boundary_edges=0)
    activate(curve)
    with Recording("surface_network") as rec:
        assert bpy.ops.mesh.dot_surface_curves(islands='HOLE') == {'FINISHED'}
    (args, kwargs, answer), = rec.calls
    assert kwargs["options"].islands == "hole"
    assert answer.report.surfaced == 6 and not answer.report.closed
    check_mesh(bpy.context.active_object, boundary_edges=24)


def test_surface_curves_walls_only_when_asked():
    clear_scene()
    data = bpy.data.curves.new("partition", 'CURVE')
    data.dimensions = '3D'
    corners = [(x, y, z) for x in (0.0, 1.0, 2.0) for y in (0.0, 1.0)
               for z in (0.0, 1.0)]
    for a in range(12):
        for b in range(a + 1, 12):
            if sum(abs(p - q) for p, q in zip(corners[a], corners[b])) == 1:
                spline = data.splines.new('POLY')
                spline.points.add(1)
                spline.points[0].co = (*corners[a], 1)
                spline.points[1].co = (*corners[b], 1)
    obj = bpy.data.objects.new("partition", data)
    bpy.context.scene.collection.objects.link(obj)
    activate(obj)
    with Recording("surface_network") as rec:
        assert bpy.ops.mesh.dot_surface_curves(stage='TRIANGULATE') \
            == {'FINISHED'}
    (args, kwargs, answer), = rec.calls
    assert not kwargs["options"].walls
    assert answer.report.surfaced == 10
    activate(obj)
    with Recording("surface_network") as rec:
        assert bpy.ops.mesh.dot_surface_curves(stage='TRIANGULATE',
                                               walls=True) == {'FINISHED'}
    (args, kwargs, answer), = rec.calls
    assert kwargs["options"].walls
    assert answer.report.surfaced == 11
    assert answer.report.non_manifold_curves == 4


def test_surface_curves_bezier_with_bevel_and_refusals():
    clear_scene()
    # A lone closed Bezier curve bounds a disk; its bevel is not sent (and
    # stays on the curve).
    bpy.ops.curve.primitive_bezier_circle_add(radius=1)
    circle = bpy.context.active_object
    circle.data.bevel_depth = 0.1
    curves, objects = len(bpy.data.curves), len(bpy.data.objects)
    assert bpy.ops.mesh.dot_surface_curves(stage='REFINE') == {'FINISHED'}
    disk = bpy.context.active_object
    rim = 4 * circle.data.resolution_u
    check_mesh(disk, boundary_edges=rim)
    v, f, _ = counts(disk)
    assert v > rim and f == 2 * v - rim - 2  # a disk: V - E + F = 1
    assert abs(circle.data.bevel_depth - 0.1) < 1e-6
    assert len(bpy.data.curves) == curves
    assert len(bpy.data.objects) == objects + 1
    # An open spline bounds nothing: the server says so, as a report.
    data = bpy.data.curves.new("open", 'CURVE')
    data.dimensions = '3D'
    spline = data.splines.new('POLY')
    spline.points.add(2)
    for point, co in zip(spline.points, [(0, 0, 0), (1, 0, 0), (1, 1, 0)]):
        point.co = (*co, 1)
    path = bpy.data.objects.new("open", data)
    bpy.context.scene.collection.objects.link(path)
    activate(path)
    expect_report(lambda: bpy.ops.mesh.dot_surface_curves(),
                  "INVALID_ARGUMENT", "bounds no patch")
    # A mesh with faces is no network.
    bpy.ops.mesh.primitive_cube_add()
    expect_report(lambda: bpy.ops.mesh.dot_surface_curves(), "has faces")


def test_no_triangulation_is_a_report():
    clear_scene()
    n = 90
    knot = [(math.sin(t) + 2 * math.sin(2 * t), math.cos(t) - 2 * math.cos(2 * t),
             -math.sin(3 * t)) for t in (2 * math.pi * i / n for i in range(n))]
    mesh_object("knot", knot, edges=[(i, (i + 1) % n) for i in range(n)])
    expect_report(lambda: bpy.ops.mesh.dot_triangulate_curve(),
                  "no triangulation", "not Delaunay-triangulable")
    assert len([o for o in bpy.data.objects if o.type == 'MESH']) == 1


def test_server_errors_are_reports(address):
    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add()
    sphere = bpy.context.active_object
    delete_faces(sphere, lambda c: c.z > 0.8)
    before = counts(sphere)
    prefs().server_address = f"127.0.0.1:{free_port()}"
    try:
        expect_report(lambda: bpy.ops.mesh.dot_fill_holes(), "UNAVAILABLE")
    finally:
        prefs().server_address = address
    prefs().server_address = ""
    prefs().run_locally = False
    try:
        expect_report(lambda: bpy.ops.mesh.dot_fill_holes(),
                      "no DOT server is set")
    finally:
        prefs().run_locally = True
        prefs().server_address = address
    # A mesh the server refuses: an edge of three faces.
    mesh_object("fin", [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (0, -1, 0),
                        (2, 2, 2), (3, 2, 2), (2, 3, 2)],
                faces=[(0, 1, 2), (0, 1, 3), (0, 1, 4), (5, 6, 7)])
    expect_report(lambda: bpy.ops.mesh.dot_fill_holes(), "INVALID_ARGUMENT",
                  "shared by 3 faces")
    assert counts(sphere) == before


def test_run_locally_starts_and_stops_a_server(address):
    import dot
    clear_scene()
    bpy.ops.mesh.primitive_uv_sphere_add()
    sphere = bpy.context.active_object
    delete_faces(sphere, lambda c: c.z > 0.8)
    prefs().server_address = ""
    prefs().run_locally = True
    prefs().server_executable = "no-such-dot-server"
    try:
        expect_report(lambda: bpy.ops.mesh.dot_fill_holes(), "not on PATH")
        prefs().server_executable = os.path.abspath(ARGS.server)
        assert bpy.ops.mesh.dot_fill_holes(stage='TRIANGULATE') == {'FINISHED'}
        check_mesh(sphere)
        assert dot.connection.local_server_running()
        process = dot.connection._local["server"].process
    finally:
        prefs().server_address = address
    addon_utils.disable("dot")
    assert process.poll() is not None, "unregister stops the local server"
    addon_utils.enable("dot", default_set=True)
    assert prefs().server_address == address


def test_background_job_and_cancel(address):
    """The worker-thread path of invoke/modal: progress, result, Esc."""
    import dot
    from dot import operators
    client = dot.connection.client(prefs())
    # The paper's Twist curve, n = 1501: a DOT2 of about a second.
    n, twist, k = 1501, [], 0
    point = lambda i: (i / n, (i / n) ** 2, (i / n) ** 3)  # noqa: E731
    while 2 * k + 1 <= n:
        twist.append(point(2 * k + 1))
        if n - 1 - 2 * k >= 2:
            twist.append(point(n - 1 - 2 * k))
        k += 1
    smooth = dot.connection.dot_client.TriangulateOptions(
        weights={"squared_dihedral": 1.0})
    job = operators.Job(operators._triangulate_work(
        [saddle(50), saddle(60)], None, smooth))
    job.start(client)
    for _ in range(600):
        if job.done:
            break
        time.sleep(0.05)
    assert job.done and job.error is None, job.error
    assert [r.ok for r in job.result] == [True, True]
    assert job.fraction == 1.0
    slow = operators.Job(operators._triangulate_work(
        [twist], None, dataclasses.replace(smooth, no_cache=True)))
    slow.start(client)
    time.sleep(0.2)
    slow.token.cancel()  # what Esc does
    for _ in range(200):
        if slow.done:
            break
        time.sleep(0.05)
    assert slow.done
    assert slow.error is not None and slow.error.code.name == "CANCELLED", \
        slow.error


def test_fill_job_reports_phases_and_keeps_a_stopped_fill(address):
    """The status bar's text per phase; a fill stopped by its time budget
    hands back the holes it finished, with the stop, not an error."""
    import dot
    from dot import operators
    P = dot.connection.dot_client.FillProgress
    assert operators.fill_status(P(phase="loops")) == "finding the holes"
    assert operators.fill_status(P(phase="holes", holes_done=3,
                                   holes_total=10, eta_ms=2500)) == \
        "3 of 10 holes, about 3 s left"
    client = dot.connection.client(prefs())
    v, f = shapes.wavy_grid_with_holes()
    seen = []
    client.fill_patches(v, f, skip_longest=True, progress=seen.append)
    stopped = []
    for budget in shapes.holes_phase_budgets(seen):
        options = dot.connection.dot_client.FillOptions(
            skip_longest=True, time_budget_ms=budget)
        job = operators.Job(operators._fill_work(v, f, options))
        job.run(client)  # what the worker thread runs
        if job.stopped is not None:
            stopped.append(job)
        else:
            assert job.error is None or \
                job.error.code.name == "DEADLINE_EXCEEDED", job.error
    assert stopped, "no budget ended inside the holes phase"
    for job in stopped:
        assert job.error is None
        report = job.result.report
        assert report.stopped > 0
        assert len(job.result.patches) == report.filled
        assert job.stopped.code.name == "DEADLINE_EXCEEDED"


def main():
    # Install the zip the build made and enable it, as a user would.
    assert os.path.exists(ARGS.addon_zip), ARGS.addon_zip
    bpy.ops.preferences.addon_install(overwrite=True, filepath=ARGS.addon_zip)
    module = addon_utils.enable("dot", default_set=True)
    assert module is not None, "the add-on did not enable"
    print(f"add-on from {module.__file__}")
    server, address = start_server()
    failures = []
    try:
        prefs().server_address = address
        tests = [(name, fn) for name, fn in globals().items()
                 if name.startswith("test_") and callable(fn)]
        for name, fn in tests:
            t0 = time.monotonic()
            try:
                if fn.__code__.co_argcount:
                    fn(address)
                else:
                    fn()
                print(f"PASS {name} ({time.monotonic() - t0:.1f} s)")
            except Exception:
                failures.append(name)
                print(f"FAIL {name}")
                traceback.print_exc()
    finally:
        addon_utils.disable("dot")
        server.terminate()
        server.wait(timeout=30)
    print(f"{len(tests) - len(failures)} of {len(tests)} passed")
    if failures:
        raise RuntimeError(f"failed: {', '.join(failures)}")


main()

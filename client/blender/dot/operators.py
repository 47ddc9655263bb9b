# SPDX-License-Identifier: AGPL-3.0-or-later
"""The add-on's operators, one per job: mesh.dot_fill_loops (FillHoles,
exactly the selected loops), mesh.dot_triangulate_loops (Triangulate, one
DOT patch per selected loop), mesh.dot_fill_holes (FillHoles, every hole),
mesh.dot_triangulate_curve, mesh.dot_surface_curves (SurfaceNetwork, a
curve network into one surface).

Each operator reads the geometry in `prepare` (main thread), does the
remote work in a function that touches no Blender data (run in a worker
thread when invoked from the UI, so the status bar shows progress and Esc
cancels, or inline from scripts and the redo panel), and writes the result
back in `finish` (main thread), as one undo step. Every failure becomes a
Blender report.
"""
import dataclasses
import sys
import threading
import traceback

import bmesh
import bpy
import numpy as np
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty

from . import connection, geometry
from .connection import dot_client

METRICS = tuple(f.name for f in dataclasses.fields(dot_client.Weights))

STAGES = [
    ('TRIANGULATE', "Triangulate", "The optimal DOT patch only"),
    ('REFINE', "Refine", "The patch refined (Liepa) to the density around it"),
    ('FAIR', "Fair", "Refined and faired: the finished surface"),
]
SEARCH_SPACES = [
    ('AUTO', "Auto", "Delaunay triangles; all triangles for small polygons "
     "that have no Delaunay triangulation"),
    ('DELAUNAY', "Delaunay", "Delaunay triangles only: never self-intersects"),
    ('ALL', "All", "Every triangle: the unrestricted optimum (small loops)"),
    ('DELAUNAY_FIRST', "Delaunay First", "Every triangle, Delaunay ones "
     "first: large loops with no Delaunay triangulation (may self-intersect)"),
]


def addon_prefs(context):
    return context.preferences.addons[__package__].preferences


def describe(error):
    if isinstance(error, dot_client.NoTriangulation):
        return f"DOT: {error} (try Protect Edges, or search space All)"
    if isinstance(error, dot_client.DotError):
        return f"DOT: {error.code.name}: {error.message}"
    if isinstance(error, geometry.MeshChanged):
        return f"DOT: {error}"
    return f"DOT failed: {type(error).__name__}: {error}"


# -- weights -------------------------------------------------------------


def _weight(name, default=0.0):
    return FloatProperty(
        name=name.replace("_", " ").title(), default=default, soft_min=-10,
        soft_max=10, description=f"Weight of the {name.replace('_', ' ')} "
        "metric (a negative weight maximizes it)")


def preset_items(leave_out=()):
    """The weight presets as enum items: dot_client.WEIGHT_PRESETS (the one
    table the client and the add-on share), then Custom."""
    return [(name.upper(), p.label, p.description)
            for name, p in dot_client.WEIGHT_PRESETS.items()
            if name not in leave_out] + [
        ('CUSTOM', "Custom", "The weights below")]


class WeightProps:
    area: _weight("area", 1.0)
    perimeter: _weight("perimeter")
    normal_deviation: _weight("normal_deviation")
    shape: _weight("shape")
    dihedral: _weight("dihedral")
    squared_dihedral: _weight("squared_dihedral")

    def weights(self, use):
        """The weights of the `preset` property: the custom ones, or the
        preset's for `use` ("triangulate": one loop's patch, "fill":
        FillHoles)."""
        if self.preset == 'CUSTOM':
            return dot_client.Weights(**{m: getattr(self, m) for m in METRICS})
        preset = dot_client.WEIGHT_PRESETS[self.preset.lower()]
        return preset.triangulate if use == "triangulate" else preset.fill

    def draw_weights(self, layout, enabled):
        col = layout.column(align=True)
        col.enabled = enabled
        for m in METRICS:
            col.prop(self, m)


class TriangulateProps:
    """What a Triangulate job adds to the weights: the search space, and
    one panel layout for every operator that triangulates loops."""
    search_space: EnumProperty(name="Search Space", items=SEARCH_SPACES,
                               default='AUTO')
    one_surface: BoolProperty(
        name="One Surface", default=False,
        description="Join the selected loops or closed curves into one "
        "surface (a tube between two rims, a ring around islands, a branch "
        "between three rims) instead of one patch each")

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "preset")
        self.draw_weights(layout, self.preset == 'CUSTOM')
        layout.prop(self, "protect_edges")
        layout.prop(self, "search_space")
        layout.prop(self, "one_surface")

    def check_several(self, loops, what):
        """Reports and returns False unless One Surface has two or more
        loops."""
        if self.one_surface and len(loops) < 2:
            self.report({'ERROR'}, f"DOT: One Surface joins two or more "
                        f"{what}; {len(loops)} is selected")
            return False
        return True


# -- the job ---------------------------------------------------------------


class Job:
    """Remote work in a worker thread: progress, cancel, result or error."""

    def __init__(self, work):
        self.work = work
        self.token = dot_client.CancelToken()
        self.fraction = 0.0
        self.text = "starting"
        self.result = None
        self.stopped = None  # dot_client.FillStopped: result is partial
        self.error = None
        self.done = False

    def progress(self, fraction, text):
        self.fraction, self.text = fraction, text

    def run(self, client):
        try:
            self.result, self.stopped = run_work(self.work, client,
                                                 self.token, self.progress)
        except BaseException as e:  # handed to the main thread
            self.error = e
        finally:
            self.done = True

    def start(self, client):
        threading.Thread(target=self.run, args=(client,), daemon=True,
                         name="dot-job").start()


def run_work(work, client, token, progress):
    """(result, None), or (the partial result, the FillStopped) when a fill
    stopped early but kept the holes it finished."""
    try:
        return work(client, token, progress), None
    except dot_client.FillStopped as stopped:
        return stopped.result, stopped


class DotOperator:
    """Shared by the operators: execute runs inline, invoke in a worker
    thread with a modal loop (progress in the status bar, Esc cancels)."""

    def prepare(self, context):  # -> (work, state) or None
        raise NotImplementedError

    def finish(self, context, state, payload):  # -> {'FINISHED'} ...
        raise NotImplementedError

    def fail(self, error):
        if not isinstance(error, (dot_client.DotError, geometry.MeshChanged)):
            traceback.print_exception(type(error), error,
                                      error.__traceback__, file=sys.stderr)
        self.report({'ERROR'}, describe(error))
        return {'CANCELLED'}

    def execute(self, context):
        try:
            prepared = self.prepare(context)
            if prepared is None:
                return {'CANCELLED'}
            work, state = prepared
            client = connection.client(addon_prefs(context))
            wm = context.window_manager
            wm.progress_begin(0, 100)
            try:
                payload, stopped = run_work(
                    work, client, None,
                    lambda f, text: wm.progress_update(int(100 * f)))
            finally:
                wm.progress_end()
            return self.finish_stopped(context, state, payload, stopped)
        except Exception as e:
            return self.fail(e)

    def invoke(self, context, event):
        if bpy.app.background or context.window is None:
            return self.execute(context)
        try:
            prepared = self.prepare(context)
            if prepared is None:
                return {'CANCELLED'}
            work, state = prepared
            client = connection.client(addon_prefs(context))
        except Exception as e:
            return self.fail(e)
        self._state = state
        self._job = Job(work)
        self._job.start(client)
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.modal_handler_add(self)
        wm.progress_begin(0, 100)
        self._status(context, "starting")
        return {'RUNNING_MODAL'}

    def _status(self, context, text):
        if context.workspace is not None:
            context.workspace.status_text_set(
                f"DOT {self.bl_label}: {text}  (Esc to cancel)")

    def _end_modal(self, context):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        if context.workspace is not None:
            context.workspace.status_text_set(None)

    def modal(self, context, event):
        job = self._job
        if event.type == 'ESC' and event.value == 'PRESS':
            job.token.cancel()
            job.text = "cancelling"
        if event.type != 'TIMER':
            # The mesh must not change under the job: other input waits.
            return {'RUNNING_MODAL'}
        context.window_manager.progress_update(int(100 * job.fraction))
        self._status(context, job.text)
        if not job.done:
            return {'RUNNING_MODAL'}
        self._end_modal(context)
        if job.error is not None:
            if job.token.cancelled:
                self.report({'WARNING'}, "DOT: cancelled")
                return {'CANCELLED'}
            return self.fail(job.error)
        try:
            return self.finish_stopped(context, self._state, job.result,
                                       job.stopped)
        except Exception as e:
            return self.fail(e)

    def finish_stopped(self, context, state, payload, stopped):
        """finish, then a warning when the work stopped early and only
        part of it is in the mesh."""
        result = self.finish(context, state, payload)
        if stopped is not None:
            answers = payload if isinstance(payload, list) else [payload]
            left = sum(a.report.stopped for a in answers)
            self.report({'WARNING'}, f"{describe(stopped)} (stopped early: "
                        f"{left} holes not filled)")
        return result


def _triangulate_work(loops, normals, options):
    """Triangulate each loop ((n, 3) arrays) with `options`
    (dot_client.TriangulateOptions) over one TriangulateBatch stream."""
    def work(client, cancel, progress):
        progress(0.0, f"0 of {len(loops)} loops")
        return client.triangulate_many(
            loops, normals, options=options, cancel=cancel,
            progress=lambda done, total, _: progress(
                done / total, f"{done} of {total} loops"))
    return work


def _face_chords(bm, loops):
    """Pairs of positions (in the loops joined) of loop vertices that share
    a face but are not consecutive on a loop: the mesh's own chords and the
    diagonals of its quads, which a surface over the rims must not use (an
    edge of three faces, or a triangle touching a quad along its
    diagonal)."""
    position, consecutive = {}, set()
    for loop in loops:
        for k, v in enumerate(loop):
            position[v] = len(position)
            consecutive.add(frozenset((v, loop[(k + 1) % len(loop)])))
    chords = set()
    for face in bm.faces:
        ids = [v.index for v in face.verts if v.index in position]
        for i, a in enumerate(ids):
            for b in ids[i + 1:]:
                if frozenset((a, b)) not in consecutive:
                    chords.add(tuple(sorted((position[a], position[b]))))
    return sorted(chords)


def _surface_work(loops, normals, options, forbidden=None):
    """One surface joining the loops ((n, 3) arrays): a Triangulate call
    with several loops, none of whose triangles has an edge of
    `forbidden` (pairs of positions in the loops joined). Its answer, like
    a batch item, has .error (None or the exception) and the result's
    fields."""
    def work(client, cancel, progress):
        progress(0.0, f"joining {len(loops)} loops")
        result = client.triangulate_loops(loops, normals, options=options,
                                          forbidden_edges=forbidden,
                                          cancel=cancel,
                                          raise_no_triangulation=False)
        if result.summary.status != "ok":
            result.error = dot_client.NoTriangulation(result.summary)
        return result
    return work


def _fill_work(vertices, faces, options, corners=None):
    """FillHoles on the mesh as triangles with their UVs and colours
    (geometry.corner_data), answered with patches (dot_client.FillPatches)
    in the ids sent."""
    def work(client, cancel, progress):
        progress(0.0, "sending the mesh")
        return client.fill_patches(
            vertices, faces, options=options, cancel=cancel,
            corner_data=corners,
            progress=lambda p: progress(
                p.holes_done / max(1, p.holes_total), fill_status(p)))
    return work


_PHASES = {"repair": "repairing the mesh", "loops": "finding the holes",
           "merge": "merging the patches"}


def fill_status(p):
    """The status bar's text for a dot_client.FillProgress."""
    if p.phase != "holes" and (p.phase or not p.holes_total):
        return _PHASES.get(p.phase, "working")  # a server without phases
    text = f"{p.holes_done} of {p.holes_total} holes"
    if p.eta_ms > 0:
        text += f", about {int(p.eta_ms / 1000) + 1} s left"
    return text


def _hole_problems(report):
    """A line per hole that was selected but stays open."""
    return [f"hole {h.id} ({h.boundary_vertices} edges): {h.status}"
            + (f": {h.reason}" if h.reason else "")
            for h in report.holes
            if h.status not in ("filled", "skipped", "stopped")]


def _edit_bmesh(context):
    obj = context.edit_object
    return obj, bmesh.from_edit_mesh(obj.data)


# -- the selected loops ----------------------------------------------------


class LoopsOperator(DotOperator, WeightProps):
    """Shared by Fill Loops and Triangulate Loops: Edit Mode, the selected
    loops gathered (with reports when there are none), the new faces
    selected alone, what was filled reported."""

    @classmethod
    def poll(cls, context):
        return (context.mode == 'EDIT_MESH' and context.edit_object is not None
                and context.edit_object.type == 'MESH')

    def selected_loops(self, context):
        """(object, bmesh, loops): the closed loops of selected boundary or
        wire edges (vertex index lists), or None when there are none (then
        reported)."""
        obj, bm = _edit_bmesh(context)
        bm.verts.index_update()
        loops, skipped = geometry.selected_loops(bm)
        if skipped:
            self.report({'WARNING'}, f"DOT: {skipped} selected edge chains "
                        "are not closed loops of boundary edges; skipped")
        if not loops:
            self.report({'ERROR'}, "DOT: select closed loops of boundary "
                        "edges (the rims of holes) to fill")
            return None
        return obj, bm, loops

    @staticmethod
    def select_only_new(bm):
        for f in bm.faces:  # the new faces end up selected, alone
            f.select_set(False)

    @staticmethod
    def update(obj, bm):
        bm.select_flush_mode()
        bm.normal_update()
        bmesh.update_edit_mesh(obj.data, loop_triangles=True, destructive=True)


def report_filled(op, filled, total, problems, stats):
    """Reports problems (warnings) and what was filled; CANCELLED when
    nothing was."""
    for p in problems:
        op.report({'WARNING'}, p)
    if filled == 0:
        op.report({'ERROR'}, "DOT: nothing was filled" +
                  (f" ({problems[0]})" if problems else ""))
        return {'CANCELLED'}
    extra = ""
    if stats.get("inserted"):
        extra += f", {stats['inserted']} boundary vertices inserted"
    if stats.get("duplicates"):
        extra += f", {stats['duplicates']} faces existed already"
    op.report({'INFO'}, f"DOT: {filled} of {total} filled{extra}")
    return {'FINISHED'}


def _loop_edges(bm, loop):
    bm.verts.ensure_lookup_table()
    n = len(loop)
    return [bm.edges.get((bm.verts[loop[i]], bm.verts[loop[(i + 1) % n]]))
            for i in range(n)]


# -- mesh.dot_fill_loops ----------------------------------------------------


class MESH_OT_dot_fill_loops(LoopsOperator, bpy.types.Operator):
    """Fill exactly the holes whose rims are selected (closed loops of
    boundary edges) through the DOT server's FillHoles: the optimal patch,
    meeting the surface around it, refined and faired if asked"""
    bl_idname = "mesh.dot_fill_loops"
    bl_label = "Fill Loops (DOT)"
    bl_options = {'REGISTER', 'UNDO'}

    preset: EnumProperty(name="Weights", default='SMOOTH',
                         items=preset_items())
    stage: EnumProperty(name="Stage", items=STAGES, default='TRIANGULATE')

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "stage")
        layout.prop(self, "preset")
        self.draw_weights(layout, self.preset == 'CUSTOM')

    def prepare(self, context):
        selected = self.selected_loops(context)
        if selected is None:
            return None
        obj, bm, loops = selected
        if any(e is None or not e.is_boundary
               for loop in loops for e in _loop_edges(bm, loop)):
            self.report({'ERROR'}, "DOT: Fill Loops fills the rims of holes "
                        "in a surface (boundary edges); for loops of loose "
                        "edges use Triangulate Loops (DOT)")
            return None
        vertices = geometry.vertex_array(bm)
        faces, owner = geometry.triangles(bm)
        corners = geometry.corner_data(bm)
        options = dot_client.FillOptions(
            stage=self.stage.lower(), weights=self.weights("fill"),
            loops_through=geometry.loop_names(bm, loops), no_repair=True)
        state = {"loops": loops, "faces": faces, "owner": owner,
                 "corners": corners,
                 "counts": (len(bm.verts), len(bm.faces))}
        return _fill_work(vertices, faces, options, corners), state

    def finish(self, context, state, answer):
        obj, bm = _edit_bmesh(context)
        geometry.check_unchanged(bm, *state["counts"])
        vertex_count = state["counts"][0]
        patches, others = geometry.patches_of_loops(
            answer.patches, state["loops"], vertex_count)
        problems = [f"DOT: {p}" for p in _hole_problems(answer.report)]
        if others:
            problems.append(f"DOT: {others} other holes through vertices of "
                            "the selected loops were left open")
        if not patches:
            return report_filled(self, 0, len(state["loops"]), problems, {})
        self.select_only_new(bm)
        _, stats = geometry.add_patches(bm, patches, vertex_count,
                                        state["faces"], state["owner"],
                                        state["corners"])
        holes = {p.hole for p in patches}
        stats["inserted"] = sum(h.boundary_inserted
                                for h in answer.report.holes if h.id in holes)
        self.update(obj, bm)
        return report_filled(self, len(patches), len(state["loops"]),
                             problems, stats)


# -- mesh.dot_triangulate_loops ---------------------------------------------


class MESH_OT_dot_triangulate_loops(LoopsOperator, TriangulateProps,
                                    bpy.types.Operator):
    """Fill each selected closed loop (boundary or loose edges) with its
    optimal DOT patch (Delaunay-restricted optimal triangulation of the
    loop alone), or join two selected loops into one surface"""
    bl_idname = "mesh.dot_triangulate_loops"
    bl_label = "Triangulate Loops (DOT)"
    bl_options = {'REGISTER', 'UNDO'}

    preset: EnumProperty(name="Preset", default='SMOOTH',
                         items=preset_items())
    protect_edges: BoolProperty(
        name="Protect Edges", default=False,
        description="Split boundary edges that are not Delaunay so more loops "
        "can be filled (the faces beside them get the new vertices)")
    def prepare(self, context):
        selected = self.selected_loops(context)
        if selected is None:
            return None
        obj, bm, loops = selected
        if not self.check_several(loops, "loops"):
            return None
        vertices = geometry.vertex_array(bm)
        weights = self.weights("triangulate")
        normals = None
        if weights.normal_deviation:
            bm.normal_update()
            bm.verts.ensure_lookup_table()
            normals = [np.array([bm.verts[i].normal[:] for i in loop])
                       for loop in loops]
        # Rims of a surface come oriented against their faces: the surface
        # joining them must keep those directions to be wound like its
        # neighbours. Loose loops have no such direction.
        rims = all(e is not None and e.is_boundary
                   for loop in loops for e in _loop_edges(bm, loop))
        options = dot_client.TriangulateOptions(
            weights=weights, protect_edges=self.protect_edges,
            search_space=self.search_space.lower(),
            keep_loop_directions=self.one_surface and rims)
        state = {"loops": loops, "counts": (len(bm.verts), len(bm.faces))}
        if self.one_surface:
            forbidden = _face_chords(bm, loops) if rims else None
            return _surface_work([vertices[loop] for loop in loops], normals,
                                 options, forbidden), state
        return _triangulate_work([vertices[loop] for loop in loops], normals,
                                 options), state

    def finish(self, context, state, results):
        obj, bm = _edit_bmesh(context)
        geometry.check_unchanged(bm, *state["counts"])
        if self.one_surface:
            return self.finish_surface(bm, obj, state["loops"], results)
        problems = [f"loop {k + 1}: {describe(r.error)}"
                    for k, r in enumerate(results) if r.error is not None]
        if len(problems) == len(results):
            return report_filled(self, 0, len(results), problems, {})
        self.select_only_new(bm)
        stats, filled = {}, 0
        for loop, result in zip(state["loops"], results):
            if result.error is None:
                geometry.add_patch(bm, loop, result.vertices,
                                   result.triangles, result.summary, stats)
                filled += 1
        self.update(obj, bm)
        return report_filled(self, filled, len(results), problems, stats)

    def finish_surface(self, bm, obj, loops, result):
        if result.error is not None:
            return report_filled(self, 0, 1, [describe(result.error)], {})
        self.select_only_new(bm)
        stats = {}
        geometry.add_patch(bm, [v for loop in loops for v in loop],
                           result.vertices, result.triangles, result.summary,
                           stats)
        self.update(obj, bm)
        if result.summary.reversed_loops:
            self.report({'INFO'}, "DOT: the second loop runs the other way "
                        "along the surface; recalculate normals if needed")
        if len(result.summary.bridges):
            self.report({'INFO'}, f"DOT: {len(loops)} loops joined by "
                        f"{len(result.summary.bridges)} bridges first (the "
                        "optimum for them: an approximation)")
        return report_filled(self, 1, 1, [], stats)


# -- mesh.dot_fill_holes ----------------------------------------------------


class HoleLimitProps:
    """Which holes Fill Holes fills and Select Holes selects: the same
    limits (FillOptions' selection), so a listing shows what a fill does."""
    max_hole_edges: IntProperty(
        name="Max Hole Edges", default=0, min=0,
        description="Only holes with at most this many edges (0: any)")
    max_hole_diameter: FloatProperty(
        name="Max Hole Diameter", default=0.0, min=0.0, subtype='DISTANCE',
        description="Only holes at most this wide, bounding-box diagonal "
        "in the object's units (0: any)")
    skip_longest: BoolProperty(
        name="Skip Longest Border", default=False,
        description="Leave the longest border open (a terrain's rim)")


class MESH_OT_dot_fill_holes(DotOperator, WeightProps, HoleLimitProps,
                             bpy.types.Operator):
    """Fill every hole of the active mesh (in Object Mode, of every
    selected mesh) through the DOT server's FillHoles: the optimal patch,
    refined and faired into the surface"""
    bl_idname = "mesh.dot_fill_holes"
    bl_label = "Fill Holes (DOT)"
    bl_options = {'REGISTER', 'UNDO'}

    stage: EnumProperty(name="Stage", items=STAGES, default='FAIR')
    merge_duplicates: BoolProperty(
        name="Merge Duplicate Vertices", default=True,
        description="First merge vertices at exactly the same position, as "
        "dotctl's repair does: a mesh imported with split vertices (OBJ, "
        "STL) otherwise has holes that repeat a vertex and cannot be filled")
    preset: EnumProperty(
        name="Weights", default='SMOOTH', items=preset_items(),
        description="The patches' metric weights (Smooth is the service's "
        "default; area and perimeter are per hole scale)")

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type == 'MESH' and context.mode in (
            'OBJECT', 'EDIT_MESH')

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "stage")
        layout.prop(self, "max_hole_edges")
        layout.prop(self, "max_hole_diameter")
        layout.prop(self, "skip_longest")
        layout.prop(self, "merge_duplicates")
        layout.prop(self, "preset")
        self.draw_weights(layout, self.preset == 'CUSTOM')

    @staticmethod
    def _bmesh(obj):
        if obj.mode == 'EDIT':
            return bmesh.from_edit_mesh(obj.data), True
        bm = bmesh.new()
        bm.from_mesh(obj.data)
        return bm, False

    @staticmethod
    def _targets(context):
        """Edit Mode: the mesh being edited. Object Mode: every selected
        mesh object (the active one first), or the active one alone."""
        active = context.active_object
        if active.mode == 'EDIT':
            return [active]
        chosen = [o for o in context.selected_objects
                  if o.type == 'MESH' and o is not active]
        return [active] + sorted(chosen, key=lambda o: o.name)

    def prepare(self, context):
        meshes = []  # (object name, vertices, faces, corners, state)
        for obj in self._targets(context):
            bm, edit = self._bmesh(obj)
            try:
                merged = 0
                if self.merge_duplicates:
                    merged = geometry.merge_coincident(bm)
                    if merged and edit:
                        bmesh.update_edit_mesh(obj.data, destructive=True)
                    elif merged:
                        bm.to_mesh(obj.data)
                        obj.data.update()
                if not any(e.is_boundary for e in bm.edges):
                    continue
                faces, owner = geometry.triangles(bm)
                corners = geometry.corner_data(bm)
                meshes.append((obj.name, geometry.vertex_array(bm), faces,
                               corners,
                               {"faces": faces, "owner": owner,
                                "corners": corners,
                                "counts": (len(bm.verts), len(bm.faces)),
                                "merged": merged}))
            finally:
                if not edit:
                    bm.free()
        if not meshes:
            self.report({'INFO'}, "DOT: the mesh has no holes")
            return None
        options = dot_client.FillOptions(
            stage=self.stage.lower(), weights=self.weights("fill"),
            max_hole_edges=self.max_hole_edges,
            max_hole_diameter=self.max_hole_diameter,
            skip_longest=self.skip_longest, no_repair=True)
        works = [(name, _fill_work(v, f, options, c))
                 for name, v, f, c, _ in meshes]

        def work(client, cancel, progress):
            # One mesh after another over the one connection; a stop keeps
            # the meshes done and the holes finished in the one it hit.
            done = []
            for i, (name, fill) in enumerate(works):
                def step(fraction, text, i=i, name=name):
                    prefix = (f"{name} ({i + 1} of {len(works)}): "
                              if len(works) > 1 else "")
                    progress((i + fraction) / len(works), prefix + text)
                try:
                    done.append(fill(client, cancel, step))
                except dot_client.FillStopped as stopped:
                    done.append(stopped.result)
                    raise dot_client.FillStopped(stopped.code,
                                                 stopped.message, done)
            return done
        return work, [(name, state) for name, _, _, _, state in meshes]

    def finish(self, context, state, results):
        lines = []
        totals = [0, 0, 0]  # filled, loops, closed meshes
        for (name, st), result in zip(state, results):
            obj = bpy.data.objects[name]
            bm, edit = self._bmesh(obj)
            try:
                geometry.check_unchanged(bm, *st["counts"])
                if edit:
                    for f in bm.faces:
                        f.select_set(False)
                geometry.add_patches(bm, result.patches, st["counts"][0],
                                     st["faces"], st["owner"], st["corners"])
                bm.normal_update()
                if edit:
                    bm.select_flush_mode()
                    bmesh.update_edit_mesh(obj.data, loop_triangles=True,
                                           destructive=True)
                else:
                    bm.to_mesh(obj.data)
                    obj.data.update()
            finally:
                if not edit:
                    bm.free()
            r = result.report
            for p in _hole_problems(r):
                self.report({'WARNING'}, f"DOT: {name}: {p}" if len(state) > 1
                            else f"DOT: {p}")
            merged = st.get("merged", 0)
            lines.append(f"{r.filled} of {r.loops} holes filled"
                         f" ({r.skipped} skipped), +{r.added_vertices} "
                         f"vertices, +{r.added_faces} faces"
                         + (", closed" if r.closed else "")
                         + (f"; merged {merged} duplicate vertices first"
                            if merged else ""))
            totals[0] += r.filled
            totals[1] += r.loops
            totals[2] += r.closed
        if len(lines) == 1:
            self.report({'INFO'}, f"DOT: {lines[0]}")
        else:
            for (name, _), line in zip(state, lines):
                self.report({'INFO'}, f"DOT: {name}: {line}")
            self.report({'INFO'}, f"DOT: {len(lines)} meshes: {totals[0]} "
                        f"of {totals[1]} holes filled, {totals[2]} closed")
        return {'FINISHED'}


# -- mesh.dot_select_holes --------------------------------------------------


class MESH_OT_dot_select_holes(DotOperator, HoleLimitProps,
                               bpy.types.Operator):
    """Find the holes of the mesh through the DOT server (FillHoles with
    dry_run: nothing is filled), select the rims of those Fill Holes would
    fill with these limits, and report their sizes"""
    bl_idname = "mesh.dot_select_holes"
    bl_label = "Select Holes (DOT)"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return context.mode == 'EDIT_MESH'

    def prepare(self, context):
        obj, bm = _edit_bmesh(context)
        loops, _ = geometry.boundary_loops(bm)
        if not loops:
            self.report({'INFO'}, "DOT: the mesh has no holes")
            return None
        vertices = geometry.vertex_array(bm)
        faces, _ = geometry.triangles(bm)
        options = dot_client.FillOptions(
            max_hole_edges=self.max_hole_edges,
            max_hole_diameter=self.max_hole_diameter,
            skip_longest=self.skip_longest, no_repair=True)
        state = {"loops": loops,
                 "centroids": [geometry.loop_centroid(bm, l) for l in loops],
                 "counts": (len(bm.verts), len(bm.faces))}

        def work(client, cancel, progress):
            progress(0.0, "finding the holes")
            return client.list_holes(vertices, faces, options=options,
                                     cancel=cancel)
        return work, state

    def finish(self, context, state, report):
        obj, bm = _edit_bmesh(context)
        geometry.check_unchanged(bm, *state["counts"])
        listed = [h for h in report.holes if h.status == "listed"]
        # Each listed hole is the rim whose centroid is nearest its own.
        centroids = np.array(state["centroids"]).reshape(-1, 3)
        chosen = []
        for h in listed:
            d = np.linalg.norm(centroids - np.array(h.centroid), axis=1)
            chosen.append(state["loops"][int(np.argmin(d))])
        geometry.select_loop_edges(bm, chosen)
        bm.select_flush_mode()
        bmesh.update_edit_mesh(obj.data)
        sizes = sorted(h.boundary_vertices for h in listed)
        reasons = sorted({h.reason for h in report.holes
                          if h.status == "skipped" and h.reason})
        self.report({'INFO'}, f"DOT: {report.loops} holes: {len(listed)} "
                    "selected"
                    + (f" ({sizes[0]} edges)" if sizes and sizes[0] == sizes[-1]
                       else f" ({sizes[0]} to {sizes[-1]} edges)" if sizes
                       else "")
                    + (f", {report.skipped} left out ({'; '.join(reasons)})"
                       if report.skipped else ""))
        return {'FINISHED'}


# -- mesh.dot_triangulate_curve ---------------------------------------------


def _curve_loops(obj):
    """Closed splines of a curve object, or closed loops of a polyline mesh
    object, as (n, 3) arrays in the object's space; and how many open
    chains were skipped."""
    loops, skipped = [], 0
    if obj.type == 'CURVE':
        for spline in obj.data.splines:
            if not spline.use_cyclic_u:
                skipped += 1
                continue
            if spline.type == 'BEZIER':
                pts = _bezier_points(spline, max(1, spline.resolution_u))
            else:
                pts = [p.co.xyz[:] for p in spline.points]
            pts = _drop_repeats(np.array(pts, dtype=np.float64).reshape(-1, 3))
            if len(pts) >= 3:
                loops.append(pts)
            else:
                skipped += 1
    else:
        bm = bmesh.new()
        bm.from_mesh(obj.data)
        try:
            bm.verts.index_update()
            ids, skipped = geometry.closed_loops_of_edges(bm)
            vertices = geometry.vertex_array(bm)
            loops = [vertices[i] for i in ids]
        finally:
            bm.free()
    return loops, skipped


def _bezier_points(spline, resolution):
    from mathutils.geometry import interpolate_bezier
    pts = []
    bp = spline.bezier_points
    for i in range(len(bp)):
        a, b = bp[i], bp[(i + 1) % len(bp)]
        seg = interpolate_bezier(a.co, a.handle_right, b.handle_left, b.co,
                                 resolution + 1)
        pts += [p[:] for p in seg[:-1]]
    return pts


def _drop_repeats(pts):
    if len(pts) == 0:
        return pts
    keep = np.ones(len(pts), dtype=bool)
    keep[1:] = np.any(pts[1:] != pts[:-1], axis=1)
    if len(pts) > 1 and np.all(pts[-1] == pts[0]):
        keep[-1] = False
    return pts[keep]


class MESH_OT_dot_triangulate_curve(DotOperator, WeightProps,
                                    TriangulateProps, bpy.types.Operator):
    """Turn the selected closed curve or polyline into a triangulated
    surface (lofting, sketch-based surfacing)"""
    bl_idname = "mesh.dot_triangulate_curve"
    bl_label = "Triangulate Curve (DOT)"
    bl_options = {'REGISTER', 'UNDO'}

    preset: EnumProperty(
        name="Preset", default='SMOOTH',
        items=preset_items(leave_out=("follow_normals",)))  # no normals
    protect_edges: BoolProperty(
        name="Protect Edges", default=False,
        description="Split curve segments that are not Delaunay so more "
        "curves can be triangulated")
    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return (context.mode == 'OBJECT' and obj is not None
                and obj.type in ('CURVE', 'MESH'))

    def prepare(self, context):
        obj = context.active_object
        if obj.type == 'MESH' and len(obj.data.polygons):
            self.report({'ERROR'}, "DOT: the mesh has faces; select a curve "
                        "or a polyline (edges only), or use Fill Loops")
            return None
        loops, skipped = _curve_loops(obj)
        if skipped:
            self.report({'WARNING'}, f"DOT: {skipped} open curves skipped "
                        "(only closed ones bound a surface)")
        if not loops:
            self.report({'ERROR'}, f"DOT: {obj.name} has no closed curve "
                        "(make it cyclic: Curve > Toggle Cyclic)")
            return None
        weights = self.weights("triangulate")
        if weights.normal_deviation:
            self.report({'ERROR'}, "DOT: curves have no normals: set the "
                        "normal deviation weight to 0")
            return None
        if not self.check_several(loops, "closed curves"):
            return None
        options = dot_client.TriangulateOptions(
            weights=weights, protect_edges=self.protect_edges,
            search_space=self.search_space.lower())
        work = (_surface_work if self.one_surface else _triangulate_work)
        return work(loops, None, options), {"object": obj.name}

    def finish(self, context, state, results):
        if self.one_surface:
            results = [results]  # one surface through every curve
        source = bpy.data.objects[state["object"]]
        bm = bmesh.new()
        problems, filled = [], 0
        try:
            index = {}
            for k, r in enumerate(results):
                if r.error is not None:
                    problems.append(f"curve {k + 1}: {describe(r.error)}")
                    continue
                verts = []
                for p in r.vertices:  # loops sharing points share vertices
                    key = tuple(p)
                    if key not in index:
                        index[key] = bm.verts.new(p)
                    verts.append(index[key])
                for t in r.triangles:
                    try:
                        bm.faces.new([verts[int(i)] for i in t])
                    except ValueError:
                        pass  # the same face from two loops
                filled += 1
            if filled == 0:
                return report_filled(self, 0, len(results), problems, {})
            bm.normal_update()
            mesh = bpy.data.meshes.new(f"{source.name} DOT surface")
            bm.to_mesh(mesh)
        finally:
            bm.free()
        obj = bpy.data.objects.new(mesh.name, mesh)
        obj.matrix_world = source.matrix_world.copy()
        collections = source.users_collection or [context.scene.collection]
        for c in collections:
            c.objects.link(obj)
        for o in context.selected_objects:
            o.select_set(False)
        obj.select_set(True)
        context.view_layer.objects.active = obj
        return report_filled(self, filled, len(results), problems, {})


# -- mesh.dot_surface_curves ------------------------------------------------


def _wire_of(context, obj):
    """(points (n, 3), edges (e, 2)) of a curve object as Blender evaluates
    it (Bezier and NURBS splines sampled at their resolution, modifiers
    applied), without bevel, extrusion or fill; or of an edges-only mesh.
    Object space. Also the number of faces it evaluates to (a modifier
    that makes a surface)."""
    copy = temporary = evaluated = None
    try:
        if obj.type == 'MESH':
            data = obj.data
        else:
            # A copy with no surface of its own: bevel, extrusion and a 2D
            # curve's fill would turn the curve into faces.
            copy = obj.data.copy()
            copy.bevel_depth = 0.0
            copy.extrude = 0.0
            copy.bevel_mode = 'ROUND'
            copy.bevel_object = None
            if copy.dimensions == '2D':
                copy.fill_mode = 'NONE'
            temporary = obj.copy()
            temporary.data = copy
            temporary.hide_viewport = False
            context.scene.collection.objects.link(temporary)
            evaluated = temporary.evaluated_get(
                context.evaluated_depsgraph_get())
            data = evaluated.to_mesh()
        points = np.zeros(3 * len(data.vertices))
        data.vertices.foreach_get("co", points)
        edges = np.zeros(2 * len(data.edges), dtype=np.int64)
        data.edges.foreach_get("vertices", edges)
        faces = len(data.polygons)
    finally:
        if evaluated is not None:
            evaluated.to_mesh_clear()
        if temporary is not None:
            bpy.data.objects.remove(temporary)
        if copy is not None:
            bpy.data.curves.remove(copy)
    return points.reshape(-1, 3), edges.reshape(-1, 2), faces


def surface_status(p):
    """The status bar's text for a dot_client.SurfaceProgress."""
    if not p.patches_total:
        return "finding the patches"
    return f"{p.patches_done} of {p.patches_total} patches"


class MESH_OT_dot_surface_curves(DotOperator, WeightProps, bpy.types.Operator):
    """Turn the curve network of the active curve object (its splines, or
    the edges of a wire mesh) into one surface through the DOT server's
    SurfaceNetwork: the patches the curves bound found, each triangulated,
    refined and faired with its neighbours; spline ends that meet become
    junctions"""
    bl_idname = "mesh.dot_surface_curves"
    bl_label = "Surface Curve Network (DOT)"
    bl_options = {'REGISTER', 'UNDO'}

    stage: EnumProperty(name="Stage", items=STAGES, default='FAIR')
    preset: EnumProperty(
        name="Weights", default='DEFAULT',
        items=[('DEFAULT', "Surface Default", "The service's: least squared "
                "dihedral angles, triangles facing like the normals the "
                "patches on each curve share, a little area")] +
        preset_items())
    skip_longest: BoolProperty(
        name="Skip Longest Cycle", default=False,
        description="Leave the longest cycle open (the rim of an open "
        "sheet: otherwise a second patch covers the sheet from behind)")
    islands: EnumProperty(
        name="Lone Loops", default='INSET',
        description="A closed spline alone inside a face the other curves "
        "bound (a circle drawn on a box's lid)",
        items=[('INSET', "Inset", "An island of the face around it and a "
                "patch of its own: the surface stays closed"),
               ('HOLE', "Hole", "An island of the face around it only: a "
                "hole in that face"),
               ('OFF', "Own Patch", "A patch of its own only")])
    walls: BoolProperty(
        name="Walls", default=False,
        description="Also find walls: flat cycles that make a third patch "
        "on their curves (a partition inside a box). Off: a ring of curves "
        "around a body is only the line between two patches")
    weld_distance: FloatProperty(
        name="Weld Distance", default=1e-4, min=0.0, soft_max=0.1,
        precision=4, subtype='DISTANCE', unit='LENGTH',
        description="A spline's free end is welded to the nearest point "
        "of another spline within this distance (object space), so "
        "strokes that nearly meet become junctions; ends that coincide "
        "always meet")

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return (context.mode == 'OBJECT' and obj is not None
                and obj.type in ('CURVE', 'MESH'))

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "stage")
        layout.prop(self, "skip_longest")
        layout.prop(self, "islands")
        layout.prop(self, "walls")
        layout.prop(self, "weld_distance")
        layout.prop(self, "preset")
        self.draw_weights(layout, self.preset == 'CUSTOM')

    def prepare(self, context):
        obj = context.active_object
        if obj.type == 'MESH' and len(obj.data.polygons):
            self.report({'ERROR'}, "DOT: the mesh has faces; select a curve "
                        "object or a wire mesh (edges only)")
            return None
        points, edges, faces = _wire_of(context, obj)
        if faces:
            self.report({'ERROR'}, f"DOT: {obj.name} evaluates to faces "
                        "(a modifier makes a surface); remove it first")
            return None
        vertices, polylines = geometry.curve_network(points, edges)
        if not polylines:
            self.report({'ERROR'}, f"DOT: {obj.name} has no curves")
            return None
        options = dot_client.SurfaceOptions(
            stage=self.stage.lower(), skip_longest=self.skip_longest,
            islands=self.islands.lower(), walls=self.walls,
            weld_distance=self.weld_distance,
            weights=None if self.preset == 'DEFAULT' else self.weights("fill"))

        def work(client, cancel, progress):
            progress(0.0, "sending the curves")
            return client.surface_network(
                vertices, polylines, options=options, cancel=cancel,
                progress=lambda p: progress(
                    p.patches_done / max(1, p.patches_total),
                    surface_status(p)))
        return work, {"object": obj.name}

    def finish(self, context, state, result):
        source = bpy.data.objects[state["object"]]
        r = result.report
        for p in r.patches:
            if p.status == "failed":
                self.report({'WARNING'}, f"DOT: patch {p.id} "
                            f"({p.boundary_vertices} curve points) failed: "
                            f"{p.reason}")
        if r.surfaced == 0 or len(result.faces) == 0:
            self.report({'ERROR'}, f"DOT: no patch was surfaced "
                        f"({len(r.patches)} found)")
            return {'CANCELLED'}
        # The vertices the faces use, in order (a curve that bounds no
        # patch, or a failed patch's, adds none).
        used, faces = np.unique(result.faces, return_inverse=True)
        mesh = bpy.data.meshes.new(f"{source.name}_surface")
        mesh.from_pydata(result.vertices[used].tolist(), [],
                         faces.reshape(-1, 3).tolist())
        mesh.update()
        obj = bpy.data.objects.new(mesh.name, mesh)
        obj.matrix_world = source.matrix_world.copy()
        for c in source.users_collection or [context.scene.collection]:
            c.objects.link(obj)
        for o in context.selected_objects:
            o.select_set(False)
        obj.select_set(True)
        context.view_layer.objects.active = obj
        notes = []
        if r.failed:
            notes.append(f"{r.failed} failed")
        if r.dangling:
            notes.append(f"{len(r.dangling)} curves bound no patch")
        if r.merged_vertices:
            notes.append(f"{r.merged_vertices} points welded")
        for note in r.notes:  # the summary below is the last: it shows
            self.report({'INFO'}, f"DOT: {note}")
        self.report({'INFO'}, f"DOT: {r.surfaced} of {len(r.patches)} "
                    f"patches surfaced"
                    + (", closed" if r.closed else "")
                    + (f" ({'; '.join(notes)})" if notes else ""))
        return {'FINISHED'}


classes = (MESH_OT_dot_fill_loops, MESH_OT_dot_triangulate_loops,
           MESH_OT_dot_fill_holes, MESH_OT_dot_select_holes,
           MESH_OT_dot_triangulate_curve, MESH_OT_dot_surface_curves)

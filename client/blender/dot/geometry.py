# SPDX-License-Identifier: AGPL-3.0-or-later
"""bmesh in, numpy out, and DOT results back into the bmesh: loops of
selected boundary edges, the mesh as triangles for FillHoles, patches
joined to their boundary (edges split where DOT inserted vertices, no
duplicate vertices, faces wound like their neighbours)."""
from collections import defaultdict

import bmesh
import numpy as np
from mathutils import Vector


class MeshChanged(Exception):
    """The mesh is not the one DOT worked on."""


def selected_loops(bm):
    """Closed loops of selected boundary (one face) or wire (no face)
    edges, as lists of vertex indices in loop order, each oriented against
    the faces beside it so a patch running the same way is wound like its
    neighbours; and the number of selected chains that are not closed
    simple loops (skipped)."""
    adjacent = defaultdict(list)
    for e in bm.edges:
        if e.select and not e.hide and (e.is_boundary or e.is_wire):
            a, b = e.verts
            adjacent[a.index].append((b.index, e))
            adjacent[b.index].append((a.index, e))
    loops, skipped, seen = [], 0, set()
    for start in adjacent:
        if start in seen:
            continue
        component, stack = {start}, [start]
        while stack:  # the connected chain, bounded by the edge count
            v = stack.pop()
            for w, _ in adjacent[v]:
                if w not in component:
                    component.add(w)
                    stack.append(w)
        seen |= component
        if len(component) < 3 or any(len(adjacent[v]) != 2 for v in component):
            skipped += 1
            continue
        order, previous_edge, v = [start], None, start
        for _ in range(len(component)):
            (w, e) = next((w, e) for w, e in adjacent[v] if e is not previous_edge)
            if w == start:
                break
            order.append(w)
            previous_edge, v = e, w
        loops.append(_orient(bm, order))
    return loops, skipped


def _orient(bm, order):
    bm.verts.ensure_lookup_table()
    n = len(order)
    for i in range(n):
        a, b = bm.verts[order[i]], bm.verts[order[(i + 1) % n]]
        e = bm.edges.get((a, b))
        if e is None or not e.link_faces:
            continue
        for loop in e.link_faces[0].loops:
            if loop.vert == a and loop.link_loop_next.vert == b:
                # The face runs a -> b: the patch must run b -> a.
                return order[::-1]
        return order
    return order  # a wire loop: any direction


def vertex_array(bm):
    return np.array([v.co[:] for v in bm.verts], dtype=np.float64).reshape(-1, 3)


def triangles(bm):
    """The mesh as triangles (Blender's loop triangulation of each face):
    (T, 3) vertex indices and, per triangle, the index of its face."""
    bm.verts.index_update()
    bm.faces.index_update()
    tris = bm.calc_loop_triangles()
    faces = np.array([[l.vert.index for l in t] for t in tris],
                     dtype=np.int64).reshape(-1, 3)
    owner = np.array([t[0].face.index for t in tris], dtype=np.int64)
    return faces, owner


def check_unchanged(bm, vertex_count, face_count):
    if len(bm.verts) != vertex_count or len(bm.faces) != face_count:
        raise MeshChanged("the mesh changed while DOT was working; run the "
                          "operator again")


def _example_face(verts):
    for v in verts:
        for f in v.link_faces:
            return f
    return None


def _new_face(bm, verts, example, stats):
    try:
        f = bm.faces.new(verts, example) if example else bm.faces.new(verts)
    except ValueError:  # the face exists already
        stats["duplicates"] = stats.get("duplicates", 0) + 1
        return None
    f.select_set(True)
    return f


def add_patch(bm, loop, vertices, triangles, summary, stats):
    """Joins one Triangulate result to its loop (vertex indices). Vertices
    DOT inserted (edge protection) split the loop's edges where they lie,
    so the faces beside them take them too. Returns the new faces."""
    bm.verts.ensure_lookup_table()
    n = len(loop)
    verts = {i: bm.verts[v] for i, v in enumerate(loop)}
    example = _example_face(verts.values())
    ids = [int(i) for i in summary.loop] if summary.inserted_count else list(range(n))
    originals = [k for k, i in enumerate(ids) if i < n]
    for a_at, b_at in zip(originals, originals[1:] + [originals[0] + len(ids)]):
        inserted = [ids[k % len(ids)] for k in range(a_at + 1, b_at)]
        if not inserted:
            continue
        a, b = verts[ids[a_at]], verts[ids[b_at % len(ids)]]
        edge, at = bm.edges.get((a, b)), a
        for k in inserted:
            target = Vector(vertices[k])
            length = (b.co - at.co).length
            fac = (target - at.co).length / length if length > 0 else 0.5
            _, v = bmesh.utils.edge_split(edge, at, min(max(fac, 0.0), 1.0))
            v.co = target
            verts[k] = v
            edge, at = bm.edges.get((v, b)), v
        stats["inserted"] = stats.get("inserted", 0) + len(inserted)
    faces = []
    for t in triangles:
        f = _new_face(bm, [verts[int(i)] for i in t], example, stats)
        if f is not None:
            faces.append(f)
    return faces


class _Union:
    def __init__(self):
        self.parent = {}

    def find(self, x):
        root = x
        while self.parent.setdefault(root, root) != root:
            root = self.parent[root]
        while self.parent[x] != root:  # path compression
            self.parent[x], x = root, self.parent[x]
        return root

    def join(self, a, b):
        self.parent[self.find(a)] = self.find(b)


def merge_coincident(bm):
    """Merges vertices at exactly the same position into the first one, as
    dotctl's repair does; returns how many were merged. (remove_doubles
    merges by distance, and at a tiny distance missed exact copies.)"""
    first = {}
    targets = {}
    for v in bm.verts:
        key = tuple(v.co)
        if key in first:
            targets[v] = first[key]
        else:
            first[key] = v
    if targets:
        bmesh.ops.weld_verts(bm, targetmap=targets)
    return len(targets)


def add_fill(bm, result, vertex_count, owner, keep_vertices=None):
    """Merges a FillHoles result made with no_repair from `triangles(bm)`
    into bm: the output's first vertices are bm's, its first len(owner)
    faces bm's triangles (those split by edge protection replaced by their
    first piece), then the pieces and patches. Faces split in place are
    rebuilt from their triangles. With `keep_vertices`, only the patches
    touching those vertex indices are added (the holes asked for).
    Returns (new faces, number of patches added)."""
    faces = result.faces
    first_new = len(owner)
    split = sorted({int(t) for h in result.report.holes
                    if h.status == "filled" for t in h.split_faces})
    # Patches: appended faces and split faces, joined across edges the input
    # did not have (chords, halves of split edges) and per Blender face.
    input_edges = {tuple(sorted((e.verts[0].index, e.verts[1].index)))
                   for e in bm.edges}
    union = _Union()
    by_edge = {}
    members = list(range(first_new, len(faces))) + split
    for f in members:
        union.find(f)
        t = faces[f]
        for i in range(3):
            e = tuple(sorted((int(t[i]), int(t[(i + 1) % 3]))))
            if e in input_edges:
                continue
            if e in by_edge:
                union.join(f, by_edge[e])
            else:
                by_edge[e] = f
    first_split_of = {}
    for t in split:
        p = int(owner[t])
        if p in first_split_of:
            union.join(t, first_split_of[p])
        else:
            first_split_of[p] = t
    groups = defaultdict(list)
    for f in members:
        groups[union.find(f)].append(f)
    kept = []
    for group in groups.values():
        if keep_vertices is None or any(
                int(v) in keep_vertices for f in group for v in faces[f]
                if v < vertex_count):
            kept.append(group)
    keep = {f for g in kept for f in g}
    rebuild = sorted({int(owner[t]) for t in split if t in keep})
    # The faces to make: every triangle of a rebuilt face, the kept
    # appended faces.
    triangles_of = defaultdict(list)
    for t, p in enumerate(owner):
        if int(p) in first_split_of:
            triangles_of[int(p)].append(t)
    make = [(faces[t], p) for p in rebuild for t in triangles_of[p]]
    make += [(faces[f], None) for f in range(first_new, len(faces)) if f in keep]
    bm.verts.ensure_lookup_table()
    bm.faces.ensure_lookup_table()
    existing = list(bm.verts)  # lookups go stale once faces are added
    old_faces = {p: bm.faces[p] for p in rebuild}
    verts = {}

    def vert(i):
        i = int(i)
        if i not in verts:
            verts[i] = (existing[i] if i < vertex_count
                        else bm.verts.new(result.vertices[i]))
        return verts[i]

    old = list(old_faces.values())
    old_edges = {e for f in old for e in f.edges}
    stats = {}
    new_faces = []
    for t, p in make:
        vs = [vert(i) for i in t]
        example = old_faces[p] if p is not None else _example_face(
            [v for v, i in zip(vs, t) if i < vertex_count])
        f = _new_face(bm, vs, example, stats)
        if f is not None:
            new_faces.append(f)
    if old:
        bmesh.ops.delete(bm, geom=old, context='FACES_ONLY')
        loose = [e for e in old_edges if e.is_valid and not e.link_faces]
        if loose:
            bmesh.ops.delete(bm, geom=loose, context='EDGES')
    return new_faces, len(kept)


def closed_loops_of_edges(bm):
    """Closed loops of a polyline mesh (edges, no faces) as vertex index
    lists; the number of chains that are not closed loops."""
    for e in bm.edges:
        e.select = not e.link_faces
    return selected_loops(bm)

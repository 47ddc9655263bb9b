# SPDX-License-Identifier: AGPL-3.0-or-later
"""bmesh in, numpy out, and DOT results back into the bmesh: loops of
selected boundary edges, the mesh as triangles for FillHoles, patches
joined to their boundary (edges split where DOT inserted vertices, no
duplicate vertices, faces wound like their neighbours). FillHoles answers
with patches (dot_client.FillPatches) in the ids of the triangles sent, so
a patch is added as it is: its new vertices, its faces, and the faces
whose triangles edge protection split, rebuilt. Curve networks for
SurfaceNetwork: a wire mesh as polylines."""
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
    return _loops(bm, lambda e: e.select and not e.hide and
                  (e.is_boundary or e.is_wire))


def boundary_loops(bm):
    """Every closed loop of boundary edges (the rims of the holes), as
    selected_loops gives them."""
    return _loops(bm, lambda e: e.is_boundary)


def loop_centroid(bm, loop):
    """The length-weighted centroid of a loop's edges, as FillHoles reports
    a hole's (HoleReport.centroid)."""
    bm.verts.ensure_lookup_table()
    points = np.array([bm.verts[i].co[:] for i in loop], dtype=np.float64)
    following = np.roll(points, -1, axis=0)
    length = np.linalg.norm(following - points, axis=1)
    if length.sum() == 0:
        return points.mean(axis=0)
    return ((points + following) / 2 * length[:, None]).sum(0) / length.sum()


def select_loop_edges(bm, loops):
    """Selects exactly the edges of `loops` (and their vertices)."""
    bm.verts.ensure_lookup_table()
    for f in bm.faces:
        f.select_set(False)
    for e in bm.edges:
        e.select_set(False)
    for v in bm.verts:
        v.select_set(False)
    for loop in loops:
        for a, b in zip(loop, loop[1:] + loop[:1]):
            e = bm.edges.get((bm.verts[a], bm.verts[b]))
            if e is not None:
                e.select_set(True)


def _loops(bm, keep):
    adjacent = defaultdict(list)
    for e in bm.edges:
        if keep(e):
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


# The most channels a FillHoles call carries.
MAX_LAYERS = 16


def _layers(bm):
    """The layers a fill carries into its new faces, as (channel name,
    layer, on_vertex, dims): UV maps and colour attributes, on face corners
    or on vertices (Blender 3.x bmesh names), the first MAX_LAYERS of them.
    Channels are named by position ("uv0", "color1"): a Blender name may be
    longer than the wire allows. Layers are listed by items(): iterating a
    layer collection fails on Blender 3.4's Python 3.11 (SystemError)."""
    found = [("uv", l, False, 2) for _, l in bm.loops.layers.uv.items()]
    for kind in ("color", "float_color"):
        for on_vertex, layers in ((False, bm.loops.layers),
                                  (True, bm.verts.layers)):
            if hasattr(layers, kind):
                found += [("color", l, on_vertex, 4)
                          for _, l in getattr(layers, kind).items()]
    return [(f"{what}{i}", l, on_vertex, dims)
            for i, (what, l, on_vertex, dims) in
            enumerate(found[:MAX_LAYERS])]


def _get(loop, layer, on_vertex, dims):
    data = loop.vert[layer] if on_vertex else loop[layer]
    return data.uv[:] if dims == 2 else data[:]


def corner_data(bm):
    """Each UV map and colour attribute at the corners of the triangles
    `triangles(bm)` gives, in its order: {channel name: float32 (3T, d)},
    for FillHoles' corner_data (so that new faces get values blended from
    their neighbours', seams kept)."""
    tris = bm.calc_loop_triangles()
    out = {}
    for name, layer, on_vertex, dims in _layers(bm):
        out[name] = np.array([_get(l, layer, on_vertex, dims)
                              for t in tris for l in t],
                             dtype=np.float32).reshape(-1, dims)
    return out


def _set_corners(bm, face, values, new_verts):
    """Sets `face`'s loops (in the order it was made) to `values` ({channel
    name: (3, d) rows}); a vertex layer is set on `new_verts` only."""
    for name, layer, on_vertex, dims in _layers(bm):
        rows = values.get(name)
        if rows is None:
            continue
        for loop, row in zip(face.loops, rows):
            if on_vertex:
                if loop.vert in new_verts:
                    loop.vert[layer] = row
            elif dims == 2:
                loop[layer].uv = row
            else:
                loop[layer] = row


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
    """Joins one Triangulate result to its loop (vertex indices; for a
    surface through several loops, their indices one loop after another).
    Vertices DOT inserted (edge protection) split the loops' edges where
    they lie, so the faces beside them take them too. Returns the new
    faces."""
    bm.verts.ensure_lookup_table()
    n = len(loop)
    verts = {i: bm.verts[v] for i, v in enumerate(loop)}
    example = _example_face(verts.values())
    if summary.inserted_count:
        # summary.loop lists each loop (cut by loop_sizes) with the inserted
        # vertices in place; each loop closes on itself.
        ids = [int(i) for i in summary.loop]
        sizes = list(summary.loop_sizes) or [len(ids)]
        begin = 0
        for size in sizes:
            _split_loop_edges(bm, verts, vertices, ids[begin:begin + size], n,
                              stats)
            begin += size
    faces = []
    for t in triangles:
        f = _new_face(bm, [verts[int(i)] for i in t], example, stats)
        if f is not None:
            faces.append(f)
    return faces


def _split_loop_edges(bm, verts, vertices, ids, n, stats):
    """Splits the edges of one loop (result ids, inserted ones >= n in
    place) at the vertices inserted on them; `verts` maps ids to bm
    vertices and gains the new ones."""
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


def loop_names(bm, loops):
    """One vertex of each loop to name it in FillOptions.loops_through: one
    with exactly two border edges where the loop has one, so that no other
    border loop passes through it (a vertex where two loops touch would
    name both)."""
    bm.verts.ensure_lookup_table()
    names = []
    for loop in loops:
        names.append(next(
            (i for i in loop
             if sum(1 for e in bm.verts[i].link_edges if e.is_boundary) == 2),
            loop[0]))
    return names


def patches_of_loops(patches, loops, vertex_count):
    """The patches that fill one of `loops` (every mesh vertex of their
    faces is on that loop), and the number of the others (a loop through a
    vertex that a selected loop touches)."""
    rims = [set(loop) for loop in loops]
    kept, others = [], 0
    for p in patches:
        on = {int(i) for i in p.faces.ravel() if i < vertex_count}
        if any(on <= rim for rim in rims):
            kept.append(p)
        else:
            others += 1
    return kept, others


def add_patches(bm, patches, vertex_count, faces, owner, corners=None):
    """Adds the patches of a FillHoles answer (dot_client.HolePatch) to bm.

    The answer is in the ids of what was sent, `faces, owner =
    triangles(bm)` with no_repair: vertex ids below `vertex_count` are
    bm's vertices, the others the patches' new vertices (numbered on from
    `vertex_count`, patch after patch; patches left out keep their ids
    unused), and a replaced face is a triangle of `faces`. Each bm face
    with a replaced triangle is rebuilt from its loop triangles, the
    replaced ones swapped for their replacements (the edges it no longer
    uses go with it). `corners`: the corner_data(bm) that was sent, whose
    channels the patches carry: every new face's UVs and colours are set
    from them (a rebuilt face's untouched triangles keep what they had).
    Returns (new faces, stats)."""
    # Checked before bm changes: a patch that does not fit is refused whole.
    new_ids = {p.first_vertex + k for p in patches
               for k in range(len(p.vertices))}
    replaced = {}
    for p in patches:
        for t, pieces in p.replaced_faces.items():
            if not 0 <= t < len(owner):
                raise ValueError(f"a patch replaces triangle {t}, but "
                                 f"{len(owner)} were sent")
            replaced[t] = pieces
        for tri in [p.faces] + list(p.replaced_faces.values()):
            for i in tri.ravel():
                if not (0 <= i < vertex_count or int(i) in new_ids):
                    raise ValueError(f"a patch refers to vertex {int(i)}, "
                                     "which is neither the mesh's nor new")
    bm.verts.ensure_lookup_table()
    bm.faces.ensure_lookup_table()
    existing = list(bm.verts)  # lookups go stale once vertices are added
    new_verts = {}
    for p in patches:
        for k, co in enumerate(p.vertices):
            new_verts[p.first_vertex + k] = bm.verts.new(co)

    def vert(i):
        i = int(i)
        return existing[i] if i < vertex_count else new_verts[i]

    corners = corners or {}
    replaced_values = {t: p.replaced_corner_data.get(t, {})
                       for p in patches for t in p.replaced_faces}

    def rows(data, k):  # {name: (3, d)} of triangle k of data's
        return {name: a[3 * k:3 * k + 3] for name, a in data.items()}

    rebuilt = {int(owner[t]) for t in replaced}
    # (vertex ids, the face to copy attributes from, corner values)
    make = []
    old_faces = {f: bm.faces[f] for f in rebuilt}
    for t, f in enumerate(owner):
        f = int(f)
        if f not in rebuilt:
            continue
        if t in replaced:
            for k, tri in enumerate(replaced[t]):
                make.append((tri, old_faces[f], rows(replaced_values[t], k)))
        else:
            make.append((faces[t], old_faces[f], rows(corners, t)))
    for p in patches:
        for k, tri in enumerate(p.faces):
            make.append((tri, None, rows(p.corner_data, k)))
    stats = {}
    new_faces = []
    added = set(new_verts.values())
    for tri, example, values in make:
        vs = [vert(i) for i in tri]
        if example is None:
            example = _example_face([v for v, i in zip(vs, tri)
                                     if i < vertex_count])
        f = _new_face(bm, vs, example, stats)
        if f is not None:
            new_faces.append(f)
            if values:
                _set_corners(bm, f, values, added)
    old = list(old_faces.values())
    if old:
        old_edges = {e for f in old for e in f.edges}
        bmesh.ops.delete(bm, geom=old, context='FACES_ONLY')
        loose = [e for e in old_edges if e.is_valid and not e.link_faces]
        if loose:  # a split boundary edge, now two halves
            bmesh.ops.delete(bm, geom=loose, context='EDGES')
    return new_faces, stats


def closed_loops_of_edges(bm):
    """Closed loops of a polyline mesh (edges, no faces) as vertex index
    lists; the number of chains that are not closed loops."""
    for e in bm.edges:
        e.select = not e.link_faces
    return selected_loops(bm)


def curve_network(points, edges):
    """A curve network from a wire mesh (a curve converted: a vertex per
    evaluated point, an edge per segment; splines do not share vertices,
    so their ends meet only by coordinates, which the server welds): the
    points on an edge, and the wire as polylines, each a chain of edges
    between points where other than two edges meet (a spline, or its
    pieces between junctions an edges-only mesh shares), a closed chain
    ending at its first point, in the order of their first points (spline
    k is polyline k). An edge between two points at the same place (a
    cyclic spline's repeated point, a zero-length segment) is left out:
    the server welds its ends. Returns (vertices (V, 3), polylines: lists
    of indices into them)."""
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    apart = np.any(points[edges[:, 0]] != points[edges[:, 1]], axis=1)
    edges = np.unique(np.sort(edges[apart], axis=1), axis=0)
    if len(edges) == 0:
        return np.zeros((0, 3)), []
    used, local = np.unique(edges, return_inverse=True)
    edges = local.reshape(-1, 2)
    incident = defaultdict(list)  # point: the edges at it
    for e, (a, b) in enumerate(edges.tolist()):
        incident[a].append(e)
        incident[b].append(e)
    done = np.zeros(len(edges), dtype=bool)

    def walk(start, e):  # from `start` along edge e to a chain's end
        chain = [start]
        while not done[e]:
            done[e] = True
            a, b = edges[e]
            chain.append(int(b if a == chain[-1] else a))
            at = incident[chain[-1]]
            if len(at) != 2:
                break
            e = at[1] if at[0] == e else at[0]
        return chain

    ends = [p for p in sorted(incident) if len(incident[p]) != 2]
    polylines = [walk(p, e) for p in ends for e in incident[p] if not done[e]]
    polylines += [walk(int(edges[e, 0]), e) for e in range(len(edges))
                  if not done[e]]  # closed chains (cyclic splines)
    polylines.sort(key=min)
    return points[used], polylines

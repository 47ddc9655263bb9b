# SPDX-License-Identifier: AGPL-3.0-or-later
"""meshio meshes in and out of :meth:`Client.fill_holes` and
:meth:`Client.list_holes`.

Imported only when a :class:`meshio.Mesh` is passed (or
``dot_client.FilledMesh`` is named), so dot_client itself needs no meshio.

A mesh is filled through the patches answer of FillHoles: the server gets
the mesh's points and its surface cells (``triangle``, ``quad`` and
``polygon`` blocks, in order) with its point data as attribute channels,
and answers only what is new, in the ids sent. The result is the mesh as
it was read, every point, cell and datum as they were (any dtype), with
the new points and triangles added; what the service interpolates (point
data of up to 16 numbers a point) is carried into the new points, and
what it cannot carry gets a documented default, named in
``report.notes``. See :class:`FilledMesh`.
"""
from __future__ import annotations

import contextlib
import copy
import io
import os
import sys
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple, Union

import meshio
import numpy as np

from ._errors import InvalidInput
from ._types import FillPatches, FillReport

SURFACE_CELLS = ("triangle", "quad", "polygon")
# Point data sent as the service's "normal" channel, whose new values are
# the patch's own normals rather than a blend: PLY's three scalars, or the
# first (V, 3) array of these names (meshio's OBJ reader says "obj:vn").
PLY_NORMALS = ("nx", "ny", "nz")
NORMAL_KEYS = ("normal", "normals", "Normals", "obj:vn")
# Cell data of this name (meshio's STL reader and writer) gets the new
# triangles' unit normals instead of zeros.
FACET_NORMALS = "facet_normals"
MAX_CHANNELS = 16  # the service's limits (README "Attributes")
MAX_FLOATS = 16


class FilledMesh(meshio.Mesh):
    """A :class:`meshio.Mesh` filled by :meth:`Client.fill_holes`, with
    the fill's :class:`FillReport` as ``report`` (which holes were filled,
    and in ``report.notes`` any point or cell data not carried into the
    new points and triangles). It is a plain meshio.Mesh otherwise:
    ``filled.write("closed.ply")``, ``meshio.write(...)``, ``copy()``.

    It is the mesh as it was given, with what the fill adds (the server's
    repair finds the holes but is not applied to it). Points: the mesh's,
    unchanged, then each patch's new points, patch after patch (dtype of
    the mesh's points). Cells: every block as it was, except the surface
    faces edge protection split: in a ``triangle`` block such a face is
    replaced in place by the first of its triangles; in a ``quad`` or
    ``polygon`` block it is removed (later cells of that block move up
    one). The other pieces of split faces, then every patch's triangles,
    are appended to the mesh's last ``triangle`` block (a new
    ``triangle`` block at the end when it has none). Points at exactly the
    same place (which the repair merged to find the holes) are named in
    the new triangles by the copy the faces around the hole use; where a
    hole's rim meets two copies of one point (a pinched point, a seam of
    split points across the hole) it cannot close unless they are one, so
    they are welded: every surface cell naming one names the lowest (a
    note lists them; the others stay, unused).

    Point data: the mesh's rows unchanged; new points get the values the
    service interpolated (harmonic from the hole's rim; a point's normals,
    ``nx ny nz`` or a (V, 3) ``normal``/``normals``/``Normals``/``obj:vn``,
    the patch's own unit normals), rounded to single precision and cast
    back to each array's dtype (integers rounded and clipped to their
    range). Arrays the service cannot carry (booleans, strings, more than
    16 numbers a point, values not finite in float32, arrays beyond 16
    channels of 16 numbers) get zeros (False, "") for new points, and a
    note. Cell data: each cell keeps its row; pieces of a split face
    inherit the face's row; new triangles get zeros (False, ""), except
    ``facet_normals`` (meshio's STL data), which gets their unit normals.
    Point sets are unchanged (new points belong to none); cell sets keep
    their cells, a split face's pieces joining its sets. Field data and
    ``info`` are copied.
    """

    def __init__(self, *args: Any, report: Optional[FillReport] = None,
                 **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.report: FillReport = report if report is not None \
            else FillReport()


def read_mesh(path: Union[str, "os.PathLike[str]"],
              file_format: Optional[str] = None) -> Any:
    """``meshio.read(path, file_format)``, its failures as exceptions:
    raises :class:`InvalidInput` naming the file and meshio's reason when
    meshio cannot read it. (meshio 7.0 prints why each reader failed and
    calls ``sys.exit(1)``, which would end a loop over a folder, and its
    readers raise what they meet, ``ValueError`` and the like.) What meshio
    prints while reading a file it can read is passed on."""
    out, err = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            mesh = meshio.read(path, file_format)
    except SystemExit:
        # Each reader's reason went to stdout, then "Couldn't read file"
        # to stderr.
        why = "; ".join(line.strip() for line in out.getvalue().splitlines()
                        if line.strip())
        raise InvalidInput(f"meshio cannot read {os.fspath(path)}"
                           f"{': ' + why if why else ''}") from None
    except Exception as e:  # a reader's ValueError, IndexError, ...
        why = str(e) if isinstance(e, meshio.ReadError) else \
            f"{type(e).__name__}: {e}"
        raise InvalidInput(f"meshio cannot read {os.fspath(path)}: "
                           f"{why}") from e
    sys.stdout.write(out.getvalue())
    sys.stderr.write(err.getvalue())
    return mesh


@dataclass
class _Unpack:
    """Where a point-data array travels: columns ``start:stop`` of
    ``channel``, reshaped to ``shape`` per point."""
    key: str
    channel: str
    start: int
    stop: int
    shape: Tuple[int, ...]


@dataclass
class MeshRequest:
    """A meshio.Mesh as FillHoles sends it: ``vertices`` (V, 3) float64,
    ``faces`` (the surface cells in block order: an (F, k) array, or a
    list of arrays when blocks differ in size), ``point_data`` (the
    channels to send), and how to read the answer back: ``blocks`` (the
    cell block index of each surface block), ``offsets`` (the first sent
    face id of each), ``unpack`` (which channel columns hold which point
    data) and ``dropped`` (point data not sent, and why)."""
    vertices: np.ndarray
    faces: Any
    point_data: Dict[str, np.ndarray] = field(default_factory=dict)
    blocks: List[int] = field(default_factory=list)
    offsets: List[int] = field(default_factory=list)
    unpack: List[_Unpack] = field(default_factory=list)
    dropped: Dict[str, str] = field(default_factory=dict)


def _numbers(value: Any, count: int) -> Tuple[Optional[np.ndarray], str]:
    """(float32 (count, d) rows, "") when ``value`` can be a channel, else
    (None, why not)."""
    a = np.asarray(value)
    if a.ndim == 0 or len(a) != count:
        return None, "not a row per point"
    if a.dtype.kind == "b":
        return None, "booleans are not interpolated"
    if a.dtype.kind not in "iuf":
        return None, f"dtype {a.dtype} is not numbers"
    d = int(np.prod(a.shape[1:], dtype=np.int64))
    if not 1 <= d <= MAX_FLOATS:
        return None, f"{d} values a point (the service carries 1 to " \
            f"{MAX_FLOATS})"
    with np.errstate(over="ignore", invalid="ignore"):
        rows = a.reshape(count, d).astype(np.float32)
    if not np.isfinite(rows).all():
        return None, "values not finite in single precision"
    return rows, ""


def mesh_request(mesh: Any, with_data: bool = True) -> MeshRequest:
    """The FillHoles upload of ``mesh`` (a :class:`meshio.Mesh`); raises
    :class:`InvalidInput` when it has no surface cells or its points are
    not 3D."""
    points = np.asarray(mesh.points)
    if points.ndim != 2 or points.shape[1] != 3:
        raise InvalidInput(f"the mesh's points must be 3D, shape (V, 3); got "
                           f"{points.shape}")
    blocks, datas, offsets = [], [], []
    count = 0
    for i, block in enumerate(mesh.cells):
        if block.type not in SURFACE_CELLS:
            continue
        data = np.asarray(block.data)
        if data.ndim != 2 or (len(data) and data.shape[1] < 3):
            raise InvalidInput(f"cell block {i} ({block.type}) must be an "
                               f"(n, k) array of point ids, k >= 3")
        blocks.append(i)
        offsets.append(count)
        datas.append(data)
        count += len(data)
    if count == 0:
        types = sorted({b.type for b in mesh.cells}) or ["none"]
        raise InvalidInput(f"the mesh has no surface cells "
                           f"({', '.join(SURFACE_CELLS)}); its cells: "
                           f"{', '.join(types)}")
    widths = {d.shape[1] for d in datas if len(d)}
    faces: Any
    if len(widths) == 1:
        faces = np.concatenate([d.reshape(-1, *widths) for d in datas])
    else:
        faces = [row for d in datas for row in d]
    request = MeshRequest(vertices=points.astype(np.float64, copy=False),
                          faces=faces, blocks=blocks, offsets=offsets)
    if with_data:
        _channels(mesh, len(points), request)
    return request


def _channels(mesh: Any, count: int, request: MeshRequest) -> None:
    """Point data as channels: the normals alone as "normal", every other
    array packed in key order into channels of up to 16 floats (values of
    one point blend with the same weights whatever channel holds them)."""
    data = dict(mesh.point_data)
    normal_keys: List[str] = []
    if all(k in data for k in PLY_NORMALS):
        parts = [_numbers(data[k], count)[0] for k in PLY_NORMALS]
        if all(p is not None and p.shape[1] == 1 for p in parts):
            request.point_data["normal"] = np.concatenate(
                [p for p in parts if p is not None], axis=1)
            normal_keys = list(PLY_NORMALS)
            for j, k in enumerate(PLY_NORMALS):
                request.unpack.append(_Unpack(k, "normal", j, j + 1,
                                              np.asarray(data[k]).shape[1:]))
    if not normal_keys:
        for k in NORMAL_KEYS:
            if k in data and np.asarray(data[k]).shape == (count, 3):
                rows, _ = _numbers(data[k], count)
                if rows is not None:
                    request.point_data["normal"] = rows
                    request.unpack.append(_Unpack(k, "normal", 0, 3, (3,)))
                    normal_keys = [k]
                    break
    channels = MAX_CHANNELS - len(request.point_data)
    packs: List[List[Tuple[str, np.ndarray]]] = []
    for key, value in data.items():
        if key in normal_keys:
            continue
        rows, why = _numbers(value, count)
        if rows is None:
            request.dropped[key] = why
            continue
        d = rows.shape[1]
        pack = next((p for p in packs
                     if sum(r.shape[1] for _, r in p) + d <= MAX_FLOATS), None)
        if pack is None:
            if len(packs) == channels:
                request.dropped[key] = (f"the service carries at most "
                                        f"{MAX_CHANNELS} channels of "
                                        f"{MAX_FLOATS} numbers")
                continue
            pack = []
            packs.append(pack)
        pack.append((key, rows))
    for i, pack in enumerate(packs):
        name = f"meshio:{i}"
        start = 0
        for key, rows in pack:
            stop = start + rows.shape[1]
            request.unpack.append(_Unpack(key, name, start, stop,
                                          np.asarray(data[key]).shape[1:]))
            start = stop
        request.point_data[name] = np.concatenate([r for _, r in pack],
                                                  axis=1)


def _cast(values: np.ndarray, like: np.ndarray) -> np.ndarray:
    """float32 ``values`` as ``like``'s dtype: integers rounded and clipped
    to their range."""
    values = np.nan_to_num(values.astype(np.float64), nan=0.0)
    if like.dtype.kind in "iu":
        info = np.iinfo(like.dtype)
        values = np.clip(np.rint(values), info.min, info.max)
    return values.astype(like.dtype)


def _unit_normals(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    p = points[triangles.astype(np.int64)]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return np.divide(n, length, out=np.zeros_like(n), where=length > 0)


def _directed_edges(faces: Any) -> np.ndarray:
    """(E, 2) int64: every face's edges, each in the face's direction."""
    if isinstance(faces, np.ndarray):
        f = faces.astype(np.int64)
        return np.stack([f, np.roll(f, -1, axis=1)], axis=2).reshape(-1, 2)
    pairs = [np.stack([f, np.roll(f, -1)], axis=1)
             for f in (np.asarray(x, dtype=np.int64) for x in faces)]
    return np.concatenate(pairs) if pairs else np.zeros((0, 2), np.int64)


def _as_sent(points: np.ndarray, request: MeshRequest,
             patches: FillPatches) -> Tuple[List[np.ndarray],
                                            Dict[int, np.ndarray],
                                            Dict[int, int]]:
    """(patch triangles, split faces' pieces, welds): each patch's
    triangles and each split face's pieces with every point the server's
    repair merged (the same coordinates exactly) named by the copy the
    mesh's own faces use there, and the copies that must be welded for
    the holes to close ({copy: the copy it becomes}).

    The answer names a merged point by its first copy. A split face's
    pieces take the face's own copies. A patch takes, at each point of its
    rim, the copy at that end of the mesh border edge its rim edge runs
    along, so a hole closes against the faces around it; where its rim
    meets two copies of one point (a rim through a pinched point, the
    server having joined two loops there, or across a seam of split
    points) the hole cannot close unless they are one: they are welded
    (every surface cell naming one names the lowest). Without duplicate
    points in the mesh, the answer's ids as they are, and no welds."""
    count = len(points)
    faces = [np.asarray(p.faces, dtype=np.int64).reshape(-1, 3)
             for p in patches.patches]
    replaced = {face: np.asarray(t, dtype=np.int64).reshape(-1, 3)
                for p in patches.patches
                for face, t in p.replaced_faces.items()}
    if count == 0:
        return faces, replaced, {}
    _, index, inverse = np.unique(points, axis=0, return_index=True,
                                  return_inverse=True)
    first = index[inverse.reshape(-1)]  # each point's first copy
    if (first == np.arange(count)).all():
        return faces, replaced, {}

    def cls(x: int) -> int:
        return int(first[x]) if x < count else x

    def renamed(ids: np.ndarray, mapping: Dict[int, int]) -> np.ndarray:
        out = ids.copy()
        for i, x in np.ndenumerate(ids):
            if x < count:
                out[i] = mapping.get(cls(int(x)), x)
        return out

    sent = request.faces
    for face, t in replaced.items():
        own = np.asarray(sent[face], dtype=np.int64)
        replaced[face] = renamed(t, {cls(int(x)): int(x) for x in own})

    edges = _directed_edges(sent)
    key = edges[:, 0] * count + edges[:, 1]
    border = edges[~np.isin(key, edges[:, 1] * count + edges[:, 0])]
    by_class: Dict[Tuple[int, int], List[Tuple[int, int]]] = {}
    for a, b in border.tolist():
        by_class.setdefault((cls(a), cls(b)), []).append((a, b))
    parent: Dict[int, int] = {}

    def root(x: int) -> int:
        while parent.get(x, x) != x:
            x = parent[x]
        return x

    out = []
    for f in faces:
        pe = _directed_edges(f)
        span = max(count, int(f.max()) + 1) if len(f) else count
        pkey = pe[:, 0] * span + pe[:, 1]
        rim = pe[~np.isin(pkey, pe[:, 1] * span + pe[:, 0])]
        found: Dict[int, set] = {}
        for u, v in rim.tolist():
            # The mesh runs v -> u beside the patch (or u -> v, wound
            # against it).
            for (a, b), (x, y) in [(e, (v, u)) for e in
                                   by_class.get((cls(v), cls(u)), [])] + \
                    [(e, (u, v)) for e in by_class.get((cls(u), cls(v)), [])]:
                for point, same in ((x, a), (y, b)):
                    if point < count:
                        found.setdefault(cls(point), set()).add(same)
        mapping = {}
        for c, copies in found.items():
            low = min(root(x) for x in copies)
            for x in copies:
                parent[root(x)] = low
            mapping[c] = low
        out.append(renamed(f, mapping))
    welds = {x: root(x) for x in parent if root(x) != x}
    if welds:
        lookup = np.arange(count)
        for x, y in welds.items():
            lookup[x] = y
        out = [np.where(f < count, lookup[np.minimum(f, count - 1)], f)
               for f in out]
        replaced = {face: np.where(t < count,
                                   lookup[np.minimum(t, count - 1)], t)
                    for face, t in replaced.items()}
    return out, replaced, welds


def filled_mesh(mesh: Any, request: MeshRequest,
                patches: FillPatches) -> FilledMesh:
    """``mesh`` with ``patches`` (the answer to ``request``) added, as
    :class:`FilledMesh` documents."""
    points = np.asarray(mesh.points)
    count = len(points)
    parts = [points]
    total = count
    for p in patches.patches:
        if p.first_vertex != total:
            raise ValueError(f"the patch of hole {p.hole} starts at vertex "
                             f"{p.first_vertex}, but {total} vertices "
                             f"precede it: these patches are not of this mesh")
        parts.append(np.asarray(p.vertices).astype(points.dtype))
        total += len(p.vertices)
    out_points = np.concatenate(parts)
    added = total - count

    # New points' channel values, from the first corner naming each.
    values = {name: np.full((added, rows.shape[1]), np.nan, np.float32)
              for name, rows in request.point_data.items()}
    seen = np.zeros(added, dtype=bool)
    corner_sets: List[Tuple[np.ndarray, Dict[str, np.ndarray]]] = []
    for p in patches.patches:
        corner_sets.append((np.asarray(p.faces).reshape(-1), p.corner_data))
    for p in patches.patches:
        for face, triangles in p.replaced_faces.items():
            corner_sets.append((np.asarray(triangles).reshape(-1),
                                p.replaced_corner_data.get(face, {})))
    for ids, data in corner_sets:
        new = ids >= count
        if not new.any() or not all(n in data for n in values):
            continue
        first_ids, first = np.unique(ids[new] - count, return_index=True)
        take = ~seen[first_ids]
        for name, target in values.items():
            target[first_ids[take]] = np.asarray(data[name])[new][first][take]
        seen[first_ids[take]] = True

    notes = list(patches.report.notes)
    point_data: Dict[str, np.ndarray] = {}
    for key, value in mesh.point_data.items():
        old = np.asarray(value)
        rows = np.zeros((added,) + old.shape[1:], dtype=old.dtype)
        for u in request.unpack:
            if u.key == key:
                rows = _cast(values[u.channel][:, u.start:u.stop]
                             .reshape((added,) + u.shape), old)
                break
        else:
            if added:
                why = request.dropped.get(key, "not sent")
                notes.append(f"point data '{key}' is not carried ({why}): "
                             f"the {added} new points have zeros")
        point_data[key] = np.concatenate([old, rows])

    # Cells.
    cells = [meshio.CellBlock(b.type, np.array(b.data, copy=True))
             for b in mesh.cells]
    cell_data = {name: [np.array(a, copy=True) for a in arrays]
                 for name, arrays in mesh.cell_data.items()}
    target = next((i for i in reversed(range(len(cells)))
                   if cells[i].type == "triangle"), None)
    removed: Dict[int, List[int]] = {}
    sources: List[Tuple[int, int]] = []  # (block, row) of appended pieces
    pieces: List[np.ndarray] = []
    starts = np.asarray(request.offsets)
    new_faces, replaced, welds = _as_sent(points, request, patches)
    if welds:
        lookup = np.arange(count)
        for x, y in welds.items():
            lookup[x] = y
        for block in request.blocks:
            cells[block] = meshio.CellBlock(
                cells[block].type,
                lookup[cells[block].data].astype(cells[block].data.dtype))
        pairs = ", ".join(f"{x} -> {y}" for x, y in sorted(welds.items())[:5])
        notes.append(f"{len(welds)} duplicate points welded so that the "
                     f"holes through them close: surface cells name the "
                     f"other copy at the same place instead ({pairs}"
                     f"{', ...' if len(welds) > 5 else ''}); the points "
                     f"stay, unused")
    for face, t in replaced.items():
        k = int(np.searchsorted(starts, face, side="right")) - 1
        block, row = request.blocks[k], face - int(starts[k])
        if cells[block].type == "triangle":
            cells[block].data[row] = t[0]
            t = t[1:]
        else:
            removed.setdefault(block, []).append(row)
        pieces.append(t)
        sources += [(block, row)] * len(t)
    appended = np.concatenate([np.zeros((0, 3), dtype=np.int64)] + pieces +
                              new_faces)
    fresh = len(appended) - len(sources)  # the patches' triangles
    cell_sets = copy.deepcopy(mesh.cell_sets)
    if len(appended):
        if target is None:
            dtype = np.asarray(cells[request.blocks[0]].data).dtype
            cells.append(meshio.CellBlock("triangle",
                                          appended.astype(dtype)))
            target = len(cells) - 1
            base = 0
            for name, arrays in cell_data.items():
                first = arrays[request.blocks[0]]
                arrays.append(np.zeros((0,) + first.shape[1:], first.dtype))
            for sets in cell_sets.values():
                if isinstance(sets, list) and len(sets) == target:
                    sets.append(np.zeros(0, dtype=np.int64))
        else:
            old = cells[target].data
            base = len(old)
            cells[target] = meshio.CellBlock(
                "triangle", np.concatenate([old, appended.astype(old.dtype)]))
        for name, arrays in cell_data.items():
            have = arrays[target]
            rows = np.zeros((len(appended),) + have.shape[1:], have.dtype)
            for j, (block, row) in enumerate(sources):
                source = arrays[block]
                if source.shape[1:] == have.shape[1:]:
                    rows[j] = source[row]
            if name == FACET_NORMALS and have.shape[1:] == (3,) and \
                    have.dtype.kind == "f" and fresh:
                rows[len(sources):] = _unit_normals(out_points,
                                                    appended[len(sources):])
            elif fresh:
                notes.append(f"cell data '{name}' is not carried into new "
                             f"cells: the {fresh} new triangles have zeros")
            arrays[target] = np.concatenate([have, rows])
        for sets in cell_sets.values():
            if not isinstance(sets, list) or len(sets) != len(cells):
                continue
            joined = [base + j for j, (block, row) in enumerate(sources)
                      if sets[block] is not None and
                      row in np.asarray(sets[block])]
            if joined:
                sets[target] = np.concatenate([np.asarray(sets[target]),
                                               np.asarray(joined)])
    for block, rows in removed.items():
        cells[block] = meshio.CellBlock(cells[block].type,
                                        np.delete(cells[block].data, rows,
                                                  axis=0))
        for arrays in cell_data.values():
            arrays[block] = np.delete(arrays[block], rows, axis=0)
        gone = np.sort(np.asarray(rows))
        for sets in cell_sets.values():
            if isinstance(sets, list) and len(sets) == len(cells) and \
                    sets[block] is not None:
                ids = np.asarray(sets[block])
                ids = ids[~np.isin(ids, gone)]
                sets[block] = ids - np.searchsorted(gone, ids)

    report = copy.deepcopy(patches.report)
    report.notes = notes
    return FilledMesh(out_points, cells, point_data=point_data,
                      cell_data=cell_data,
                      field_data=copy.deepcopy(mesh.field_data),
                      point_sets=copy.deepcopy(mesh.point_sets),
                      cell_sets=cell_sets,
                      gmsh_periodic=copy.deepcopy(mesh.gmsh_periodic),
                      info=copy.deepcopy(mesh.info), report=report)

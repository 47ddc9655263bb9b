# SPDX-License-Identifier: AGPL-3.0-or-later
"""Plain Python mirrors of the dot.v1 messages a caller reads, and the
option objects a caller writes.

Each result class mirrors one proto message field by field (see
``proto/dot/v1/triangulation.proto``); enums become lower-case strings
(``"ok"``, ``"no_triangulation"``, ``"delaunay"``), repeated index fields
become numpy arrays, metric weights a dict keyed by metric name.

The option classes (:class:`Weights`, :class:`TriangulateOptions`,
:class:`FillOptions`, :class:`SurfaceOptions`) are frozen dataclasses with the service's defaults;
each checks its values when made (raising :class:`InvalidInput`) and
builds its proto message in one place (``to_proto``), which the client's
keyword arguments go through too. :data:`WEIGHT_PRESETS` is the one table
of named metric weights (the Blender add-on's presets are its entries).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import (Any, Dict, List, Mapping, Optional, Sequence, Tuple,
                    Type, TypeVar, Union)

import numpy as np

from . import _validate as check
from ._errors import DotError, InvalidInput
from ._proto.dot.v1 import triangulation_pb2 as pb

METRICS = ("area", "perimeter", "normal_deviation", "shape", "dihedral",
           "squared_dihedral")


def _enum_name(value: int, enum: Any, prefix: str,
               zero: Optional[str] = None) -> str:
    """The readable name of a proto enum value: its descriptor's name
    without ``prefix``, lower case (``HOLE_STATUS_NO_TRIANGULATION`` ->
    ``"no_triangulation"``); ``zero`` names the value 0 when given (an
    enum whose 0 means "not set"); a value this client does not know
    reads as its number."""
    if value == 0 and zero is not None:
        return zero
    try:
        name = enum.Name(value)
    except ValueError:
        return str(value)
    return name[len(prefix):].lower() if name.startswith(prefix) else name.lower()


def _enum_values(enum: Any, prefix: str,
                 skip: Sequence[str] = ()) -> Dict[str, int]:
    """{readable name: value} of a proto enum, from its descriptor (the
    inverse of :func:`_enum_name`), without the names in ``skip``."""
    out = {}
    for name, value in enum.items():
        short = name[len(prefix):].lower() if name.startswith(prefix) else name.lower()
        if short not in skip:
            out[short] = value
    return out


def _scalars(cls: Any, message: Any, **overrides: Any) -> Any:
    """cls(...) from the same-named scalar fields of message."""
    values = {}
    for f in dataclasses.fields(cls):
        if f.name in overrides:
            values[f.name] = overrides[f.name]
        else:
            values[f.name] = getattr(message, f.name)
    return cls(**values)


def _as_dict(obj: Any) -> Any:
    if dataclasses.is_dataclass(obj):
        return {f.name: _as_dict(getattr(obj, f.name))
                for f in dataclasses.fields(obj)}
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, dict):
        return {k: _as_dict(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_as_dict(v) for v in obj]
    return obj


def weights_dict(w: Any) -> Dict[str, float]:
    """A MetricWeights message as {"area": ..., ..., "squared_dihedral": ...}."""
    return {m: float(getattr(w, m)) for m in METRICS}


class _Plain:
    def to_dict(self) -> Dict[str, Any]:
        """Nested plain dicts and lists (numpy arrays as lists), for JSON."""
        return _as_dict(self)


@dataclass
class Stats(_Plain):
    """Sizes and per-stage times of one solve (proto ``Stats``)."""
    n: int = 0
    tetrahedra: int = 0
    delaunay_triangles: int = 0
    search_triangles: int = 0
    adjacency_entries: int = 0
    dp_states: int = 0
    table_bytes: int = 0
    validate_ms: float = 0.0
    delaunay_ms: float = 0.0
    adjacency_ms: float = 0.0
    dp_ms: float = 0.0
    tiling_ms: float = 0.0
    total_ms: float = 0.0
    non_delaunay_triangles: int = 0

    @classmethod
    def from_proto(cls, m: Any) -> "Stats":
        return _scalars(cls, m)


@dataclass
class Summary(_Plain):
    """The proto ``Summary`` of one triangulation.

    ``status`` is ``"ok"`` or ``"no_triangulation"`` (then ``message`` says
    why and ``non_delaunay_edges`` lists offending edges as (k, 2) vertex
    index pairs). ``loop`` is the polygon with inserted vertices in place
    (only when ``inserted_count`` > 0, or for several loops: then
    ``loop_sizes`` cuts it into loops, each listed in the direction the
    surface runs along it, and ``reversed_loops`` names those that run
    against their input; three or more loops are joined by ``bridges``
    first, (k - 1, 2) vertex index pairs, and the surface is the optimum
    for them: an approximation). ``metric_costs`` maps each metric to its
    unweighted sum. ``intersecting_pairs`` is -1 when not checked.
    """
    status: str = "unspecified"
    message: str = ""
    vertex_count: int = 0
    triangle_count: int = 0
    inserted_count: int = 0
    loop: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int32))
    non_delaunay_edges: np.ndarray = field(
        default_factory=lambda: np.zeros((0, 2), np.int32))
    total_cost: float = 0.0
    metric_costs: Dict[str, float] = field(default_factory=dict)
    search_space_used: str = ""
    solver: str = ""
    planar: bool = False
    intersecting_pairs: int = -1
    stats: Stats = field(default_factory=Stats)
    queue_ms: float = 0.0
    compute_ms: float = 0.0
    delaunay_backend: str = ""
    cache_hit: bool = False
    loop_sizes: List[int] = field(default_factory=list)
    reversed_loops: List[int] = field(default_factory=list)
    bridges: np.ndarray = field(
        default_factory=lambda: np.zeros((0, 2), np.int32))

    @classmethod
    def from_proto(cls, m: Any) -> "Summary":
        return _scalars(
            cls, m,
            status=_enum_name(m.status, pb.ResultStatus, "RESULT_STATUS_"),
            loop=np.array(m.loop, dtype=np.int64).astype(np.int32),
            loop_sizes=[int(x) for x in m.loop_sizes],
            reversed_loops=[int(x) for x in m.reversed_loops],
            bridges=np.array(m.bridges, dtype=np.int64).astype(np.int32)
            .reshape(-1, 2),
            non_delaunay_edges=np.array(m.non_delaunay_edges, dtype=np.int64)
            .astype(np.int32).reshape(-1, 2),
            metric_costs=weights_dict(m.metric_costs),
            stats=Stats.from_proto(m.stats))


@dataclass
class Progress(_Plain):
    """A progress message of Triangulate: the stage (``"validate"``,
    ``"delaunay"``, ``"adjacency"``, ``"dynamic_program"``, ``"tiling"``,
    ``"queued"``), the fraction of it done (0..1) and the time so far."""
    stage: str = ""
    fraction: float = 0.0
    elapsed_ms: float = 0.0

    @classmethod
    def from_proto(cls, m: Any) -> "Progress":
        return _scalars(cls, m, stage=_enum_name(m.stage, pb.Stage, "STAGE_"))


@dataclass
class Result(_Plain):
    """One triangulated polygon.

    ``vertices``: float64 array (V, 3), the input points first (exactly as
    given), then vertices inserted by edge protection. ``triangles``: int32
    array (T, 3) of vertex indices, oriented so that the polygon runs
    0 -> 1 -> ... around the patch. ``summary``: the server's
    :class:`Summary`. In :meth:`Client.triangulate_many` a polygon that
    failed alone has ``error`` set (a :class:`DotError`, or
    :class:`NoTriangulation`) and empty arrays; ``ok`` is True otherwise.
    """
    vertices: np.ndarray
    triangles: np.ndarray
    summary: Optional[Summary] = None
    error: Optional[DotError] = None
    id: str = ""

    @property
    def ok(self) -> bool:
        """True when the polygon was triangulated."""
        return (self.error is None and self.summary is not None
                and self.summary.status == "ok")


@dataclass
class RepairReport(_Plain):
    """What the server's mesh repair changed before filling."""
    merged_vertices: int = 0
    degenerate_faces: int = 0
    duplicate_faces: int = 0
    triangulated_polygons: int = 0
    reoriented_faces: int = 0
    non_manifold_vertices: int = 0
    components: int = 0

    @classmethod
    def from_proto(cls, m: Any) -> "RepairReport":
        return _scalars(cls, m)


@dataclass
class HoleReport(_Plain):
    """One hole: ``status`` is ``"filled"``, ``"skipped"``,
    ``"no_triangulation"``, ``"failed"`` (``reason`` says why),
    ``"stopped"`` (the fill stopped before it was done: see
    :class:`FillStopped`) or, from :meth:`Client.list_holes`,
    ``"listed"`` (selected, not filled);
    ``diameter`` (bounding-box diagonal), ``perimeter`` and ``centroid``
    (length-weighted, x y z) give the loop's size and place;
    ``escalation``, the search step that made the patch, is
    ``"delaunay"``, ``"protected_edges"``, ``"all_triangles"``,
    ``"delaunay_first"`` (every triangle, Delaunay ones first: large holes
    with no Delaunay patch) or ``""`` (no patch); ``split_faces`` lists
    input faces split by edge protection. ``intersecting_pairs`` is 0 on a
    filled hole unless ``allow_input_intersections`` filled it over a
    mesh that already intersects itself (``input_pairs_near`` such pairs
    near it).
    Holes with islands: on a rim, ``joined`` lists the island loops its
    patch joins; on an island, ``joined_to`` is its rim's id (None
    otherwise) and its status is the rim's.
    (The wire carries ``status`` and ``escalation`` as the enums
    ``HoleStatus`` and ``Escalation``; these are their names.)"""
    id: int = 0
    boundary_vertices: int = 0
    pinched: bool = False
    status: str = ""
    reason: str = ""
    escalation: str = ""
    search_space_used: str = ""
    solver: str = ""
    boundary_inserted: int = 0
    split_faces: List[int] = field(default_factory=list)
    patch_triangles: int = 0
    refined_vertices: int = 0
    faired: bool = False
    cost: float = 0.0
    intersecting_pairs: int = -1
    triangulate_ms: float = 0.0
    refine_ms: float = 0.0
    fair_ms: float = 0.0
    check_ms: float = 0.0
    diameter: float = 0.0
    perimeter: float = 0.0
    centroid: Tuple[float, ...] = ()
    joined: List[int] = field(default_factory=list)
    joined_to: Optional[int] = None
    input_pairs_near: int = 0
    non_delaunay_triangles: int = 0

    @classmethod
    def from_proto(cls, m: Any) -> "HoleReport":
        return _scalars(
            cls, m, centroid=tuple(m.centroid), joined=list(m.joined),
            joined_to=m.joined_to if m.HasField("joined_to") else None,
            status=_enum_name(m.status, pb.HoleStatus, "HOLE_STATUS_"),
            escalation=_enum_name(m.escalation, pb.Escalation, "ESCALATION_",
                                  zero=""),
            split_faces=list(m.split_faces))


@dataclass
class FillReport(_Plain):
    """The proto ``FillReport``: one :class:`HoleReport` per hole loop and
    the totals. The filled mesh has ``input_vertices + added_vertices``
    vertices and ``input_faces + added_faces`` faces (input = after
    repair); ``closed`` is True when no border edge is left."""
    version: int = 0
    holes: List[HoleReport] = field(default_factory=list)
    loops: int = 0
    filled: int = 0
    skipped: int = 0
    unfilled: int = 0
    added_vertices: int = 0
    added_faces: int = 0
    closed: bool = False
    total_ms: float = 0.0
    repair: RepairReport = field(default_factory=RepairReport)
    input_vertices: int = 0
    input_faces: int = 0
    listed: int = 0  # list_holes: selected, not filled
    stopped: int = 0  # the fill stopped before these (see FillStopped)
    # What the answer could not carry (an attribute channel and why).
    notes: List[str] = field(default_factory=list)

    @classmethod
    def from_proto(cls, m: Any) -> "FillReport":
        return _scalars(cls, m,
                        holes=[HoleReport.from_proto(h) for h in m.holes],
                        repair=RepairReport.from_proto(m.repair),
                        notes=list(m.notes))


@dataclass
class FillResult(_Plain):
    """A filled mesh: ``vertices`` float64 (V, 3), the (repaired) input's
    first, then new ones; ``faces`` int32 (F, 3), or with
    ``keep_polygons`` a list of int32 arrays (the polygons sent where no
    patch split one, then triangles); ``report`` the :class:`FillReport`.

    ``point_data`` and ``corner_data``: the attribute channels sent
    (float32 arrays), carried through the repair and interpolated into
    every new vertex and corner: a row per vertex, or a row per face
    corner (faces in order, corners in order; a UV seam gives one vertex
    several). A channel comes back per vertex when no vertex has corners
    that disagree, else per corner."""
    vertices: np.ndarray
    faces: Any
    report: FillReport
    point_data: Dict[str, np.ndarray] = field(default_factory=dict)
    corner_data: Dict[str, np.ndarray] = field(default_factory=dict)


@dataclass
class HolePatch(_Plain):
    """What filling one hole adds to the mesh as it was sent (proto
    ``HolePatch``, reassembled across messages).

    ``hole``: the :class:`HoleReport` id. ``vertices``: float64 (N, 3), the
    new vertices, which are ids ``first_vertex`` .. ``first_vertex + N -
    1`` (numbered on from the sent mesh's vertex count, patch after patch).
    ``faces``: int32 (M, 3), the new triangles over vertex ids as sent (an
    id below the sent vertex count is one of the caller's vertices; a
    duplicate the server's repair merged is named by its first copy).
    ``replaced_faces``: {sent face id: int32 (K, 3) triangles}, the sent
    faces edge protection split, each with the triangles that replace all
    of it. With attribute channels sent: ``corner_data`` {name: float32
    (3M, d)}, each channel's values at the corners of ``faces`` in order,
    and ``replaced_corner_data`` {sent face id: {name: (3K, d)}}, at the
    corners of its replacement triangles.
    """
    hole: int
    first_vertex: int
    vertices: np.ndarray
    faces: np.ndarray
    replaced_faces: Dict[int, np.ndarray] = field(default_factory=dict)
    corner_data: Dict[str, np.ndarray] = field(default_factory=dict)
    replaced_corner_data: Dict[int, Dict[str, np.ndarray]] = field(
        default_factory=dict)


FaceList = Union[np.ndarray, List[np.ndarray]]


@dataclass
class FillPatches(_Plain):
    """The patches answer of FillHoles (:meth:`Client.fill_patches`): one
    :class:`HolePatch` per filled hole, in the ids of the mesh as sent, and
    the :class:`FillReport`. The caller keeps its mesh and adds them
    (:meth:`apply`, or its own code: the Blender add-on adds them to a
    bmesh)."""
    patches: List[HolePatch]
    report: FillReport

    def apply(self, vertices: Any, faces: Any) -> Tuple[np.ndarray, FaceList]:
        """The sent mesh with the patches added: ``(vertices, faces)``.

        ``vertices`` and ``faces`` must be the mesh as it was sent. The
        new vertices follow the sent ones; a replaced face is replaced in
        place by the first of its triangles, the others are appended, then
        every patch's faces, patch after patch (so a face that was not
        replaced keeps its index). ``faces`` comes back as an int32
        (F', 3) array when it was an (F, 3) array, else as a list of int
        arrays (the sent polygons and the new triangles). Raises
        :class:`ValueError` when the patches do not fit this mesh.
        """
        v = check.points("vertices", vertices)
        f = check.faces(faces, len(v))
        parts = [v]
        count = len(v)
        for p in self.patches:
            if p.first_vertex != count:
                raise ValueError(
                    f"the patch of hole {p.hole} starts at vertex "
                    f"{p.first_vertex}, but {count} vertices precede it: "
                    f"these patches are not of this mesh")
            parts.append(p.vertices)
            count += len(p.vertices)
        replaced: Dict[int, np.ndarray] = {}
        for p in self.patches:
            for face, triangles in p.replaced_faces.items():
                if face in replaced:
                    raise ValueError(f"face {face} is replaced twice")
                if not 0 <= face < len(f):
                    raise ValueError(
                        f"the patch of hole {p.hole} replaces face {face}, "
                        f"but the mesh has {len(f)} faces")
                if len(triangles) == 0:
                    raise ValueError(f"face {face} is replaced by nothing")
                replaced[face] = triangles
        firsts = {face: t[0] for face, t in replaced.items()}
        appended = [t[1:] for t in replaced.values()]
        appended += [p.faces for p in self.patches]
        extra = np.concatenate([np.zeros((0, 3), dtype=np.int64)] + [
            np.asarray(t, dtype=np.int64).reshape(-1, 3) for t in appended])
        every = np.concatenate([extra] + [
            np.asarray(t, dtype=np.int64).reshape(-1, 3)
            for t in firsts.values()])
        bad = (every < 0) | (every >= count)
        if bad.any():
            raise ValueError(f"a patch triangle refers to vertex "
                             f"{int(every[bad][0])}, but the mesh with the "
                             f"patches has {count} vertices")
        out_vertices = np.concatenate(parts) if len(parts) > 1 else v.copy()
        if isinstance(f, np.ndarray) and f.shape[1] == 3:
            out = f.copy()
            for face, t in firsts.items():
                out[face] = t
            return out_vertices, np.concatenate([out, extra]).astype(np.int32)
        rows = [firsts.get(i, face) for i, face in enumerate(f)]
        return out_vertices, [np.asarray(r, dtype=np.int64)
                              for r in rows + list(extra)]


@dataclass
class FillProgress(_Plain):
    """Where a fill is: ``phase`` is ``"repair"``, ``"loops"`` (finding
    the holes), ``"holes"`` (``holes_done`` of ``holes_total`` filled;
    ``eta_ms`` the time the rest should take at the pace so far, 0 before
    the first hole) or ``"merge"``, on the server; ``elapsed_ms`` since the
    call arrived. (The wire carries ``phase`` as the enum ``FillPhase``.)"""
    holes_done: int = 0
    holes_total: int = 0
    elapsed_ms: float = 0.0
    phase: str = ""
    eta_ms: float = 0.0

    @classmethod
    def from_proto(cls, m: Any) -> "FillProgress":
        return _scalars(cls, m, phase=_enum_name(m.phase, pb.FillPhase,
                                                 "FILL_PHASE_", zero=""))


def _vertex_ids(values: Any) -> np.ndarray:
    """A repeated uint32 field of vertex ids as an int32 array."""
    return np.array(values, dtype=np.int64).astype(np.int32)


@dataclass
class CurveUse(_Plain):
    """One curve of a patch's loop (proto ``CurveUse``): ``curve`` is its
    index in :attr:`SurfaceReport.curves`; ``reversed``: the loop runs it
    from its last vertex to its first."""
    curve: int = 0
    reversed: bool = False

    @classmethod
    def from_proto(cls, m: Any) -> "CurveUse":
        return _scalars(cls, m)


@dataclass
class PatchLoop(_Plain):
    """One loop of a patch's boundary (proto ``PatchLoop``): the curves it
    runs along, in order, and ``vertices``, its vertex ids as sent (int32
    array, its first junction once)."""
    curves: List[CurveUse] = field(default_factory=list)
    vertices: np.ndarray = field(
        default_factory=lambda: np.zeros(0, np.int32))

    @classmethod
    def from_proto(cls, m: Any) -> "PatchLoop":
        return cls(curves=[CurveUse.from_proto(c) for c in m.curves],
                   vertices=_vertex_ids(m.vertices))


@dataclass
class PatchReport(_Plain):
    """One patch of a surfaced curve network (proto ``PatchReport``): the
    cycle of curves that bounds it (``loops``: one, or several for a patch
    joining loops, such as a tube between two rims) and what became of it.

    ``status`` is ``"surfaced"``, ``"failed"`` (no surface meets the rest
    only along the curves; ``reason`` says why, and the patch is left out
    of the mesh), ``"skipped"`` (``skip_longest``) or ``"stopped"``.
    ``search_space_used`` and ``solver`` name how its DOT patch was found;
    ``cost`` is that patch's weighted cost; ``resolves`` counts re-solves
    forbidding chords that met other patches; ``fan`` is True when DOT found
    nothing and the patch is a fan from a new vertex at the loop's centroid;
    ``triangles`` (in the output), ``refined_vertices`` and ``faired`` say
    what refinement and fairing did to it. (The wire carries ``status`` as
    the enum ``PatchStatus``; these are its names.)"""
    id: int = 0
    loops: List[PatchLoop] = field(default_factory=list)
    boundary_vertices: int = 0
    status: str = ""
    reason: str = ""
    search_space_used: str = ""
    solver: str = ""
    cost: float = 0.0
    resolves: int = 0
    fan: bool = False
    triangles: int = 0
    refined_vertices: int = 0
    faired: bool = False
    triangulate_ms: float = 0.0
    refine_ms: float = 0.0

    @classmethod
    def from_proto(cls, m: Any) -> "PatchReport":
        return _scalars(
            cls, m, loops=[PatchLoop.from_proto(loop) for loop in m.loops],
            status=_enum_name(m.status, pb.PatchStatus, "PATCH_STATUS_"))


@dataclass
class SurfaceReport(_Plain):
    """The proto ``SurfaceReport`` of a surfaced curve network.

    The network as a graph: ``curves`` (a vertex id array per curve, ids as
    sent, from one junction to the next; a closed curve's first id is also
    its last), ``junctions``, ``merged_vertices`` (points welded to an
    earlier one: a copy at the same coordinates, or a stroke end within
    ``weld_distance``), ``dangling`` (ids of
    curves that bound no patch). ``patches``: a :class:`PatchReport` per
    cycle; ``surfaced`` and ``failed`` count them. ``closed``: every curve
    that is not dangling borders two surfaced patches or more (more: the
    ``non_manifold_curves``). ``faired_whole``: one fairing ran over the
    whole network. ``intersecting_pairs`` of the surface: 0. ``notes``: what
    was found odd. Times in ms per phase. The mesh's first
    ``input_vertices`` vertices are the network's, in order; it has
    ``mesh_vertices`` vertices and ``mesh_faces`` triangles in all."""
    version: int = 0
    curves: List[np.ndarray] = field(default_factory=list)
    junctions: int = 0
    merged_vertices: int = 0
    dangling: List[int] = field(default_factory=list)
    notes: List[str] = field(default_factory=list)
    patches: List[PatchReport] = field(default_factory=list)
    surfaced: int = 0
    failed: int = 0
    closed: bool = False
    non_manifold_curves: int = 0
    faired_whole: bool = False
    intersecting_pairs: int = 0
    cycles_ms: float = 0.0
    triangulate_ms: float = 0.0
    refine_ms: float = 0.0
    fair_ms: float = 0.0
    check_ms: float = 0.0
    total_ms: float = 0.0
    input_vertices: int = 0
    mesh_vertices: int = 0
    mesh_faces: int = 0

    @classmethod
    def from_proto(cls, m: Any) -> "SurfaceReport":
        return _scalars(
            cls, m, curves=[_vertex_ids(c.vertices) for c in m.curves],
            dangling=[int(c) for c in m.dangling], notes=list(m.notes),
            patches=[PatchReport.from_proto(p) for p in m.patches])


@dataclass
class SurfaceProgress(_Plain):
    """Where a SurfaceNetwork call is: ``patches_done`` of
    ``patches_total`` triangulated (0 of n once the cycles are found),
    ``elapsed_ms`` since the call arrived on the server."""
    patches_done: int = 0
    patches_total: int = 0
    elapsed_ms: float = 0.0

    @classmethod
    def from_proto(cls, m: Any) -> "SurfaceProgress":
        return _scalars(cls, m)


@dataclass
class SurfaceResult(_Plain):
    """A curve network's surface (:meth:`Client.surface_network`):
    ``vertices`` float64 (V, 3), the network's vertices first, every one in
    its order at its exact coordinates (``report.input_vertices`` of them;
    a point welded to an earlier copy is left unused), then the new ones;
    ``faces`` int32 (F, 3) triangles, consistently oriented, every curve
    edge of a surfaced patch among their edges; ``report`` the
    :class:`SurfaceReport`."""
    vertices: np.ndarray
    faces: np.ndarray
    report: SurfaceReport


@dataclass
class Limits(_Plain):
    """The server's limits (proto ``Limits``)."""
    max_vertices: int = 0
    max_compute_ms: int = 0
    memory_budget_bytes: int = 0
    compute_threads: int = 0
    queue_size: int = 0
    all_space_max_vertices: int = 0
    max_message_bytes: int = 0
    cache_bytes: int = 0

    @classmethod
    def from_proto(cls, m: Any) -> "Limits":
        return _scalars(cls, m)


@dataclass
class ServerInfo(_Plain):
    """Version, build, backends, limits, license and source of a server."""
    version: str = ""
    build: str = ""
    backends: List[str] = field(default_factory=list)
    limits: Limits = field(default_factory=Limits)
    license: str = ""
    source_url: str = ""
    source_note: str = ""

    @classmethod
    def from_proto(cls, m: Any) -> "ServerInfo":
        return _scalars(cls, m, backends=list(m.backends),
                        limits=Limits.from_proto(m.limits))


# -- options ---------------------------------------------------------------


def _set(obj: Any, name: str, value: Any) -> None:
    object.__setattr__(obj, name, value)  # a frozen dataclass's own checks


@dataclass(frozen=True)
class Weights(_Plain):
    """A weight per metric (proto ``MetricWeights``): the objective is the
    weighted sum. All zero means area alone (Triangulate); a negative
    weight maximizes that metric. The metrics are defined in
    ``core/include/dot/metrics.h``."""
    area: float = 0.0
    perimeter: float = 0.0
    normal_deviation: float = 0.0
    shape: float = 0.0
    dihedral: float = 0.0
    squared_dihedral: float = 0.0

    def __post_init__(self) -> None:
        for m in METRICS:
            _set(self, m, check.number(m, getattr(self, m)))

    @classmethod
    def of(cls, value: "WeightsLike", use: str = "triangulate") -> "Weights":
        """Weights from a :class:`Weights`, the name of a
        :data:`WEIGHT_PRESETS` entry (its weights for ``use``:
        ``"triangulate"`` or ``"fill"``) or a mapping ``{metric: weight}``
        (the metrics it leaves out weigh 0)."""
        if isinstance(value, Weights):
            return value
        if isinstance(value, str):
            preset = WEIGHT_PRESETS.get(value.lower())
            if preset is None:
                raise InvalidInput(
                    f"there is no weights preset {value!r}; the presets are "
                    f"{', '.join(WEIGHT_PRESETS)}")
            return preset.triangulate if use == "triangulate" else preset.fill
        if isinstance(value, Mapping):
            unknown = sorted(str(k) for k in value if k not in METRICS)
            if unknown:
                raise InvalidInput(
                    f"unknown metric {', '.join(unknown)} in weights (the "
                    f"metrics are {', '.join(METRICS)})")
            return cls(**value)
        raise InvalidInput(
            f"weights must be a dot_client.Weights, a preset name "
            f"({', '.join(WEIGHT_PRESETS)}) or a dict of metric weights; got "
            f"{type(value).__name__}")

    def is_zero(self) -> bool:
        """True when every weight is 0."""
        return all(getattr(self, m) == 0 for m in METRICS)

    def to_proto(self, message: Any) -> None:
        """Sets the fields of a MetricWeights message."""
        for m in METRICS:
            setattr(message, m, getattr(self, m))


WeightsLike = Union[Weights, str, Mapping[str, float]]


@dataclass(frozen=True)
class WeightPreset:
    """Named metric weights (an entry of :data:`WEIGHT_PRESETS`):
    ``triangulate`` for one polygon's patch (Triangulate), ``fill`` for
    FillHoles, whose patches also meet the faces around the hole and whose
    area weight is per hole scale."""
    label: str
    description: str
    triangulate: Weights
    fill: Weights


#: The named weights of the client and the Blender add-on (its presets are
#: these entries). "smooth" for FillHoles is the service's own default
#: (FillOptions.weights unset), so choosing it changes nothing there.
#: Shape is a scale-free tie-break where the main metric has ties (flat
#: loops).
WEIGHT_PRESETS: Mapping[str, WeightPreset] = {
    "minimal_area": WeightPreset(
        "Minimal Area", "The patch of least area",
        triangulate=Weights(area=1), fill=Weights(area=1)),
    "smooth": WeightPreset(
        "Smooth", "Least squared dihedral angles between the patch's "
        "triangles (and the faces around a hole): a fair patch",
        triangulate=Weights(squared_dihedral=1, shape=0.01),
        fill=Weights(squared_dihedral=1, area=0.01)),
    "follow_normals": WeightPreset(
        "Follow Surrounding Normals", "Triangles facing like the surface's "
        "vertex normals around the loop",
        triangulate=Weights(normal_deviation=1, shape=0.01),
        fill=Weights(normal_deviation=1, area=0.01)),
}

_SEARCH_SPACES = _enum_values(pb.SearchSpace, "SEARCH_SPACE_")
_BACKENDS = _enum_values(pb.DelaunayBackend, "DELAUNAY_BACKEND_")
# FILL_STAGE_DEFAULT is fair: the client names the stage it means.
_FILL_STAGES = _enum_values(pb.FillStage, "FILL_STAGE_", skip=("default",))
_NETWORK_ISLANDS = _enum_values(pb.NetworkIslands, "NETWORK_ISLANDS_")

_O = TypeVar("_O", bound="_Options")


class _Options(_Plain):
    _weights_use = "triangulate"

    @classmethod
    def merged(cls: Type[_O], options: Optional[_O] = None,
               **changes: Any) -> _O:
        """``options`` (None: the defaults) with ``changes``: fields of
        this class, and metric names (``area=1``), each replacing that
        weight of the options' weights (of zero weights when they are
        unset). A change whose value is None is not given. This is how
        the client's keyword arguments become options."""
        if options is None:
            options = cls()
        elif not isinstance(options, cls):
            raise InvalidInput(f"options must be a dot_client.{cls.__name__}; "
                               f"got {type(options).__name__}")
        given = {k: v for k, v in changes.items() if v is not None}
        metrics = {m: given.pop(m) for m in METRICS if m in given}
        unknown = sorted(set(given) - {f.name for f in dataclasses.fields(cls)})
        if unknown:
            raise TypeError(f"{cls.__name__} has no option "
                            f"{', '.join(unknown)}")
        if metrics:
            base = given.get("weights", getattr(options, "weights"))
            base = Weights() if base is None else Weights.of(
                base, cls._weights_use)
            given["weights"] = dataclasses.replace(base, **metrics)
        return dataclasses.replace(options, **given) if given else options


@dataclass(frozen=True)
class TriangulateOptions(_Options):
    """How one polygon is triangulated (Triangulate, and each polygon of
    TriangulateBatch). Every field and its default:

    ``weights``: the objective, a :class:`Weights` (a preset name of
    :data:`WEIGHT_PRESETS` or a dict of metric weights is taken too).
    Default all zero: area alone. ``search_space``: ``"auto"`` (Delaunay
    triangles; all triangles for small polygons without a Delaunay
    triangulation; default), ``"delaunay"`` (never self-intersects),
    ``"all"`` or ``"delaunay_first"`` (every triangle, Delaunay ones first:
    large polygons with no Delaunay triangulation; may self-intersect, the
    summary counts the pairs). ``protect_edges``: split polygon edges that are not
    Delaunay (default False). ``delaunay_backend``: ``"default"`` (the
    server's), ``"cgal"`` or ``"tetgen"``. ``validate_output``: count
    self-intersecting pairs (default False). ``time_budget_ms``,
    ``memory_budget_bytes``: lower the server's limits (0, the default:
    the server's). ``no_cache``: skip the server's search-space cache
    (default False). ``keep_loop_directions``: with several loops, keep
    each loop's direction (default False: the solver may reverse loops
    after the first when the surface is cheaper that way).
    """
    weights: Weights = Weights()
    search_space: str = "auto"
    protect_edges: bool = False
    delaunay_backend: str = "default"
    validate_output: bool = False
    time_budget_ms: int = 0
    memory_budget_bytes: int = 0
    no_cache: bool = False
    keep_loop_directions: bool = False

    def __post_init__(self) -> None:
        _set(self, "weights", Weights.of(self.weights, "triangulate"))
        _set(self, "keep_loop_directions", check.flag(
            "keep_loop_directions", self.keep_loop_directions))
        _set(self, "search_space", check.choice(
            "search_space", self.search_space, list(_SEARCH_SPACES)))
        _set(self, "delaunay_backend", check.choice(
            "delaunay_backend", self.delaunay_backend, list(_BACKENDS)))
        _set(self, "protect_edges", check.flag("protect_edges",
                                               self.protect_edges))
        _set(self, "validate_output", check.flag("validate_output",
                                                 self.validate_output))
        _set(self, "no_cache", check.flag("no_cache", self.no_cache))
        _set(self, "time_budget_ms", check.integer("time_budget_ms",
                                                   self.time_budget_ms))
        _set(self, "memory_budget_bytes", check.integer(
            "memory_budget_bytes", self.memory_budget_bytes,
            maximum=check.UINT64_MAX))

    def to_proto(self, request: Any) -> None:
        """Sets ``weights`` and ``options`` of a TriangulateRequest (not
        ``progress_interval_ms`` and ``omit_input_vertices``: those are the
        call's)."""
        self.weights.to_proto(request.weights)
        o = request.options
        o.search_space = _SEARCH_SPACES[self.search_space]
        o.delaunay_backend = _BACKENDS[self.delaunay_backend]
        o.protect_edges = self.protect_edges
        o.validate_output = self.validate_output
        o.no_cache = self.no_cache
        o.keep_loop_directions = self.keep_loop_directions
        o.time_budget_ms = self.time_budget_ms
        o.memory_budget_bytes = self.memory_budget_bytes


def _ids(name: str, value: Any, minimum: int, maximum: int) -> Tuple[int, ...]:
    if value is None:
        return ()
    if isinstance(value, (str, bytes)) or not isinstance(
            value, (Sequence, np.ndarray)):
        raise InvalidInput(f"{name} must be a list of "
                           f"{'hole' if name == 'holes' or name.startswith('join') else 'vertex'} ids")
    return tuple(check.integer(f"{name}[{i}]", h, minimum=minimum,
                               maximum=maximum) for i, h in enumerate(value))


def _nonzero_weights(value: Any) -> Weights:
    """FillOptions' and SurfaceOptions' weights: set, so not all zero."""
    w = Weights.of(value, "fill")
    if w.is_zero():
        raise InvalidInput("every metric weight is zero; leave the weights "
                           "unset (None) for the default")
    return w


def _density(value: Any) -> float:
    """A refinement density factor: 0 (the default, sqrt(2)) or 0.1 .. 100."""
    d = check.number("density", value)
    if d != 0 and not 0.1 <= d <= 100:
        raise InvalidInput(
            f"density must be between 0.1 and 100 (0: sqrt(2)); got {d}")
    return d


@dataclass(frozen=True)
class FillOptions(_Options):
    """How FillHoles fills a mesh. Every field and its default:

    ``stage``: ``"triangulate"`` (the DOT patch), ``"refine"`` (+ Liepa
    refinement) or ``"fair"`` (+ fairing: the finished surface; default).
    ``weights``: None (default) for the hole-filling default (squared
    dihedral 1, area 0.01: the ``"smooth"`` preset), or a :class:`Weights`
    (a preset name of :data:`WEIGHT_PRESETS` or a dict is taken too; not
    all zero). ``absolute_weights``: keep area and perimeter in the mesh's
    units instead of per hole scale (default False).

    Which holes (a hole is filled when it passes every rule given):
    ``max_hole_edges`` (0, the default: any), ``max_hole_diameter``
    (bounding-box diagonal; 0: any), ``skip_longest`` (leave the longest
    border open; default False), ``holes`` (only these loop ids, as
    numbered in the report; empty: all), ``loops_through`` (only the loops
    through these vertex ids, as sent; a vertex on no border loop is
    refused; empty: all).

    Holes with islands: ``islands`` ``"auto"`` (default) joins each island
    (a piece of surface floating in a hole) to the rim around it in one
    patch, ``"off"`` fills every loop alone; ``join``: groups of loop ids,
    each filled by one patch (e.g. ``[(3, 7)]``).

    ``density``: refinement density factor (0, the default: sqrt(2);
    else 0.1 .. 100). ``fairing_continuity``: 0, 1 or 2 (None, the
    default: 1). ``no_repair``: use the mesh exactly as sent (default
    False: duplicate vertices merged, degenerate and duplicate faces
    dropped, polygons triangulated, faces oriented). ``time_budget_ms``,
    ``memory_budget_bytes``: lower the server's limits (0: the server's).
    ``keep_polygons``: :meth:`Client.fill_holes` answers the polygons sent
    (quads, n-gons) where no patch split one, instead of triangles
    (default False). ``allow_input_intersections``: fill a hole every
    patch of which meets the mesh when the mesh already intersects itself
    near it (its report keeps ``intersecting_pairs`` and
    ``input_pairs_near``); default False: such holes stay open.
    """
    _weights_use = "fill"

    stage: str = "fair"
    weights: Optional[Weights] = None
    absolute_weights: bool = False
    max_hole_edges: int = 0
    max_hole_diameter: float = 0.0
    skip_longest: bool = False
    holes: Tuple[int, ...] = ()
    loops_through: Tuple[int, ...] = ()
    islands: str = "auto"
    join: Tuple[Tuple[int, ...], ...] = ()
    density: float = 0.0
    fairing_continuity: Optional[int] = None
    no_repair: bool = False
    time_budget_ms: int = 0
    memory_budget_bytes: int = 0
    keep_polygons: bool = False
    allow_input_intersections: bool = False

    def __post_init__(self) -> None:
        _set(self, "stage", check.choice("stage", self.stage,
                                         list(_FILL_STAGES)))
        if self.weights is not None:
            _set(self, "weights", _nonzero_weights(self.weights))
        _set(self, "absolute_weights", check.flag("absolute_weights",
                                                  self.absolute_weights))
        _set(self, "max_hole_edges", check.integer("max_hole_edges",
                                                   self.max_hole_edges))
        _set(self, "max_hole_diameter", check.number(
            "max_hole_diameter", self.max_hole_diameter, minimum=0))
        _set(self, "skip_longest", check.flag("skip_longest",
                                              self.skip_longest))
        _set(self, "holes", _ids("holes", self.holes, -2**31, 2**31 - 1))
        _set(self, "loops_through", _ids("loops_through", self.loops_through,
                                         0, check.UINT32_MAX))
        _set(self, "islands", check.choice("islands", self.islands,
                                           ["auto", "off"]))
        if isinstance(self.join, (str, bytes)):
            raise InvalidInput("join must be groups of loop ids, e.g. "
                               "[(3, 7)]")
        groups = []
        for i, group in enumerate(self.join):
            ids = _ids(f"join[{i}]", group, 0, 2**31 - 1)
            if len(ids) < 2:
                raise InvalidInput(f"join[{i}] names fewer than 2 loops")
            groups.append(ids)
        _set(self, "join", tuple(groups))
        _set(self, "density", _density(self.density))
        if self.fairing_continuity is not None:
            _set(self, "fairing_continuity", check.integer(
                "fairing_continuity", self.fairing_continuity, 0, 2))
        _set(self, "no_repair", check.flag("no_repair", self.no_repair))
        _set(self, "keep_polygons", check.flag("keep_polygons",
                                               self.keep_polygons))
        _set(self, "allow_input_intersections", check.flag(
            "allow_input_intersections", self.allow_input_intersections))
        _set(self, "time_budget_ms", check.integer("time_budget_ms",
                                                   self.time_budget_ms))
        _set(self, "memory_budget_bytes", check.integer(
            "memory_budget_bytes", self.memory_budget_bytes,
            maximum=check.UINT64_MAX))

    def to_proto(self, answer: str = "mesh", dry_run: bool = False) -> Any:
        """The FillOptions message, asking for ``answer``: ``"mesh"`` (the
        whole filled mesh) or ``"patches"``; ``dry_run``: the report alone,
        nothing filled."""
        answers = _enum_values(pb.FillAnswer, "FILL_ANSWER_")
        o = pb.FillOptions(answer=answers[check.choice("answer", answer,
                                                       list(answers))])
        o.stage = _FILL_STAGES[self.stage]
        if self.weights is not None:
            self.weights.to_proto(o.weights)
        o.absolute_weights = self.absolute_weights
        o.max_hole_edges = self.max_hole_edges
        o.max_hole_diameter = self.max_hole_diameter
        o.skip_longest = self.skip_longest
        o.holes.extend(self.holes)
        o.loops_through.extend(self.loops_through)
        o.islands = pb.ISLANDS_OFF if self.islands == "off" else pb.ISLANDS_AUTO
        for group in self.join:
            o.join.add().loops.extend(group)
        o.density = self.density
        if self.fairing_continuity is not None:
            o.fairing_continuity = self.fairing_continuity
        o.no_repair = self.no_repair
        o.time_budget_ms = self.time_budget_ms
        o.memory_budget_bytes = self.memory_budget_bytes
        o.dry_run = dry_run
        o.keep_polygons = self.keep_polygons
        o.allow_input_intersections = self.allow_input_intersections
        return o


def _cycles(value: Any) -> Tuple[Tuple[Tuple[int, ...], ...], ...]:
    """SurfaceOptions.cycles as tuples: patches of loops of vertex ids."""
    if value is None:
        return ()
    hint = ("cycles must be a list of patches, each a list of loops, each a "
            "list of vertex ids (one patch of one loop: [[0, 1, 2, 3]])")
    if isinstance(value, (str, bytes)) or not isinstance(
            value, (Sequence, np.ndarray)):
        raise InvalidInput(hint)
    patches = []
    for p, patch in enumerate(value):
        if isinstance(patch, (str, bytes)) or not isinstance(
                patch, (Sequence, np.ndarray)):
            raise InvalidInput(f"cycles[{p}]: {hint}")
        if len(patch) == 0:
            raise InvalidInput(f"cycles[{p}] has no loops")
        loops = []
        for k, loop in enumerate(patch):
            if not isinstance(loop, (Sequence, np.ndarray)) or isinstance(
                    loop, (str, bytes)):
                raise InvalidInput(f"cycles[{p}][{k}] is not a list of "
                                   f"vertex ids: {hint}")
            ids = _ids(f"cycles[{p}][{k}]", loop, 0, check.UINT32_MAX)
            if not ids:
                raise InvalidInput(f"cycles[{p}][{k}] has no vertices")
            loops.append(ids)
        patches.append(tuple(loops))
    return tuple(patches)


@dataclass(frozen=True)
class SurfaceOptions(_Options):
    """How SurfaceNetwork surfaces a curve network. Every field and its
    default:

    ``stage``: ``"triangulate"`` (each patch's DOT triangulation over the
    curve vertices alone: no new vertices), ``"refine"`` (+ Liepa
    refinement) or ``"fair"`` (+ fairing of the whole network at once, every
    curve vertex fixed: the finished surface; default).
    ``weights``: None (default) for the service's (squared dihedral 1,
    normal deviation 0.25 against the normals the patches on each curve
    share, area 0.01), or a :class:`Weights` (a preset name of
    :data:`WEIGHT_PRESETS`, its FillHoles weights, or a dict is taken too;
    not all zero). ``absolute_weights``: keep area and perimeter in the
    network's units instead of per cycle scale (default False).
    ``density``: refinement density factor (0, the default: sqrt(2); else
    0.1 .. 100). ``fairing_continuity``: 0 (membrane), 1 (thin plate) or 2
    (minimum variation); None, the default: 1.

    ``cycles``: the patches, given: a list of patches, each a list of
    loops, each a list of vertex ids as sent (``[[bottom, top]]``: one
    patch joining two rims, a tube); consecutive ids must be joined by a
    curve (listing the junctions is enough where one curve joins them).
    Empty (default): the server finds the cycles (a rotation system at the
    junctions; manifold networks of any genus; a closed curve alone bounds
    a disk). ``skip_longest``: leave the found cycle with the most vertices
    open (the rim of an open sheet; default False). ``islands``: a closed
    curve alone inside a found face (a circle drawn on a box's lid):
    ``"inset"`` (default) makes it an island of that face and a patch of
    its own, so the surface stays closed; ``"hole"`` an island only (a
    hole in the face); ``"off"`` a patch of its own only. ``walls``: also
    find walls, flat cycles that make a third patch on their curves (a
    partition inside a box; default False: a ring of curves around a body
    is only the line between two patches). ``weld_distance``: each free
    end (an end no other polyline meets) is welded to the nearest point
    within this distance (the network's units) not on its own stroke, so
    that strokes whose ends nearly meet become junctions (default 0: only points at exactly
    the same place).
    ``time_budget_ms``, ``memory_budget_bytes``: lower the server's limits
    (0: the server's).
    """
    _weights_use = "fill"

    stage: str = "fair"
    weights: Optional[Weights] = None
    absolute_weights: bool = False
    density: float = 0.0
    fairing_continuity: Optional[int] = None
    cycles: Tuple[Tuple[Tuple[int, ...], ...], ...] = ()
    skip_longest: bool = False
    islands: str = "inset"
    walls: bool = False
    weld_distance: float = 0.0
    time_budget_ms: int = 0
    memory_budget_bytes: int = 0

    def __post_init__(self) -> None:
        _set(self, "stage", check.choice("stage", self.stage,
                                         list(_FILL_STAGES)))
        _set(self, "islands", check.choice("islands", self.islands,
                                           list(_NETWORK_ISLANDS)))
        _set(self, "walls", check.flag("walls", self.walls))
        _set(self, "weld_distance", check.number(
            "weld_distance", self.weld_distance, minimum=0))
        if self.weights is not None:
            _set(self, "weights", _nonzero_weights(self.weights))
        _set(self, "absolute_weights", check.flag("absolute_weights",
                                                  self.absolute_weights))
        _set(self, "density", _density(self.density))
        if self.fairing_continuity is not None:
            _set(self, "fairing_continuity", check.integer(
                "fairing_continuity", self.fairing_continuity, 0, 2))
        _set(self, "cycles", _cycles(self.cycles))
        _set(self, "skip_longest", check.flag("skip_longest",
                                              self.skip_longest))
        _set(self, "time_budget_ms", check.integer("time_budget_ms",
                                                   self.time_budget_ms))
        _set(self, "memory_budget_bytes", check.integer(
            "memory_budget_bytes", self.memory_budget_bytes,
            maximum=check.UINT64_MAX))

    def to_proto(self) -> Any:
        """The SurfaceOptions message."""
        o = pb.SurfaceOptions(stage=_FILL_STAGES[self.stage])
        if self.weights is not None:
            self.weights.to_proto(o.weights)
        o.absolute_weights = self.absolute_weights
        o.density = self.density
        if self.fairing_continuity is not None:
            o.fairing_continuity = self.fairing_continuity
        for patch in self.cycles:
            c = o.cycles.add()
            for loop in patch:
                c.loops.add().vertices.extend(loop)
        o.skip_longest = self.skip_longest
        o.islands = _NETWORK_ISLANDS[self.islands]
        o.walls = self.walls
        o.weld_distance = self.weld_distance
        o.time_budget_ms = self.time_budget_ms
        o.memory_budget_bytes = self.memory_budget_bytes
        return o

# SPDX-License-Identifier: AGPL-3.0-or-later
"""Plain Python mirrors of the dot.v1 messages a caller reads.

Each class mirrors one proto message field by field (see
``proto/dot/v1/triangulation.proto``); enums become lower-case strings
(``"ok"``, ``"no_triangulation"``, ``"delaunay"``), repeated index fields
become numpy arrays, metric weights a dict keyed by metric name.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

import numpy as np

from ._errors import DotError

METRICS = ("area", "perimeter", "normal_deviation", "shape", "dihedral",
           "squared_dihedral")


def _enum_name(value: int, enum: Any, prefix: str) -> str:
    try:
        name = enum.Name(value)
    except ValueError:
        return str(value)
    return name[len(prefix):].lower() if name.startswith(prefix) else name.lower()


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

    @classmethod
    def from_proto(cls, m: Any) -> "Stats":
        return _scalars(cls, m)


@dataclass
class Summary(_Plain):
    """The proto ``Summary`` of one triangulation.

    ``status`` is ``"ok"`` or ``"no_triangulation"`` (then ``message`` says
    why and ``non_delaunay_edges`` lists offending edges as (k, 2) vertex
    index pairs). ``loop`` is the polygon with inserted vertices in place
    (only when ``inserted_count`` > 0). ``metric_costs`` maps each metric to
    its unweighted sum. ``intersecting_pairs`` is -1 when not checked.
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

    @classmethod
    def from_proto(cls, m: Any) -> "Summary":
        from ._proto.dot.v1 import triangulation_pb2 as pb
        return _scalars(
            cls, m,
            status=_enum_name(m.status, pb.ResultStatus, "RESULT_STATUS_"),
            loop=np.array(m.loop, dtype=np.int64).astype(np.int32),
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
        from ._proto.dot.v1 import triangulation_pb2 as pb
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
    ``"no_triangulation"`` or ``"failed"`` (``reason`` says why);
    ``split_faces`` lists input faces split by edge protection."""
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

    @classmethod
    def from_proto(cls, m: Any) -> "HoleReport":
        return _scalars(cls, m, split_faces=list(m.split_faces))


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

    @classmethod
    def from_proto(cls, m: Any) -> "FillReport":
        return _scalars(cls, m,
                        holes=[HoleReport.from_proto(h) for h in m.holes],
                        repair=RepairReport.from_proto(m.repair))


@dataclass
class FillResult(_Plain):
    """A filled mesh: ``vertices`` float64 (V, 3), the (repaired) input's
    first, then new ones; ``faces`` int32 (F, 3); ``report`` the
    :class:`FillReport`."""
    vertices: np.ndarray
    faces: np.ndarray
    report: FillReport


@dataclass
class FillProgress(_Plain):
    """Holes done so far out of all holes being filled."""
    holes_done: int = 0
    holes_total: int = 0
    elapsed_ms: float = 0.0

    @classmethod
    def from_proto(cls, m: Any) -> "FillProgress":
        return _scalars(cls, m)


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

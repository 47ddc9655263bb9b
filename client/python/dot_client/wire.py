# SPDX-License-Identifier: AGPL-3.0-or-later
"""The dot.v1 wire format as dotctl speaks it, in Python.

:class:`MeshAssembler` mirrors ``dot::wire::MeshAssembler``
(``proto/wire/wire.cc``) and :class:`PatchReader`
``dot::wire::PatchReader`` (``proto/wire/fill_wire.cc``) check for check
and message for message; :func:`fill_requests` mirrors
``dot::wire::FillRequestWriter`` (``proto/wire/fill_wire.cc``) and
:func:`surface_requests` ``dot::wire::SurfaceRequestWriter``
(``proto/wire/surface_wire.cc``);
:func:`assemble_triangulate`, :func:`assemble_fill` and
:func:`assemble_patches` read a response stream as ``TriangulateRemote``
(``client/remote/grpc_calls.cc``) and ``FillRemote`` (same file)
do, and :func:`assemble_surface` a SurfaceNetwork answer. The client
uses them on live streams; tests replay recorded streams
(``tests/golden/``) through them, and the C++ tests replay the same files
through the C++ code, so the two cannot drift apart.
"""
from __future__ import annotations

import struct
from typing import (Any, BinaryIO, Callable, Dict, Iterable, Iterator, List,
                    Optional, Sequence, Tuple, Type, TypeVar, Union)

import grpc
import numpy as np

from ._errors import DotError, FillStopped, from_rpc_error
from ._proto.dot.v1 import triangulation_pb2 as pb
from ._types import (FillPatches, FillProgress, FillReport, FillResult,
                     HolePatch, Progress, Result, Summary, SurfaceProgress,
                     SurfaceReport, SurfaceResult)

#: Requests stay well under gRPC's default 4 MiB message limit (as dotctl).
REQUEST_BYTES = 1 << 20


class AssemblyError(Exception):
    """A mesh chunk stream that does not add up (message as the C++ one)."""


def _float_array(values: Any) -> np.ndarray:
    return np.fromiter(values, dtype=np.float64, count=len(values))


def _index_array(values: Any) -> np.ndarray:
    return np.fromiter(values, dtype=np.int64, count=len(values))


class MeshAssembler:
    """Reassembles a mesh from MeshChunk messages (``wire::MeshAssembler``).

    Vertices and triangles are each contiguous across chunks; the first
    vertex chunk fixes where the received vertices start, and vertices
    before that (the input's, when ``omit_input_vertices`` was set) are
    taken from the caller's input in :meth:`finish`.
    """

    def __init__(self) -> None:
        self._vertices: List[np.ndarray] = []
        self._vertex_count = 0
        self._triangles: List[np.ndarray] = []
        self._triangle_count = 0
        self._first_vertex = 0
        self._started = False

    def add(self, chunk: Any) -> None:
        """Adds one MeshChunk; raises :class:`AssemblyError` when it does
        not continue the mesh."""
        nv, nt = len(chunk.vertices), len(chunk.triangles)
        if nv % 3 != 0 or nt % 3 != 0:
            raise AssemblyError("mesh chunk with a partial vertex or triangle")
        if nv > 0:
            if not self._started:
                self._started = True
                self._first_vertex = chunk.first_vertex
            expected = self._first_vertex + self._vertex_count
            if chunk.first_vertex != expected:
                raise AssemblyError(
                    f"mesh chunk out of order: vertex {chunk.first_vertex} "
                    f"after {expected}")
            self._vertices.append(_float_array(chunk.vertices).reshape(-1, 3))
            self._vertex_count += nv // 3
        if nt > 0:
            if chunk.first_triangle != self._triangle_count:
                raise AssemblyError(
                    f"mesh chunk out of order: triangle {chunk.first_triangle}"
                    f" after {self._triangle_count}")
            self._triangles.append(_index_array(chunk.triangles).reshape(-1, 3))
            self._triangle_count += nt // 3

    def finish(self, vertex_count: int, triangle_count: int,
               input_vertices: Optional[np.ndarray] = None
               ) -> Tuple[np.ndarray, np.ndarray]:
        """The whole mesh: (vertices float64 (V, 3), triangles int32 (T, 3)).

        Checks it against the announced counts; vertices the server
        omitted come from ``input_vertices``.
        """
        if input_vertices is None:
            input_vertices = np.zeros((0, 3))
        if not self._started:
            self._first_vertex = vertex_count
        if self._first_vertex > len(input_vertices):
            raise AssemblyError(
                f"mesh starts at vertex {self._first_vertex} but only "
                f"{len(input_vertices)} input vertices are known")
        parts = [np.asarray(input_vertices[:self._first_vertex],
                            dtype=np.float64).reshape(-1, 3)] + self._vertices
        vertices = np.concatenate(parts) if len(parts) > 1 else parts[0].copy()
        triangles = (np.concatenate(self._triangles) if self._triangles
                     else np.zeros((0, 3), dtype=np.int64))
        self._vertices, self._triangles = [], []
        if len(vertices) != vertex_count or len(triangles) != triangle_count:
            raise AssemblyError(
                f"incomplete mesh: {len(vertices)} vertices and "
                f"{len(triangles)} triangles received, the server announced "
                f"{vertex_count} and {triangle_count}")
        # Indices arrive as uint32; C++ reads them as int32, so values past
        # 2^31 are negative there: both refuse them.
        signed = np.where(triangles >= 2**31, triangles - 2**32, triangles)
        bad = (signed < 0) | (signed >= len(vertices))
        if bad.any():
            raise AssemblyError(
                f"mesh triangle refers to vertex {int(signed[bad][0])}")
        return vertices, signed.astype(np.int32)


class SoupAssembler:
    """Reassembles a polygon soup with attribute channels from MeshChunk
    slices (``wire::SoupChunkReader``, order checks and messages as
    there): vertices, then faces (``face_sizes`` for polygons), then each
    channel's rows and, per corner, its indices."""

    def __init__(self) -> None:
        self._vertices: List[np.ndarray] = []
        self._vertex_count = 0
        self._indices: List[np.ndarray] = []
        self._sizes: List[np.ndarray] = []
        self._face_count = 0
        self._corner_count = 0
        self._channels: Dict[str, Dict[str, Any]] = {}
        self._last: Optional[str] = None

    def add(self, chunk: Any, where: str) -> None:
        """Adds one MeshChunk; raises :class:`AssemblyError` naming
        ``where`` when it does not continue the soup."""
        nv, ni = len(chunk.vertices), len(chunk.triangles)
        if nv % 3 != 0:
            raise AssemblyError(f"{where} has {nv} coordinates, not a "
                                f"multiple of 3")
        if (nv or ni) and self._channels:
            raise AssemblyError(f"{where} sends "
                                f"{'faces' if ni else 'vertices'} after "
                                f"attributes")
        if nv:
            if self._face_count:
                raise AssemblyError(f"{where} sends vertices after faces")
            if chunk.first_vertex != self._vertex_count:
                raise AssemblyError(
                    f"{where} starts at vertex {chunk.first_vertex} but "
                    f"{self._vertex_count} vertices have arrived")
            self._vertices.append(_float_array(chunk.vertices).reshape(-1, 3))
            self._vertex_count += nv // 3
        if ni:
            if chunk.first_triangle != self._face_count:
                raise AssemblyError(
                    f"{where} starts at face {chunk.first_triangle} but "
                    f"{self._face_count} faces have arrived")
            sizes = (_index_array(chunk.face_sizes) if len(chunk.face_sizes)
                     else np.full(ni // 3, 3, dtype=np.int64))
            if (sizes < 3).any() or sizes.sum() != ni:
                raise AssemblyError(f"{where}: face_sizes do not add up to "
                                    f"its {ni} face indices")
            ids = _index_array(chunk.triangles)
            if (ids >= self._vertex_count).any():
                raise AssemblyError(
                    f"face {self._face_count} has vertex index "
                    f"{int(ids[ids >= self._vertex_count][0])}, but only "
                    f"{self._vertex_count} vertices were sent")
            self._indices.append(ids)
            self._sizes.append(sizes)
            self._face_count += len(sizes)
            self._corner_count += ni
        if chunk.HasField("attribute"):
            self._add_attribute(chunk.attribute, where)

    def _add_attribute(self, a: Any, where: str) -> None:
        name = a.name
        if not self._face_count:
            raise AssemblyError(f"{where} sends attribute '{name}' before "
                                f"any face")
        if name != self._last:
            if name in self._channels:
                raise AssemblyError(f"{where}: attribute '{name}' is sent "
                                    f"twice")
            if not 1 <= a.dims <= 16:
                raise AssemblyError(f"{where}: attribute '{name}' has "
                                    f"{a.dims} values an entry")
            self._channels[name] = {"dims": a.dims,
                                    "per_corner": a.per_corner,
                                    "values": [], "entries": 0,
                                    "indices": [], "corners": 0}
            self._last = name
        ch = self._channels[name]
        if a.dims != ch["dims"] or a.per_corner != ch["per_corner"]:
            raise AssemblyError(f"{where}: attribute '{name}' changes its "
                                f"dims or per_corner between slices")
        if len(a.values):
            if len(a.values) % ch["dims"] or a.first_value != ch["entries"] \
                    or ch["corners"]:
                raise AssemblyError(f"{where}: attribute '{name}' values do "
                                    f"not continue at entry {ch['entries']}")
            ch["values"].append(np.fromiter(
                a.values, dtype=np.float32,
                count=len(a.values)).reshape(-1, ch["dims"]))
            ch["entries"] += len(a.values) // ch["dims"]
        if len(a.indices):
            if not ch["per_corner"] or a.first_corner != ch["corners"]:
                raise AssemblyError(f"{where}: attribute '{name}' indices do "
                                    f"not continue at corner "
                                    f"{ch['corners']}")
            ch["indices"].append(_index_array(a.indices))
            ch["corners"] += len(a.indices)

    def finish(self, vertex_count: int) -> Tuple[
            np.ndarray, Union[np.ndarray, List[np.ndarray]],
            Dict[str, Tuple[bool, np.ndarray]]]:
        """(vertices (V, 3), faces, channels): faces an int32 (F, 3) array
        when every face is a triangle, else a list of int32 arrays;
        channels {name: (per_corner, float32 rows)}, a row per vertex or,
        per corner, per face corner in face order (indices resolved)."""
        vertices = (np.concatenate(self._vertices) if self._vertices
                    else np.zeros((0, 3)))
        if len(vertices) != vertex_count:
            raise AssemblyError(
                f"{len(vertices)} vertices received, the report announced "
                f"{vertex_count}")
        ids = (np.concatenate(self._indices) if self._indices
               else np.zeros(0, dtype=np.int64)).astype(np.int32)
        sizes = (np.concatenate(self._sizes) if self._sizes
                 else np.zeros(0, dtype=np.int64))
        faces: Union[np.ndarray, List[np.ndarray]]
        if (sizes == 3).all():
            faces = ids.reshape(-1, 3)
        else:
            faces = np.split(ids, np.cumsum(sizes)[:-1])
        channels: Dict[str, Tuple[bool, np.ndarray]] = {}
        for name, ch in self._channels.items():
            rows = (np.concatenate(ch["values"]) if ch["values"]
                    else np.zeros((0, ch["dims"]), dtype=np.float32))
            if not ch["per_corner"]:
                if len(rows) != len(vertices):
                    raise AssemblyError(
                        f"attribute '{name}' has {len(rows)} entries for "
                        f"{len(vertices)} vertices")
                channels[name] = (False, rows)
                continue
            index = (np.concatenate(ch["indices"]) if ch["indices"]
                     else np.zeros(0, dtype=np.int64))
            if len(index) != self._corner_count:
                raise AssemblyError(
                    f"attribute '{name}' is per_corner but {len(index)} "
                    f"indices arrived for {self._corner_count} face corners")
            if len(index) and index.max() >= len(rows):
                raise AssemblyError(f"attribute '{name}' names entry "
                                    f"{int(index.max())}, outside "
                                    f"0..{len(rows) - 1}")
            channels[name] = (True, rows[index])
        return vertices, faces, channels


def assemble_triangulate(
        responses: Iterable[Any], points: np.ndarray,
        on_progress: Optional[Callable[[Progress], None]] = None) -> Result:
    """The Result of a Triangulate response stream that ended OK.

    ``points`` are the polygon's vertices as sent (the server leaves them
    out when ``omit_input_vertices`` is set). A polygon without
    triangulation gives a Result with empty arrays and
    ``summary.status == "no_triangulation"``. Raises :class:`DotError`
    (``DATA_LOSS``) when the stream does not add up, as dotctl does;
    errors raised by ``responses`` itself (a failed RPC) pass through.
    """
    assembler = MeshAssembler()
    summary = None
    assembly: Optional[str] = None
    request_id = ""
    for message in responses:
        request_id = message.id or request_id
        kind = message.WhichOneof("payload")
        if kind == "progress":
            if on_progress is not None:
                on_progress(Progress.from_proto(message.progress))
        elif kind == "mesh":
            if assembly is None:
                try:
                    assembler.add(message.mesh)
                except AssemblyError as e:
                    assembly = str(e)
        elif kind == "summary":
            summary = message.summary
    if summary is None:
        raise DotError(grpc.StatusCode.DATA_LOSS,
                       "stream ended without a summary")
    return _finish_triangulate(request_id, summary, assembler, assembly, points)


def _finish_triangulate(request_id: str, summary_proto: Any,
                        assembler: MeshAssembler, assembly: Optional[str],
                        points: np.ndarray) -> Result:
    summary = Summary.from_proto(summary_proto)
    vertices = np.zeros((0, 3))
    triangles = np.zeros((0, 3), dtype=np.int32)
    if assembly is None and summary_proto.status == pb.RESULT_STATUS_OK:
        try:
            vertices, triangles = assembler.finish(
                summary_proto.vertex_count, summary_proto.triangle_count,
                points)
        except AssemblyError as e:
            assembly = str(e)
    if assembly is not None:
        raise DotError(grpc.StatusCode.DATA_LOSS, assembly)
    return Result(vertices=vertices, triangles=triangles, summary=summary,
                  id=request_id)


class PatchReader:
    """Reassembles the HolePatch messages of a patches answer
    (``wire::PatchReader``, check for check and message for message): a
    message with the hole of the last one continues that patch; every
    message's ``first_vertex`` follows the vertices received so far (the
    first patch's the ``sent_vertices`` of the upload, when given); holes
    come in increasing id order; faces name vertices that exist by then."""

    def __init__(self, sent_vertices: Optional[int] = None) -> None:
        self._patches: List[Dict[str, Any]] = []
        self._next = sent_vertices

    def add(self, m: Any) -> None:
        """Adds one HolePatch message; raises :class:`AssemblyError` when
        it does not continue the patches."""
        if len(m.vertices) % 3 != 0 or len(m.faces) % 3 != 0:
            raise AssemblyError(f"a patch message of hole {m.hole} has a "
                                f"partial vertex or triangle")
        if self._next is None:
            self._next = m.first_vertex
        if m.first_vertex != self._next:
            raise AssemblyError(
                f"the patch of hole {m.hole} starts at vertex "
                f"{m.first_vertex}, not {self._next}: it does not continue "
                f"where the last message ended")
        continues = bool(self._patches) and self._patches[-1]["hole"] == m.hole
        if not continues and self._patches and \
                m.hole < self._patches[-1]["hole"]:
            raise AssemblyError(
                f"the patch of hole {m.hole} comes after hole "
                f"{self._patches[-1]['hole']}'s: patches come in hole order")
        if not continues:
            self._patches.append({"hole": m.hole,
                                  "first_vertex": m.first_vertex,
                                  "vertices": [], "faces": [],
                                  "replaced": [],
                                  "channels": [(c.name, c.dims, [], [])
                                               for c in m.attributes]})
        p = self._patches[-1]
        # Each message gives every channel's values for its own corners.
        replacing = sum(len(r.triangles) // 3 for r in m.replaced_faces)
        if len(m.attributes) != len(p["channels"]):
            raise AssemblyError(
                f"a patch message of hole {m.hole} has {len(m.attributes)} "
                f"attribute channels, not {len(p['channels'])}")
        for c, (name, dims, on_faces, on_replaced) in zip(m.attributes,
                                                          p["channels"]):
            if c.name != name or c.dims != dims or not 1 <= dims <= 16 or \
                    len(c.faces) != dims * len(m.faces) or \
                    len(c.replaced) != 3 * dims * replacing:
                raise AssemblyError(
                    f"a patch message of hole {m.hole}: attribute "
                    f"'{c.name}' does not match the message's corners")
            on_faces.append(np.fromiter(c.faces, dtype=np.float32,
                                        count=len(c.faces)))
            on_replaced.append(np.fromiter(c.replaced, dtype=np.float32,
                                           count=len(c.replaced)))
        self._next += len(m.vertices) // 3
        for ids in [m.faces] + [r.triangles for r in m.replaced_faces]:
            if len(ids) and max(ids) >= self._next:
                bad = next(v for v in ids if v >= self._next)
                raise AssemblyError(
                    f"the patch of hole {m.hole} names vertex {bad}, but "
                    f"only {self._next} exist")
        if len(m.vertices):
            p["vertices"].append(_float_array(m.vertices).reshape(-1, 3))
        if len(m.faces):
            p["faces"].append(_index_array(m.faces).reshape(-1, 3))
        for r in m.replaced_faces:
            if len(r.triangles) % 3 != 0:
                raise AssemblyError(
                    f"replaced face {r.face} has a partial triangle")
            p["replaced"].append(
                (r.face, _index_array(r.triangles).reshape(-1, 3)))

    def finish(self) -> List[HolePatch]:
        """The patches, in the order they came. Ids arrive as uint32 and
        are read as int32, as the C++ client reads them."""
        def ids(parts: List[np.ndarray]) -> np.ndarray:
            a = (np.concatenate(parts) if parts
                 else np.zeros((0, 3), dtype=np.int64))
            return a.astype(np.int32)

        out = []
        for p in self._patches:
            corner_data, replaced_data = {}, {}
            for name, dims, on_faces, on_replaced in p["channels"]:
                corner_data[name] = np.concatenate(on_faces).reshape(-1, dims)
                rows = np.concatenate(on_replaced).reshape(-1, dims)
                at = 0
                for face, t in p["replaced"]:
                    replaced_data.setdefault(int(face), {})[name] = \
                        rows[at:at + 3 * len(t)]
                    at += 3 * len(t)
            out.append(HolePatch(
                hole=p["hole"], first_vertex=p["first_vertex"],
                vertices=(np.concatenate(p["vertices"]) if p["vertices"]
                          else np.zeros((0, 3))),
                faces=ids(p["faces"]),
                replaced_faces={int(face): ids([t])
                                for face, t in p["replaced"]},
                corner_data=corner_data, replaced_corner_data=replaced_data))
        return out


def _read_fill(responses: Iterable[Any],
               on_progress: Optional[Callable[[FillProgress], None]],
               answer: str,
               sent_vertices: Optional[int] = None
               ) -> Tuple[Any, Any, Optional[grpc.RpcError]]:
    # answer "soup": the mesh as SoupAssembler reads it (polygons or
    # attribute channels kept).
    """FillRemote's loop over a FillHoles response stream: the report
    message, the mesh (``answer`` "mesh": vertices, faces) or the
    patches, and the error the stream ended with when the fill stopped
    early but answered whole (a report with ``stopped`` holes), else None;
    raises :class:`DotError` (``INTERNAL``) with dotctl's messages."""
    assembler = MeshAssembler()
    soup = SoupAssembler()
    chunks = 0
    patches = PatchReader(sent_vertices)
    report = None
    assembled: Optional[str] = None
    stopped: Optional[grpc.RpcError] = None
    messages = iter(responses)
    while True:
        try:
            message = next(messages)
        except StopIteration:
            break
        except grpc.RpcError as e:
            # A fill that stopped early answers whole, then says why.
            if report is None or report.stopped == 0:
                raise
            stopped = e
            break
        kind = message.WhichOneof("payload")
        if kind == "progress":
            if on_progress is not None:
                on_progress(FillProgress.from_proto(message.progress))
        elif kind == "mesh":
            if assembled is None:
                try:
                    if answer == "soup":
                        soup.add(message.mesh, f"mesh chunk {chunks}")
                    else:
                        assembler.add(message.mesh)
                except AssemblyError as e:
                    assembled = str(e)
                chunks += 1
        elif kind == "patch":
            if assembled is None:
                try:
                    patches.add(message.patch)
                except AssemblyError as e:
                    assembled = str(e)
        elif kind == "report":
            report = message.report
    if report is None:
        raise DotError(grpc.StatusCode.INTERNAL,
                       "the server ended the stream without a report")
    out: Any = None
    if assembled is None and answer == "soup":
        try:
            out = soup.finish(report.input_vertices + report.added_vertices)
        except AssemblyError as e:
            assembled = str(e)
    elif assembled is None and answer == "mesh":
        try:
            out = assembler.finish(
                report.input_vertices + report.added_vertices,
                report.input_faces + report.added_faces)
        except AssemblyError as e:
            assembled = str(e)
    elif assembled is None:
        out = patches.finish()
    if assembled is not None:
        raise DotError(grpc.StatusCode.INTERNAL,
                       f"bad mesh from the server: {assembled}")
    return report, out, stopped


def _raise_stopped(stopped: Optional[grpc.RpcError], result: Any) -> None:
    """FillStopped with `result` when the stream ended with a stop."""
    if stopped is None:
        return
    error = from_rpc_error(stopped)
    raise FillStopped(error.code, error.message, result)


def assemble_fill(
        responses: Iterable[Any],
        on_progress: Optional[Callable[[FillProgress], None]] = None,
        as_sent: bool = False, per_corner: Sequence[str] = (),
        sent: Sequence[str] = (), triangles: bool = True
) -> FillResult:
    """The FillResult of a FillHoles response stream (answer
    ``FILL_ANSWER_MESH``) that ended OK; raises :class:`FillStopped`
    with it when the fill stopped early but answered what it had.
    ``as_sent``: the request kept polygons or sent attribute channels, so
    the mesh comes as :class:`SoupAssembler` reads it; the channels go in
    the result's ``point_data`` and ``corner_data`` as they came, except
    the ``per_corner`` ones (sent per corner), which stay per corner; a
    channel of ``sent`` that did not come back (a server from before
    attributes on the wire) is named in ``report.notes``. ``triangles``:
    polygons were not kept, so the faces must be the report's count.

    Raises :class:`DotError` (``INTERNAL``) when the report is missing or
    the mesh does not add up, with dotctl's messages.
    """
    report, mesh, stopped = _read_fill(responses, on_progress,
                                       "soup" if as_sent else "mesh")
    result = FillResult(vertices=mesh[0], faces=mesh[1],
                        report=FillReport.from_proto(report))
    faces = report.input_faces + report.added_faces
    if as_sent and triangles and len(mesh[1]) != faces:
        raise DotError(grpc.StatusCode.INTERNAL,
                       f"bad mesh from the server: {len(mesh[1])} faces "
                       f"received, the report announced {faces}")
    if as_sent:
        corner_ids = (mesh[1].reshape(-1) if isinstance(mesh[1], np.ndarray)
                      else np.concatenate(mesh[1]))
        for name, (corner, rows) in mesh[2].items():
            if corner:
                result.corner_data[name] = rows
            elif name in per_corner:
                result.corner_data[name] = rows[corner_ids]
            else:
                result.point_data[name] = rows
        for name in sent:
            if name not in mesh[2] and not any(
                    f"'{name}'" in n for n in result.report.notes):
                result.report.notes.append(
                    f"attribute '{name}' was not answered: the server "
                    f"predates attributes on the wire")
    _raise_stopped(stopped, result)
    return result


def assemble_patches(
        responses: Iterable[Any],
        on_progress: Optional[Callable[[FillProgress], None]] = None,
        sent_vertices: Optional[int] = None
) -> FillPatches:
    """The FillPatches of a FillHoles response stream (answer
    ``FILL_ANSWER_PATCHES``) that ended OK (or :class:`FillStopped` with
    it, as :func:`assemble_fill`): its HolePatch messages
    reassembled by :class:`PatchReader` (the first patch's vertices must
    follow the upload's ``sent_vertices``, when given). Raises
    :class:`DotError` (``INTERNAL``) as :func:`assemble_fill` does."""
    report, patches, stopped = _read_fill(responses, on_progress, "patches",
                                          sent_vertices)
    result = FillPatches(patches=patches, report=FillReport.from_proto(report))
    _raise_stopped(stopped, result)
    return result


def assemble_surface(
        responses: Iterable[Any], vertices: np.ndarray,
        on_progress: Optional[Callable[[SurfaceProgress], None]] = None
) -> SurfaceResult:
    """The SurfaceResult of a SurfaceNetwork response stream that ended
    OK, read as ``SurfaceRemote`` (``client/remote/grpc_calls.cc``) reads it:
    progress messages (to ``on_progress``), the whole mesh in MeshChunk
    slices (reassembled by :class:`MeshAssembler` to the report's
    ``mesh_vertices`` and ``mesh_faces``, at least as many vertices as
    ``vertices``, the network as sent), the report last. Raises
    :class:`DotError` (``INTERNAL``) when the report is missing or the
    mesh does not add up, with dotctl's messages."""
    assembler = MeshAssembler()
    report = None
    assembled: Optional[str] = None
    for message in responses:
        kind = message.WhichOneof("payload")
        if kind == "progress":
            if on_progress is not None:
                on_progress(SurfaceProgress.from_proto(message.progress))
        elif kind == "mesh":
            if assembled is None:
                try:
                    assembler.add(message.mesh)
                except AssemblyError as e:
                    assembled = str(e)
        elif kind == "report":
            report = message.report
    if report is None:
        raise DotError(grpc.StatusCode.INTERNAL,
                       "the server ended the stream without a report")
    if assembled is None:
        try:
            mesh_vertices, faces = assembler.finish(report.mesh_vertices,
                                                    report.mesh_faces)
            if len(mesh_vertices) < len(vertices):
                assembled = ("the surface has fewer vertices than the "
                             "network sent")
        except AssemblyError as e:
            assembled = str(e)
    if assembled is not None:
        raise DotError(grpc.StatusCode.INTERNAL,
                       f"bad mesh from the server: {assembled}")
    return SurfaceResult(vertices=mesh_vertices, faces=faces,
                         report=SurfaceReport.from_proto(report))


FaceInput = Union[np.ndarray, Sequence[Sequence[int]]]


def fill_requests(request_id: str, options: Any, vertices: np.ndarray,
                  faces: Union[np.ndarray, List[np.ndarray]],
                  max_bytes: int = REQUEST_BYTES,
                  channels: Sequence[Tuple[str, bool, np.ndarray]] = ()
                  ) -> Iterator[Any]:
    """The FillHolesRequest stream of a mesh, made lazily, message by
    message (the upload never holds a second copy of the mesh).

    As ``FillRequestWriter`` (dot.v1 revision 2): the mesh goes in
    ``mesh`` (MeshChunk) slices, vertices first, at most ``max_bytes`` //
    24 per message, each slice's ``first_vertex`` the number of vertices
    sent before it; then faces, starting in a message of their own, at
    most ``max_bytes`` // 5 indices per message but never splitting a
    face, each slice's ``first_triangle`` the number of faces sent before
    it (and its ``first_vertex`` the vertex count). The first message
    carries id and options with the first slice. ``face_sizes`` is sent
    only when some face is not a triangle. ``faces`` is an int array
    (F, k) or a list of int arrays (polygons). Then each of ``channels``
    ((name, per_corner, float32 (n, d) rows)) in ``attribute`` slices of
    at most ``max_bytes`` // 5 floats: its rows, then, per corner, an
    index per corner (row c for corner c).
    """
    first = pb.FillHolesRequest(id=request_id)
    first.options.CopyFrom(options)
    return _sliced(first, pb.FillHolesRequest, "mesh", vertices, faces,
                   max_bytes, channels)


def surface_requests(request_id: str, options: Any, vertices: np.ndarray,
                     polylines: Union[np.ndarray, List[np.ndarray]],
                     max_bytes: int = REQUEST_BYTES,
                     channels: Sequence[Tuple[str, bool, np.ndarray]] = ()
                     ) -> Iterator[Any]:
    """The SurfaceNetworkRequest stream of a curve network, made lazily
    (``SurfaceRequestWriter``, ``proto/wire/surface_wire.cc``): its
    ``network`` slices exactly as :func:`fill_requests` slices a mesh, the
    polylines as the faces (``face_sizes`` their point counts), the
    optional per-vertex normals as the channel ``("normal", False, (V, 3)
    rows)``; id and ``options`` (a SurfaceOptions message) with the first
    slice."""
    first = pb.SurfaceNetworkRequest(id=request_id)
    first.options.CopyFrom(options)
    return _sliced(first, pb.SurfaceNetworkRequest, "network", vertices,
                   polylines, max_bytes, channels)


def _sliced(first: Any, make: Callable[[], Any], field: str,
            vertices: np.ndarray, faces: Union[np.ndarray, List[np.ndarray]],
            max_bytes: int,
            channels: Sequence[Tuple[str, bool, np.ndarray]]
            ) -> Iterator[Any]:
    """The messages of :func:`fill_requests`: ``first`` (id and options
    set), then more of ``make()``, each with a MeshChunk slice in its
    field ``field``."""
    vertices_per = max(1, max_bytes // 24)
    indices_per = max(3, max_bytes // 5)
    flat = np.ascontiguousarray(vertices, dtype=np.float64).reshape(-1)
    n = len(flat) // 3
    pending: Optional[Any] = first  # id and options go with the first slice

    def message() -> Tuple[Any, Any]:
        """The next message and its MeshChunk."""
        nonlocal pending
        m, pending = (pending or make()), None
        return m, getattr(m, field)

    for start in range(0, n, vertices_per):
        m, c = message()
        end = min(n, start + vertices_per)
        c.first_vertex = start
        c.vertices.extend(flat[3 * start:3 * end].tolist())
        yield m
    if isinstance(faces, np.ndarray):
        k = faces.shape[1] if faces.ndim == 2 else 3
        per = max(1, indices_per // k)  # whole faces per message
        rows = np.ascontiguousarray(faces, dtype=np.int64).reshape(-1, k)
        for start in range(0, len(rows), per):
            m, c = message()
            block = rows[start:start + per]
            c.first_vertex = n
            c.first_triangle = start
            c.triangles.extend(block.reshape(-1).tolist())
            if k != 3:
                c.face_sizes.extend([k] * len(block))
            yield m
    else:
        all_triangles = all(len(f) == 3 for f in faces)
        m, c, in_message = None, None, 0
        for i, face in enumerate(faces):
            if m is None or in_message + len(face) > indices_per:
                if m is not None:
                    yield m
                (m, c), in_message = message(), 0
                c.first_vertex = n
                c.first_triangle = i
            c.triangles.extend(int(v) for v in face)
            if not all_triangles:
                c.face_sizes.append(len(face))
            in_message += len(face)
        if m is not None:
            yield m
    faces_sent = len(faces)
    for name, per_corner, rows in channels:
        dims = rows.shape[1]
        per = max(1, (max_bytes // 5) // dims)

        def slice_of() -> Tuple[Any, Any]:
            m, c = message()
            c.first_vertex = n
            c.first_triangle = faces_sent
            a = c.attribute
            a.name, a.dims, a.per_corner = name, dims, per_corner
            return m, a

        for start in range(0, max(1, len(rows)), per):
            m, a = slice_of()
            a.first_value = start
            a.values.extend(rows[start:start + per].reshape(-1).tolist())
            yield m
        if per_corner:
            per = max(1, max_bytes // 5)
            for start in range(0, len(rows), per):
                m, a = slice_of()
                a.first_value = len(rows)
                a.first_corner = start
                a.indices.extend(range(start, min(len(rows), start + per)))
                yield m
    if pending is not None:
        yield pending  # an empty mesh: id and options alone


T = TypeVar("T")


def read_length_prefixed(source: Union[bytes, BinaryIO],
                         message_type: Type[T]) -> List[T]:
    """Messages from a recorded stream: each one a 4-byte little-endian
    length, then its serialized bytes (the format of ``tests/golden/``)."""
    data = source if isinstance(source, bytes) else source.read()
    out: List[T] = []
    at = 0
    while at < len(data):
        if at + 4 > len(data):
            raise ValueError(f"truncated length prefix at byte {at}")
        (size,) = struct.unpack_from("<I", data, at)
        at += 4
        if at + size > len(data):
            raise ValueError(f"truncated message at byte {at}")
        out.append(message_type.FromString(data[at:at + size]))  # type: ignore
        at += size
    return out


def write_length_prefixed(stream: BinaryIO, payloads: Iterable[bytes]) -> None:
    """Writes serialized messages in the format :func:`read_length_prefixed`
    reads."""
    for p in payloads:
        stream.write(struct.pack("<I", len(p)))
        stream.write(p)

# SPDX-License-Identifier: AGPL-3.0-or-later
"""The dot.v1 wire format as dotctl speaks it, in Python.

:class:`MeshAssembler` mirrors ``dot::wire::MeshAssembler``
(``proto/wire/wire.cc``) check for check and message for message;
:func:`fill_requests` mirrors ``dot::wire::MakeFillRequests``
(``proto/wire/fill_wire.cc``); :func:`assemble_triangulate` and
:func:`assemble_fill` read a response stream as ``TriangulateRemote``
(``client/remote_call.cc``) and ``FillRemote`` (``client/fill_call.cc``)
do. The client uses them on live streams; tests replay recorded streams
(``tests/golden/``) through them, and the C++ tests replay the same files
through the C++ code, so the two cannot drift apart.
"""
from __future__ import annotations

import struct
from typing import (Any, BinaryIO, Callable, Iterable, Iterator, List,
                    Optional, Sequence, Tuple, Type, TypeVar, Union)

import grpc
import numpy as np

from ._errors import DotError
from ._proto.dot.v1 import triangulation_pb2 as pb
from ._types import (FillProgress, FillReport, FillResult, Progress, Result,
                     Summary)

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


def assemble_fill(
        responses: Iterable[Any],
        on_progress: Optional[Callable[[FillProgress], None]] = None
) -> FillResult:
    """The FillResult of a FillHoles response stream that ended OK.

    Raises :class:`DotError` (``INTERNAL``) when the report is missing or
    the mesh does not add up, with dotctl's messages.
    """
    assembler = MeshAssembler()
    report = None
    assembled: Optional[str] = None
    for message in responses:
        kind = message.WhichOneof("payload")
        if kind == "progress":
            if on_progress is not None:
                on_progress(FillProgress.from_proto(message.progress))
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
    vertices = report.input_vertices + report.added_vertices
    faces = report.input_faces + report.added_faces
    mesh = None
    if assembled is None:
        try:
            mesh = assembler.finish(vertices, faces)
        except AssemblyError as e:
            assembled = str(e)
    if assembled is not None or mesh is None:
        raise DotError(grpc.StatusCode.INTERNAL,
                       f"bad mesh from the server: {assembled}")
    return FillResult(vertices=mesh[0], faces=mesh[1],
                      report=FillReport.from_proto(report))


FaceInput = Union[np.ndarray, Sequence[Sequence[int]]]


def fill_requests(request_id: str, options: Any, vertices: np.ndarray,
                  faces: Union[np.ndarray, List[np.ndarray]],
                  max_bytes: int = REQUEST_BYTES) -> Iterator[Any]:
    """The FillHolesRequest stream of a mesh, made lazily.

    As ``MakeFillRequests``: the first message carries id and options (and
    the first vertices), vertices fill messages of at most ``max_bytes``
    // 24 vertices, faces start in a message of their own and fill messages
    of at most ``max_bytes`` // 5 indices, never splitting a face;
    ``face_sizes`` is sent only when some face is not a triangle.
    ``faces`` is an int array (F, k) or a list of int arrays (polygons).
    """
    vertices_per = max(1, max_bytes // 24)
    indices_per = max(3, max_bytes // 5)
    first = pb.FillHolesRequest(id=request_id)
    first.options.CopyFrom(options)
    flat = np.ascontiguousarray(vertices, dtype=np.float64).reshape(-1)
    n = len(flat) // 3
    message = first
    done = 0
    while done < n:
        if done > 0:
            yield message
            message = pb.FillHolesRequest()
        end = min(n, done + vertices_per)
        message.vertices.extend(flat[3 * done:3 * end].tolist())
        done = end
    yield message
    if isinstance(faces, np.ndarray):
        k = faces.shape[1] if faces.ndim == 2 else 3
        per = indices_per // k  # whole faces per message
        all_triangles = k == 3
        rows = np.ascontiguousarray(faces, dtype=np.int64)
        for start in range(0, len(rows), per):
            message = pb.FillHolesRequest()
            block = rows[start:start + per]
            message.faces.extend(block.reshape(-1).tolist())
            if not all_triangles:
                message.face_sizes.extend([k] * len(block))
            yield message
        return
    all_triangles = all(len(f) == 3 for f in faces)
    message = None
    in_message = indices_per
    for face in faces:
        if in_message + len(face) > indices_per:
            if message is not None:
                yield message
            message = pb.FillHolesRequest()
            in_message = 0
        message.faces.extend(int(v) for v in face)
        if not all_triangles:
            message.face_sizes.append(len(face))
        in_message += len(face)
    if message is not None:
        yield message


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

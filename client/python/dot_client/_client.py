# SPDX-License-Identifier: AGPL-3.0-or-later
"""dot_client.Client: the dot.v1 service from Python, numpy in and out."""
from __future__ import annotations

import json
import sys
import threading
from typing import (TYPE_CHECKING, Any, Callable, Dict, Iterator, List,
                    Optional, Sequence, Union, overload)

import grpc
import numpy as np

from . import _validate as check
from . import wire
from ._errors import (DotError, FillStopped, InvalidInput, NoTriangulation,
                      from_rpc_error)
from ._local import LocalServer
from ._proto.dot.v1 import triangulation_pb2 as pb
from ._proto.dot.v1 import triangulation_pb2_grpc as pb_grpc
from ._proto.grpc.health.v1 import health_pb2, health_pb2_grpc
from ._types import (FillOptions, FillPatches, FillProgress, FillReport,
                     FillResult, Progress, Result, ServerInfo, SurfaceOptions,
                     SurfaceProgress, SurfaceResult, TriangulateOptions,
                     WeightsLike)

if TYPE_CHECKING:  # pragma: no cover
    import meshio

    from ._meshio import FilledMesh

ArrayLike = Any  # anything numpy.asarray takes: arrays, lists of tuples, ...
FaceLike = Union[ArrayLike, Sequence[Sequence[int]]]

# Retry UNAVAILABLE (a replica draining or gone: the call did nothing), as
# dotctl does. The load-balancing policy stays gRPC's default, pick_first:
# one connection to one replica keeps its search-space cache useful for
# interactive re-solves (README: "The cache and replicas").
_SERVICE_CONFIG = json.dumps({
    "methodConfig": [{
        "name": [{"service": "dot.v1.Triangulator"},
                 {"service": "grpc.health.v1.Health"}],
        "retryPolicy": {
            "maxAttempts": 5,
            "initialBackoff": "0.05s",
            "maxBackoff": "1s",
            "backoffMultiplier": 2,
            "retryableStatusCodes": ["UNAVAILABLE"],
        },
    }],
})

_MESSAGE_BYTES = 64 << 20


class _Default:
    def __repr__(self) -> str:
        return "<client default>"


_DEFAULT: Any = _Default()


class CancelToken:
    """Cancels the calls it is passed to, from any thread.

    ``token = CancelToken(); client.fill_holes(v, f, cancel=token)`` in one
    thread, ``token.cancel()`` in another (an Esc key handler): the call
    raises :class:`DotError` with code ``CANCELLED`` and the server stops
    working on it. A token cancelled before a call starts cancels it at
    once.
    """

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._calls: List[Any] = []
        self._cancelled = False

    @property
    def cancelled(self) -> bool:
        return self._cancelled

    def cancel(self) -> None:
        with self._lock:
            self._cancelled = True
            calls = list(self._calls)
        for c in calls:
            c.cancel()

    def _attach(self, call: Any) -> None:
        with self._lock:
            self._calls.append(call)
            cancelled = self._cancelled
        if cancelled:
            call.cancel()

    def _detach(self, call: Any) -> None:
        with self._lock:
            if call in self._calls:
                self._calls.remove(call)


def _read(path: Optional[str], what: str) -> Optional[bytes]:
    if path is None:
        return None
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError as e:
        raise InvalidInput(f"cannot read {what} {path!r}: {e.strerror}") from None


class Client:
    """A connection to a dot-server.

    ``address`` is ``host:port`` (any gRPC target, e.g.
    ``dns:///dot-headless:50051``). TLS is on when any of ``tls_ca`` (PEM
    CA bundle that signed the server's certificate; None: the system's
    roots), ``tls_cert`` and ``tls_key`` (a client certificate and its key,
    for mutual TLS) is given. ``timeout`` is the default deadline of each
    call in seconds (None: no deadline); every method takes its own
    ``timeout`` too. Use as a context manager, or call :meth:`close`::

        with dot_client.Client("localhost:50051") as client:
            result = client.triangulate(points, squared_dihedral=1)

    Every failure raises :class:`DotError` (``code``, ``message``);
    input that cannot be sent raises its subclass :class:`InvalidInput`
    before any call is made.
    """

    def __init__(self, address: str = "localhost:50051", *,
                 tls_ca: Optional[str] = None, tls_cert: Optional[str] = None,
                 tls_key: Optional[str] = None,
                 timeout: Optional[float] = None) -> None:
        if not isinstance(address, str) or not address:
            raise InvalidInput(f"address must be 'host:port'; got {address!r}")
        if (tls_cert is None) != (tls_key is None):
            raise InvalidInput("tls_cert and tls_key go together (mutual TLS)")
        self.address = address
        self.timeout = check.timeout("timeout", timeout)
        options = [("grpc.max_receive_message_length", _MESSAGE_BYTES),
                   ("grpc.max_send_message_length", _MESSAGE_BYTES),
                   ("grpc.enable_retries", 1),
                   ("grpc.service_config", _SERVICE_CONFIG)]
        if tls_ca is None and tls_cert is None:
            self._channel = grpc.insecure_channel(address, options=options)
        else:
            credentials = grpc.ssl_channel_credentials(
                root_certificates=_read(tls_ca, "tls_ca"),
                private_key=_read(tls_key, "tls_key"),
                certificate_chain=_read(tls_cert, "tls_cert"))
            self._channel = grpc.secure_channel(address, credentials,
                                                options=options)
        self._closed = False
        self._stub = pb_grpc.TriangulatorStub(self._channel)
        self._health = health_pb2_grpc.HealthStub(self._channel)
        #: The :class:`LocalServer` this client owns (:meth:`local`), else
        #: None.
        self.server: Optional[LocalServer] = None

    @classmethod
    def local(cls, executable: Optional[str] = None, *,
              timeout: Optional[float] = None, transport: str = "unix",
              threads: int = 0, log_level: str = "warn",
              args: Sequence[str] = (), wait_s: float = 30.0) -> "Client":
        """A client of its own private dot-server: starts a
        :class:`LocalServer` (``executable``, ``transport``, ``threads``,
        ``log_level``, ``args`` and ``wait_s`` are its arguments; by
        default ``$DOT_SERVER_PATH`` or ``dot-server`` on PATH, on a Unix
        socket only this user can reach) and connects to it; :meth:`close`
        (or leaving ``with``) stops it, and it never outlives this
        process, however the process ends::

            with dot_client.Client.local() as client:
                filled = client.fill_holes(vertices, faces)

        ``timeout`` is the client's default deadline, as in the
        constructor. The server is ``client.server`` (its ``address``,
        ``pid``, ``log()``). Raises :class:`DotError` (``UNAVAILABLE``)
        when no server could be started, leaving nothing running.
        """
        server = LocalServer(executable, transport=transport,
                             threads=threads, log_level=log_level, args=args,
                             wait_s=wait_s)
        try:
            client = cls(server.address, timeout=timeout)
        except BaseException:
            server.stop()
            raise
        client.server = server
        return client

    # -- lifetime -----------------------------------------------------------

    def close(self) -> None:
        """Closes the channel; calls in flight are cancelled. Calls made
        afterwards raise DotError (``FAILED_PRECONDITION``). A client made
        by :meth:`local` stops its server too."""
        self._closed = True
        self._channel.close()
        if self.server is not None:
            self.server.stop()

    def _check_open(self) -> None:
        if self._closed:
            raise DotError(grpc.StatusCode.FAILED_PRECONDITION,
                           "this Client is closed")

    def __enter__(self) -> "Client":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __repr__(self) -> str:
        if self.server is not None:
            return f"dot_client.Client.local() at {self.address!r}"
        return f"dot_client.Client({self.address!r})"

    # -- helpers ------------------------------------------------------------

    def _deadline(self, timeout: Any) -> Optional[float]:
        self._check_open()
        if timeout is _DEFAULT:
            return self.timeout
        return check.timeout("timeout", timeout)

    @staticmethod
    def _run(call: Any, cancel: Optional[CancelToken],
             consume: Callable[[Any], Any]) -> Any:
        """consume(call) with RPC errors as DotError; any other way out
        (an error, KeyboardInterrupt) cancels the call first."""
        if cancel is not None:
            cancel._attach(call)
        try:
            return consume(call)
        except grpc.RpcError as e:
            raise from_rpc_error(e) from None
        except BaseException:
            call.cancel()
            raise
        finally:
            if cancel is not None:
                cancel._detach(call)

    def _request(self, request_id: str, points: ArrayLike,
                 normals: Optional[ArrayLike], options: TriangulateOptions,
                 progress_interval_ms: int = 0, what: str = "points"
                 ) -> "tuple[Any, np.ndarray]":
        p = check.points(what, points, min_rows=3)
        r = pb.TriangulateRequest(id=request_id)
        r.polygon.coordinates.extend(p.reshape(-1).tolist())
        if normals is not None:
            name = "normals" if what == "points" else what.replace(
                "polygons", "normals")
            n = check.points(name, normals)
            if n.shape != p.shape:
                raise InvalidInput(
                    f"{name} has {len(n)} rows; expected one per vertex "
                    f"({len(p)})")
            r.polygon.normals.extend(n.reshape(-1).tolist())
        options.to_proto(r)
        r.options.progress_interval_ms = progress_interval_ms
        # The server leaves the input vertices out; they are put back from
        # `p` on arrival (as dotctl does).
        r.options.omit_input_vertices = True
        return r, p

    # -- Triangulate --------------------------------------------------------

    def triangulate(self, points: ArrayLike,
                    normals: Optional[ArrayLike] = None, *,
                    options: Optional[TriangulateOptions] = None,
                    weights: Optional[WeightsLike] = None,
                    area: Optional[float] = None,
                    perimeter: Optional[float] = None,
                    normal_deviation: Optional[float] = None,
                    shape: Optional[float] = None,
                    dihedral: Optional[float] = None,
                    squared_dihedral: Optional[float] = None,
                    search_space: Optional[str] = None,
                    protect_edges: Optional[bool] = None,
                    delaunay_backend: Optional[str] = None,
                    validate_output: Optional[bool] = None,
                    time_budget_ms: Optional[int] = None,
                    memory_budget_bytes: Optional[int] = None,
                    no_cache: Optional[bool] = None,
                    keep_loop_directions: Optional[bool] = None,
                    loop_sizes: Optional[Sequence[int]] = None,
                    forbidden_edges: Optional[ArrayLike] = None,
                    progress: Optional[Callable[[Progress], None]] = None,
                    progress_interval_ms: int = 100,
                    raise_no_triangulation: bool = True,
                    request_id: str = "",
                    timeout: Optional[float] = _DEFAULT,
                    cancel: Optional[CancelToken] = None) -> Result:
        """The optimal triangulation of one closed polygon.

        ``points``: (n, 3) vertices of the loop 0, 1, ..., n-1, 0 (n >= 3).
        ``normals``: optional (n, 3) boundary normals for the
        ``normal_deviation`` metric, pointing to the side around which the
        polygon runs counter-clockwise.

        ``options``: a :class:`TriangulateOptions` (None: its defaults).
        The keyword arguments below, when given (not None), replace its
        fields: ``weights`` (a :class:`Weights`, a :data:`WEIGHT_PRESETS`
        name such as ``"smooth"``, or a dict), then each metric weight
        alone (the objective is their weighted sum; all zero means area;
        a negative weight maximizes): ``area``, ``perimeter``,
        ``normal_deviation``, ``shape``, ``dihedral``,
        ``squared_dihedral``.

        ``search_space``: ``"auto"`` (Delaunay triangles, all triangles for
        small polygons without a Delaunay triangulation), ``"delaunay"``
        (never self-intersects), ``"all"`` or ``"delaunay_first"`` (every
        triangle, Delaunay ones first, for large polygons with no Delaunay
        triangulation; may self-intersect). ``protect_edges`` splits
        polygon edges that are not Delaunay (the inserted vertices follow
        the input's in ``result.vertices``; ``summary.loop`` is the polygon
        with them in place). ``delaunay_backend``: ``"default"``,
        ``"cgal"`` or ``"tetgen"``. ``validate_output`` counts
        self-intersecting pairs. ``time_budget_ms`` and
        ``memory_budget_bytes`` lower the server's limits (0: the
        server's). ``no_cache`` skips the server's search-space cache.

        ``loop_sizes``: several loops bounding one surface (see
        :meth:`triangulate_loops`, which sets it): the row count of each
        loop in ``points``, in order. ``keep_loop_directions`` keeps each
        loop's direction (by default the solver may reverse loops after
        the first). ``forbidden_edges``: (k, 2) vertex index pairs no
        triangle may use as an edge (chords a surrounding mesh already
        has, or the diagonals of its quads).

        ``progress`` is called with a :class:`Progress` at most every
        ``progress_interval_ms``; an exception it raises (also
        KeyboardInterrupt) cancels the call and propagates.

        Returns a :class:`Result`. When no triangulation exists, raises
        :class:`NoTriangulation` (its ``summary`` says why), or with
        ``raise_no_triangulation=False`` returns a Result whose
        ``summary.status`` is ``"no_triangulation"`` and whose arrays are
        empty. Other failures raise :class:`DotError`.
        """
        o = TriangulateOptions.merged(
            options, weights=weights, area=area, perimeter=perimeter,
            normal_deviation=normal_deviation, shape=shape,
            dihedral=dihedral, squared_dihedral=squared_dihedral,
            search_space=search_space, protect_edges=protect_edges,
            delaunay_backend=delaunay_backend,
            validate_output=validate_output, time_budget_ms=time_budget_ms,
            memory_budget_bytes=memory_budget_bytes, no_cache=no_cache,
            keep_loop_directions=keep_loop_directions)
        interval = (check.integer("progress_interval_ms",
                                  progress_interval_ms, minimum=1)
                    if progress is not None else 0)
        request, p = self._request(str(request_id), points, normals, o,
                                   interval)
        if loop_sizes is not None:
            sizes = [check.integer("loop_sizes", s, minimum=3)
                     for s in loop_sizes]
            if sum(sizes) != len(p):
                raise InvalidInput(
                    f"loop_sizes sum to {sum(sizes)}, but points has "
                    f"{len(p)} rows")
            if len(sizes) > 1:
                request.polygon.loop_sizes.extend(sizes)
        if forbidden_edges is not None:
            pairs = np.asarray(forbidden_edges)
            if pairs.size and (pairs.ndim != 2 or pairs.shape[1] != 2):
                raise InvalidInput("forbidden_edges must be (k, 2) vertex "
                                   "index pairs")
            for i, (a, b) in enumerate(pairs.reshape(-1, 2).tolist()):
                for v in (a, b):
                    check.integer(f"forbidden_edges[{i}]", v, minimum=0,
                                  maximum=len(p) - 1)
                request.polygon.forbidden_edges.extend([int(a), int(b)])
        deadline = self._deadline(timeout)
        call = self._stub.Triangulate(request, timeout=deadline)
        result: Result = self._run(
            call, cancel,
            lambda c: wire.assemble_triangulate(c, p, on_progress=progress))
        if (raise_no_triangulation and result.summary is not None
                and result.summary.status != "ok"):
            raise NoTriangulation(result.summary)
        return result

    def triangulate_loops(self, loops: Sequence[ArrayLike],
                          normals: Optional[Sequence[ArrayLike]] = None,
                          **kwargs: Any) -> Result:
        """One surface joining several closed loops: the minimal-cost
        surface of genus 0 whose boundary is exactly these loops (an
        island inside a hole, a tube between two rims, a branch between
        three). Two loops are solved exactly; three or more are joined by
        bridges first (``result.summary.bridges``) and the surface is the
        optimum for them, an approximation.

        ``loops``: a sequence of (n_i, 3) arrays, each loop's vertices in
        order (n_i >= 3). ``normals``: optional, one (n_i, 3) array per
        loop. Every keyword argument of :meth:`triangulate` applies
        (``keep_loop_directions`` among them).

        Each loop runs along the surface in its given direction unless the
        solver reversed it: ``result.summary.reversed_loops`` names those,
        and ``result.summary.loop`` / ``loop_sizes`` list every loop as the
        surface runs along it (vertex ids into ``result.vertices``).
        """
        if isinstance(loops, np.ndarray) or not isinstance(
                loops, (list, tuple)):
            raise InvalidInput("loops must be a list of (n, 3) arrays, one "
                               "per loop")
        if len(loops) < 1:
            raise InvalidInput("loops is empty; give at least one loop")
        arrays = [check.points(f"loops[{i}]", loop, min_rows=3)
                  for i, loop in enumerate(loops)]
        joined_normals = None
        if normals is not None:
            if len(normals) != len(arrays):
                raise InvalidInput(
                    f"normals has {len(normals)} arrays for {len(arrays)} "
                    "loops; give one per loop")
            arrays_n = [check.points(f"normals[{i}]", n)
                        for i, n in enumerate(normals)]
            for i, (n, a) in enumerate(zip(arrays_n, arrays)):
                if len(n) != len(a):
                    raise InvalidInput(
                        f"normals[{i}] has {len(n)} rows; expected one per "
                        f"vertex of loops[{i}] ({len(a)})")
            joined_normals = np.concatenate(arrays_n)
        if "loop_sizes" in kwargs:
            raise TypeError("triangulate_loops sets loop_sizes itself")
        return self.triangulate(np.concatenate(arrays), joined_normals,
                                loop_sizes=[len(a) for a in arrays],
                                **kwargs)

    def triangulate_many(self, polygons: Sequence[ArrayLike],
                         normals: Optional[Sequence[Optional[ArrayLike]]] = None,
                         *, options: Optional[TriangulateOptions] = None,
                         weights: Optional[WeightsLike] = None,
                         area: Optional[float] = None,
                         perimeter: Optional[float] = None,
                         normal_deviation: Optional[float] = None,
                         shape: Optional[float] = None,
                         dihedral: Optional[float] = None,
                         squared_dihedral: Optional[float] = None,
                         search_space: Optional[str] = None,
                         protect_edges: Optional[bool] = None,
                         delaunay_backend: Optional[str] = None,
                         validate_output: Optional[bool] = None,
                         time_budget_ms: Optional[int] = None,
                         memory_budget_bytes: Optional[int] = None,
                         no_cache: Optional[bool] = None,
                         progress: Optional[Callable[[int, int, Result],
                                                     None]] = None,
                         timeout: Optional[float] = _DEFAULT,
                         cancel: Optional[CancelToken] = None) -> List[Result]:
        """Many polygons over one TriangulateBatch stream.

        Takes the options of :meth:`triangulate` (``options`` and the
        keyword arguments that replace its fields), applied to every
        polygon; ``normals`` is None or one entry (an (n, 3) array or
        None) per polygon. The server works on them concurrently; results
        come back in input order, one :class:`Result` per polygon. A
        polygon that fails alone (bad input the server refused, no
        triangulation) does not fail the call: its Result has ``ok`` False
        and ``error`` set to a :class:`DotError` (a
        :class:`NoTriangulation` for the latter). ``progress(done, total,
        result)`` is called as each result arrives (in arrival order).
        ``timeout`` bounds the whole stream. A failure of the stream itself
        raises :class:`DotError`.
        """
        if isinstance(polygons, np.ndarray) and polygons.ndim == 2:
            raise InvalidInput("polygons must be a list of (n, 3) arrays; "
                               "for one polygon call triangulate()")
        if not isinstance(polygons, (Sequence, np.ndarray)):
            raise InvalidInput("polygons must be a list of (n, 3) arrays")
        if normals is not None and len(normals) != len(polygons):
            raise InvalidInput(
                f"normals has {len(normals)} entries; expected one (or None) "
                f"per polygon ({len(polygons)})")
        o = TriangulateOptions.merged(
            options, weights=weights, area=area, perimeter=perimeter,
            normal_deviation=normal_deviation, shape=shape,
            dihedral=dihedral, squared_dihedral=squared_dihedral,
            search_space=search_space, protect_edges=protect_edges,
            delaunay_backend=delaunay_backend,
            validate_output=validate_output, time_budget_ms=time_budget_ms,
            memory_budget_bytes=memory_budget_bytes, no_cache=no_cache)
        requests = []
        inputs = []
        for i, polygon in enumerate(polygons):
            r, p = self._request(
                str(i), polygon, None if normals is None else normals[i],
                o, what=f"polygons[{i}]")
            requests.append(r)
            inputs.append(p)
        total = len(requests)
        if total == 0:
            return []
        deadline = self._deadline(timeout)
        call = self._stub.TriangulateBatch(iter(requests), timeout=deadline)

        def consume(responses: Iterator[Any]) -> List[Result]:
            assemblers: Dict[int, wire.MeshAssembler] = {}
            failed: Dict[int, str] = {}
            results: List[Optional[Result]] = [None] * total
            done = 0
            for message in responses:
                try:
                    i = int(message.id)
                except ValueError:
                    continue
                if not 0 <= i < total or results[i] is not None:
                    continue
                kind = message.WhichOneof("payload")
                if kind == "mesh":
                    if i not in failed:
                        try:
                            assemblers.setdefault(
                                i, wire.MeshAssembler()).add(message.mesh)
                        except wire.AssemblyError as e:
                            failed[i] = str(e)
                    continue
                empty = Result(vertices=np.zeros((0, 3)),
                               triangles=np.zeros((0, 3), np.int32),
                               id=message.id)
                if kind == "error":
                    code = _status_code(message.error.code)
                    empty.error = DotError(code, message.error.message)
                    result = empty
                elif kind == "summary":
                    try:
                        result = wire._finish_triangulate(
                            message.id, message.summary,
                            assemblers.pop(i, wire.MeshAssembler()),
                            failed.pop(i, None), inputs[i])
                    except DotError as e:
                        empty.error = e
                        result = empty
                    if result.error is None and result.summary is not None \
                            and result.summary.status != "ok":
                        result.error = NoTriangulation(result.summary, str(i))
                else:
                    continue  # progress
                results[i] = result
                done += 1
                if progress is not None:
                    progress(done, total, result)
            for i, r in enumerate(results):
                if r is None:
                    results[i] = Result(
                        vertices=np.zeros((0, 3)),
                        triangles=np.zeros((0, 3), np.int32), id=str(i),
                        error=DotError(grpc.StatusCode.DATA_LOSS,
                                       "the stream ended without an answer "
                                       "for this polygon"))
            return results  # type: ignore[return-value]

        return self._run(call, cancel, consume)

    # -- FillHoles ----------------------------------------------------------

    @overload
    def fill_holes(self, vertices: "meshio.Mesh", faces: None = None,
                   **kwargs: Any) -> "FilledMesh": ...

    @overload
    def fill_holes(self, vertices: ArrayLike, faces: FaceLike,
                   **kwargs: Any) -> FillResult: ...

    def fill_holes(self, vertices: Any, faces: Optional[FaceLike] = None, *,
                   options: Optional[FillOptions] = None,
                   stage: Optional[str] = None,
                   max_hole_edges: Optional[int] = None,
                   max_hole_diameter: Optional[float] = None,
                   skip_longest: Optional[bool] = None,
                   holes: Optional[Sequence[int]] = None,
                   loops_through: Optional[Sequence[int]] = None,
                   islands: Optional[str] = None,
                   join: Optional[Sequence[Sequence[int]]] = None,
                   weights: Optional[WeightsLike] = None,
                   area: Optional[float] = None,
                   perimeter: Optional[float] = None,
                   normal_deviation: Optional[float] = None,
                   shape: Optional[float] = None,
                   dihedral: Optional[float] = None,
                   squared_dihedral: Optional[float] = None,
                   absolute_weights: Optional[bool] = None,
                   density: Optional[float] = None,
                   fairing_continuity: Optional[int] = None,
                   no_repair: Optional[bool] = None,
                   time_budget_ms: Optional[int] = None,
                   memory_budget_bytes: Optional[int] = None,
                   keep_polygons: Optional[bool] = None,
                   allow_input_intersections: Optional[bool] = None,
                   point_data: Optional[Dict[str, ArrayLike]] = None,
                   corner_data: Optional[Dict[str, ArrayLike]] = None,
                   progress: Optional[Callable[[FillProgress], None]] = None,
                   request_id: str = "",
                   timeout: Optional[float] = _DEFAULT,
                   cancel: Optional[CancelToken] = None
                   ) -> Union[FillResult, "FilledMesh"]:
        """Fills the holes of a mesh (the FillHoles stream); the whole
        filled mesh comes back. (:meth:`fill_patches` brings back only
        what is new.)

        ``vertices``: (V, 3) floats; ``faces``: (F, 3) vertex indices, or
        (F, k) polygons, or a list of polygons of any sizes (the server
        triangulates them). The mesh streams to the server lazily in
        MeshChunk slices of about 1 MiB, so any size up to the server's
        limits fits.

        Or ``vertices`` is a :class:`meshio.Mesh` (``meshio.read(path)``),
        given alone (no ``faces``, ``point_data`` or ``corner_data``: they
        come from the mesh): its ``triangle``, ``quad`` and ``polygon``
        cells are the surface, and a :class:`FilledMesh` (a meshio.Mesh
        with the :class:`FillReport` as ``report``) comes back: the mesh
        as it was (the server's repair finds and fills the holes but is
        not applied to it), with the new points and triangles added, point
        data interpolated into the new points and cell data given to the
        new cells as ``dot_client.FilledMesh`` documents (what is not
        carried is named in ``report.notes``).
        ``keep_polygons`` has no effect there (cells are always kept).

        ``options``: a :class:`FillOptions` (None: its defaults, which are
        the service's). The keyword arguments, when given (not None),
        replace its fields. ``stage``: ``"triangulate"`` (the DOT patch),
        ``"refine"`` (+ Liepa refinement) or ``"fair"`` (+ fairing: the
        finished surface). Which holes: ``max_hole_edges`` (0: any),
        ``max_hole_diameter`` (bounding-box diagonal, 0: any),
        ``skip_longest`` (leave the longest border open), ``holes`` (only
        these loop ids, as numbered in the report), ``loops_through``
        (only the loops through these vertex ids; a vertex on no border
        loop is INVALID_ARGUMENT); a hole is filled when it passes every
        rule given, the others are reported ``"skipped"``. Holes with
        islands: ``islands`` ``"auto"`` (the default) joins each island
        floating in a hole to its rim in one patch, ``"off"`` fills every
        loop alone; ``join`` names groups of loop ids each filled by one
        patch (``[(3, 7)]``). Weights: leave
        them unset for the hole-filling default (squared dihedral 1, area
        0.01, per hole scale: the ``"smooth"`` preset), or give
        ``weights`` (a :class:`Weights`, a :data:`WEIGHT_PRESETS` name or
        a dict) and/or single metric weights (``area``, ``perimeter``,
        ``normal_deviation``, ``shape``, ``dihedral``,
        ``squared_dihedral``: the others count 0); ``absolute_weights``
        keeps area and perimeter in the mesh's units. ``density``
        (refinement, 0: sqrt(2)), ``fairing_continuity`` (0, 1 or 2;
        None: 1), ``no_repair`` (use the mesh exactly as sent: then the
        output's first V vertices and, except faces listed in a hole's
        ``split_faces``, its first faces are the input's),
        ``keep_polygons`` (answer the polygons sent where no patch split
        one, as a list of arrays, instead of triangles),
        ``allow_input_intersections`` (fill a hole every patch of which
        meets the mesh when the mesh already intersects itself near it;
        its report counts both).

        Attributes (normals, colours, UVs, any float data): ``point_data``
        {name: (V, d) array}, a row per vertex, and ``corner_data`` {name:
        (C, d) array}, a row per face corner (faces in order, corners in
        order: what carries UV seams); 1 to 16 floats a row, at most 16
        channels. They come back in the result's ``point_data`` and
        ``corner_data``, carried through the repair and interpolated into
        every new vertex (harmonic from the hole's rim, seams continued;
        a channel named ``"normal"`` gets the patch's own normals; every
        other value blends with positive weights, so it stays within the
        range of the values it comes from: colours on a 0..255 scale stay
        on it).

        ``progress(FillProgress)`` is called as the server's phases start
        (repair, loops, holes, merge) and as holes are done, with an
        estimate of the time left; an exception it raises cancels the call
        and propagates.

        Returns a :class:`FillResult` (vertices, faces, report), or a
        :class:`FilledMesh` for a meshio.Mesh; holes that stay open are
        reported in ``report.holes``, not raised. A fill that stops early
        (``time_budget_ms`` or the server's limit passes, the server
        drains) raises :class:`FillStopped`, whose ``result`` holds every
        hole finished before the stop (a FilledMesh for a meshio.Mesh).
        """
        o = FillOptions.merged(
            options, stage=stage, max_hole_edges=max_hole_edges,
            max_hole_diameter=max_hole_diameter, skip_longest=skip_longest,
            holes=holes, loops_through=loops_through, islands=islands,
            join=join, weights=weights,
            area=area, perimeter=perimeter,
            normal_deviation=normal_deviation, shape=shape,
            dihedral=dihedral, squared_dihedral=squared_dihedral,
            absolute_weights=absolute_weights, density=density,
            fairing_continuity=fairing_continuity, no_repair=no_repair,
            time_budget_ms=time_budget_ms,
            memory_budget_bytes=memory_budget_bytes,
            keep_polygons=keep_polygons,
            allow_input_intersections=allow_input_intersections)
        if _is_meshio(vertices):
            if faces is not None or point_data is not None or \
                    corner_data is not None:
                raise InvalidInput(
                    "give a meshio.Mesh alone: its cells are the faces and "
                    "its point_data the attributes (faces, point_data and "
                    "corner_data are for arrays)")
            return self._fill_meshio(vertices, o, progress, request_id,
                                     timeout, cancel)
        if faces is None:
            raise InvalidInput("faces is missing: give (vertices, faces) "
                               "arrays, or a meshio.Mesh alone")
        result: FillResult = self._fill(vertices, faces, o, "mesh", progress,
                                        request_id, timeout, cancel,
                                        point_data=point_data,
                                        corner_data=corner_data)
        return result

    def _fill_meshio(self, mesh: Any, options: FillOptions,
                     progress: Optional[Callable[[FillProgress], None]],
                     request_id: str, timeout: Any,
                     cancel: Optional[CancelToken]) -> "FilledMesh":
        """fill_holes of a meshio.Mesh: its patches, added to it."""
        from . import _meshio

        request = _meshio.mesh_request(mesh)
        try:
            patches: FillPatches = self._fill(
                request.vertices, request.faces, options, "patches",
                progress, request_id, timeout, cancel,
                point_data=request.point_data)
        except FillStopped as stop:
            if not isinstance(stop.result, FillPatches):
                raise
            partial = _meshio.filled_mesh(mesh, request, stop.result)
            raise FillStopped(stop.code, stop.message, partial) from None
        return _meshio.filled_mesh(mesh, request, patches)

    def fill_patches(self, vertices: ArrayLike, faces: FaceLike, *,
                     options: Optional[FillOptions] = None,
                     point_data: Optional[Dict[str, ArrayLike]] = None,
                     corner_data: Optional[Dict[str, ArrayLike]] = None,
                     progress: Optional[Callable[[FillProgress], None]] = None,
                     request_id: str = "",
                     timeout: Optional[float] = _DEFAULT,
                     cancel: Optional[CancelToken] = None,
                     **changes: Any) -> FillPatches:
        """Fills the holes of a mesh and brings back only what is new: one
        :class:`HolePatch` per filled hole, in the ids of the mesh as sent
        (FillHoles with ``FILL_ANSWER_PATCHES``), for a caller that keeps
        its mesh and adds them (:meth:`FillPatches.apply`).

        Takes the arguments of :meth:`fill_holes`: ``options`` (a
        :class:`FillOptions`) and, as keyword arguments, any of its fields
        or metric weights, which replace the options' (``stage="refine",
        loops_through=[17]``), and ``point_data`` / ``corner_data`` as
        :meth:`fill_holes` does: each patch then has every channel's values
        at the corners of its faces (``HolePatch.corner_data``) and of its
        replacement triangles. Returns a :class:`FillPatches` (patches,
        report).
        """
        o = FillOptions.merged(options, **changes)
        patches: FillPatches = self._fill(vertices, faces, o, "patches",
                                          progress, request_id, timeout,
                                          cancel, point_data=point_data,
                                          corner_data=corner_data)
        return patches

    def list_holes(self, vertices: Any, faces: Optional[FaceLike] = None,
                   *, options: Optional[FillOptions] = None,
                   request_id: str = "",
                   timeout: Optional[float] = _DEFAULT,
                   cancel: Optional[CancelToken] = None,
                   **changes: Any) -> FillReport:
        """The holes of a mesh, filled none (FillHoles with ``dry_run``):
        a :class:`FillReport` with one :class:`HoleReport` per loop, its
        size and place, ``"listed"`` when the selection in ``options`` (and
        the keyword ``changes`` to it, as :meth:`fill_patches` takes them)
        would fill it, else ``"skipped"`` with the reason. The mesh is
        ``vertices`` and ``faces`` arrays or a :class:`meshio.Mesh` alone,
        as for :meth:`fill_holes`."""
        o = FillOptions.merged(options, **changes)
        if _is_meshio(vertices):
            if faces is not None:
                raise InvalidInput("give a meshio.Mesh alone: its cells are "
                                   "the faces")
            from . import _meshio

            request = _meshio.mesh_request(vertices, with_data=False)
            vertices, faces = request.vertices, request.faces
        elif faces is None:
            raise InvalidInput("faces is missing: give (vertices, faces) "
                               "arrays, or a meshio.Mesh alone")
        patches: FillPatches = self._fill(vertices, faces, o, "patches", None,
                                          request_id, timeout, cancel,
                                          dry_run=True)
        return patches.report

    def _fill(self, vertices: ArrayLike, faces: FaceLike,
              options: FillOptions, answer: str,
              progress: Optional[Callable[[FillProgress], None]],
              request_id: str, timeout: Any,
              cancel: Optional[CancelToken], dry_run: bool = False,
              point_data: Optional[Dict[str, ArrayLike]] = None,
              corner_data: Optional[Dict[str, ArrayLike]] = None) -> Any:
        v = check.points("vertices", vertices)
        f = check.faces(faces, len(v))
        corners = (f.size if isinstance(f, np.ndarray)
                   else sum(len(face) for face in f))
        channels = check.attributes(point_data, corner_data, len(v), corners)
        for i, vertex in enumerate(options.loops_through):
            if vertex >= len(v):
                raise InvalidInput(
                    f"loops_through[{i}] = {vertex} is not a vertex of the "
                    f"mesh (it has {len(v)})")
        message = options.to_proto(answer, dry_run)
        deadline = self._deadline(timeout)
        requests = wire.fill_requests(str(request_id), message, v, f,
                                      channels=channels)
        call = self._stub.FillHoles(requests, timeout=deadline)
        if answer == "mesh":
            as_sent = bool(channels) or options.keep_polygons
            per_corner = [name for name, corner, _ in channels if corner]
            return self._run(call, cancel, lambda c: wire.assemble_fill(
                c, on_progress=progress, as_sent=as_sent,
                per_corner=per_corner, sent=[name for name, _, _ in channels],
                triangles=not options.keep_polygons))
        return self._run(call, cancel, lambda c: wire.assemble_patches(
            c, on_progress=progress, sent_vertices=len(v)))

    # -- SurfaceNetwork -----------------------------------------------------

    def surface_network(self, vertices: ArrayLike,
                        polylines: FaceLike, *,
                        normals: Optional[ArrayLike] = None,
                        options: Optional[SurfaceOptions] = None,
                        cycles: Optional[Sequence[Sequence[Sequence[int]]]]
                        = None,
                        stage: Optional[str] = None,
                        weights: Optional[WeightsLike] = None,
                        area: Optional[float] = None,
                        perimeter: Optional[float] = None,
                        normal_deviation: Optional[float] = None,
                        shape: Optional[float] = None,
                        dihedral: Optional[float] = None,
                        squared_dihedral: Optional[float] = None,
                        absolute_weights: Optional[bool] = None,
                        density: Optional[float] = None,
                        fairing_continuity: Optional[int] = None,
                        skip_longest: Optional[bool] = None,
                        islands: Optional[str] = None,
                        walls: Optional[bool] = None,
                        weld_distance: Optional[float] = None,
                        time_budget_ms: Optional[int] = None,
                        memory_budget_bytes: Optional[int] = None,
                        progress: Optional[Callable[[SurfaceProgress],
                                                    None]] = None,
                        request_id: str = "",
                        timeout: Optional[float] = _DEFAULT,
                        cancel: Optional[CancelToken] = None
                        ) -> SurfaceResult:
        """One surface through a network of 3D curves (the SurfaceNetwork
        stream): the cycles of curves that bound patches are found (or
        given), each patch is triangulated by DOT, refined, and the whole
        network is faired at once, every curve vertex fixed.

        ``vertices``: (V, 3) floats. ``polylines``: the curves, each a
        sequence of vertex ids (at least 2; a polyline that ends at its
        first vertex is closed), as a list of int sequences of any lengths
        or a (P, k) array ((E, 2): one polyline per edge, as Blender's mesh
        edges). Curves meet where they share a vertex id or exactly the
        same coordinates (the server welds those; with ``weld_distance``
        also a stroke's free end to the nearest point that close); where other than two
        curve pieces meet is a junction. ``normals``: optional (V, 3)
        surface normals at the vertices (sent as the channel
        ``"normal"``), for the ``normal_deviation`` metric.

        ``options``: a :class:`SurfaceOptions` (None: its defaults, which
        are the service's). The keyword arguments, when given (not None),
        replace its fields: ``cycles`` (the patches given, each a list of
        loops of vertex ids: ``[[bottom_rim, top_rim]]`` is a tube),
        ``stage`` (``"triangulate"``: no new vertices; ``"refine"``;
        ``"fair"``, the default), ``weights`` (a :class:`Weights`, a
        :data:`WEIGHT_PRESETS` name or a dict) and single metric weights
        (``area``, ..., ``squared_dihedral``: the others count 0),
        ``absolute_weights``, ``density``, ``fairing_continuity``,
        ``skip_longest``, ``islands`` (a closed curve alone inside a found
        face: ``"inset"``, ``"hole"`` or ``"off"``; see
        :class:`SurfaceOptions`), ``walls`` (also find flat cycles that
        make a third patch on their curves), ``weld_distance`` (weld
        stroke ends to points within it: strokes that nearly meet),
        ``time_budget_ms``, ``memory_budget_bytes``.

        ``progress(SurfaceProgress)`` is called once the cycles are found
        and as patches are triangulated; an exception it raises (also
        KeyboardInterrupt), a ``timeout`` or a ``cancel`` token cancels the
        call on the server.

        Returns a :class:`SurfaceResult`: ``vertices`` (the network's
        first, exactly as sent, then new ones), ``faces`` (int32 (F, 3),
        consistently oriented, every curve edge of a surfaced patch among
        their edges) and the :class:`SurfaceReport` (patches that could not
        be surfaced are reported ``"failed"`` and left out, never raised).
        A network that bounds no patch, crossing or duplicate curves, and
        cycles that are not cycles of the network raise :class:`DotError`
        (``INVALID_ARGUMENT``) naming them.
        """
        o = SurfaceOptions.merged(
            options, cycles=cycles, stage=stage, weights=weights, area=area,
            perimeter=perimeter, normal_deviation=normal_deviation,
            shape=shape, dihedral=dihedral,
            squared_dihedral=squared_dihedral,
            absolute_weights=absolute_weights, density=density,
            fairing_continuity=fairing_continuity,
            skip_longest=skip_longest, islands=islands, walls=walls,
            weld_distance=weld_distance, time_budget_ms=time_budget_ms,
            memory_budget_bytes=memory_budget_bytes)
        v = check.points("vertices", vertices)
        lines = check.polylines(polylines, len(v))
        channels: List[Any] = []
        if normals is not None:
            n = check.points("normals", normals)
            if n.shape != v.shape:
                raise InvalidInput(
                    f"normals has {len(n)} rows; expected one per vertex "
                    f"({len(v)})")
            channels = check.attributes({"normal": n}, None, len(v), 0)
        for p, patch in enumerate(o.cycles):
            for k, loop in enumerate(patch):
                for i, vertex in enumerate(loop):
                    if vertex >= len(v):
                        raise InvalidInput(
                            f"cycles[{p}][{k}][{i}] = {vertex} is not a "
                            f"vertex of the network (it has {len(v)})")
        deadline = self._deadline(timeout)
        requests = wire.surface_requests(str(request_id), o.to_proto(), v,
                                         lines, channels=channels)
        call = self._stub.SurfaceNetwork(requests, timeout=deadline)
        result: SurfaceResult = self._run(
            call, cancel,
            lambda c: wire.assemble_surface(c, v, on_progress=progress))
        return result

    # -- Health and info ----------------------------------------------------

    def health(self, service: str = "", *,
               timeout: Optional[float] = _DEFAULT) -> str:
        """grpc.health.v1 Check: ``"SERVING"``, ``"NOT_SERVING"`` (e.g.
        draining), ``"SERVICE_UNKNOWN"`` or ``"UNKNOWN"``; raises
        :class:`DotError` (``UNAVAILABLE``) when the server cannot be
        reached. ``service`` "" asks about the server as a whole,
        ``"dot.v1.Triangulator"`` about the service."""
        deadline = self._deadline(timeout)
        try:
            r = self._health.Check(
                health_pb2.HealthCheckRequest(service=service),
                timeout=deadline)
        except grpc.RpcError as e:
            raise from_rpc_error(e) from None
        return health_pb2.HealthCheckResponse.ServingStatus.Name(r.status)

    def server_info(self, *, timeout: Optional[float] = _DEFAULT) -> ServerInfo:
        """The server's version, build, backends, limits, license and where
        its source is (GetServerInfo)."""
        deadline = self._deadline(timeout)
        try:
            r = self._stub.GetServerInfo(pb.GetServerInfoRequest(),
                                         timeout=deadline)
        except grpc.RpcError as e:
            raise from_rpc_error(e) from None
        return ServerInfo.from_proto(r)


def _is_meshio(value: Any) -> bool:
    """Whether ``value`` is a meshio.Mesh (without importing meshio: a
    caller holding one has imported it)."""
    meshio = sys.modules.get("meshio")
    return meshio is not None and isinstance(value, meshio.Mesh)


def _status_code(value: int) -> grpc.StatusCode:
    for c in grpc.StatusCode:
        if c.value[0] == value:
            return c
    return grpc.StatusCode.UNKNOWN

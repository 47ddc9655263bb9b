# SPDX-License-Identifier: AGPL-3.0-or-later
"""dot_client: the dot triangulation service from Python.

Optimal, intersection-free triangulation of closed 3D polygons, hole
filling of meshes and surfaces through curve networks, computed by a
``dot-server`` over gRPC; numpy arrays in and out::

    import numpy as np
    import dot_client

    square = np.array([(0, 0, 0), (1, 0, 0), (1, 1, 0.5), (0, 1, 0)])
    with dot_client.Client("localhost:50051") as client:
        result = client.triangulate(square, squared_dihedral=1)
        print(result.triangles, result.summary.total_cost)

        # A curve network (polylines over shared vertices) into a surface:
        # the square's sides and a diagonal bound three cycles: the two
        # triangles, and the square, the longest, left open.
        s = client.surface_network(square, [[0, 1, 2], [2, 3, 0], [0, 2]],
                                   skip_longest=True)
        print(s.faces, s.report.surfaced, [p.status for p in s.report.patches])

Meshes read by meshio (optional: Debian's python3-meshio) go in and come
out whole, and a client can run its own private server::

    with dot_client.Client.local() as client:  # dot-server from PATH
        filled = client.fill_holes(dot_client.read_mesh("scan.ply"))
        filled.write("closed.ply")
        print(filled.report.filled, "holes filled")

Names exported here are the API other tools script against: :class:`Client`
(``triangulate``, ``triangulate_many``, ``fill_holes``, ``fill_patches``,
``list_holes``, ``surface_network``, ``health``, ``server_info``,
``Client.local``), :class:`LocalServer` (a private dot-server that never
outlives this process) and :func:`find_server`, :class:`FilledMesh` (the
meshio.Mesh ``fill_holes`` returns for one) and :func:`read_mesh`
(``meshio.read`` raising :class:`InvalidInput` where meshio 7.0 would exit;
both need meshio), the options (:class:`TriangulateOptions`,
:class:`FillOptions`, :class:`SurfaceOptions`, :class:`Weights` and the presets
:data:`WEIGHT_PRESETS`), the results (:class:`Result`, :class:`FillResult`,
:class:`FillPatches`, :class:`HolePatch`, :class:`SurfaceResult`,
:class:`Summary`, :class:`FillReport`, :class:`SurfaceReport`,
:class:`PatchReport`, ...), the errors (:class:`DotError` and its subclasses
:class:`InvalidInput`, :class:`NoTriangulation`, :class:`FillStopped`, which
carries a stopped fill's partial result) and :class:`CancelToken`. The wire
helpers live in :mod:`dot_client.wire`.
"""
from ._errors import DotError, FillStopped, InvalidInput, NoTriangulation
from ._types import (WEIGHT_PRESETS, CurveUse, FillOptions, FillPatches,
                     FillProgress, FillReport, FillResult, HolePatch,
                     HoleReport, Limits, PatchLoop, PatchReport, Progress,
                     RepairReport, Result, ServerInfo, Stats, Summary,
                     SurfaceOptions, SurfaceProgress, SurfaceReport,
                     SurfaceResult, TriangulateOptions, WeightPreset, Weights)
from ._client import CancelToken, Client
from ._local import LocalServer, find_server

__version__ = "0.1.0"


def __getattr__(name: str) -> object:
    """``FilledMesh`` and ``read_mesh``, imported on first use: they need
    meshio, and dot_client works without it (so they are not in
    ``__all__`` either: ``from dot_client import *`` must not need it)."""
    if name in ("FilledMesh", "read_mesh"):
        try:
            from . import _meshio
        except ImportError as e:
            raise ImportError(f"dot_client.{name} needs meshio (Debian: "
                              f"python3-meshio): {e}") from e
        return getattr(_meshio, name)
    raise AttributeError(f"module 'dot_client' has no attribute {name!r}")


__all__ = [
    "CancelToken", "Client", "CurveUse", "DotError", "FillOptions",
    "FillPatches", "FillProgress", "FillStopped", "FillReport", "FillResult",
    "HolePatch", "HoleReport", "InvalidInput", "Limits", "LocalServer",
    "NoTriangulation", "PatchLoop", "PatchReport", "Progress", "RepairReport",
    "Result", "ServerInfo", "Stats", "Summary", "SurfaceOptions",
    "SurfaceProgress", "SurfaceReport", "SurfaceResult", "TriangulateOptions",
    "WEIGHT_PRESETS", "WeightPreset", "Weights", "find_server",
]

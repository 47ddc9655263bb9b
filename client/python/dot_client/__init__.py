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

Names exported here are the API other tools script against: :class:`Client`
(``triangulate``, ``triangulate_many``, ``fill_holes``, ``fill_patches``,
``list_holes``, ``surface_network``, ``health``, ``server_info``), the
options (:class:`TriangulateOptions`, :class:`FillOptions`,
:class:`SurfaceOptions`, :class:`Weights` and the presets
:data:`WEIGHT_PRESETS`), the results (:class:`Result`, :class:`FillResult`,
:class:`FillPatches`, :class:`HolePatch`, :class:`SurfaceResult`,
:class:`Summary`, :class:`FillReport`, :class:`SurfaceReport`,
:class:`PatchReport`, ...), the errors (:class:`DotError` and its
subclasses :class:`InvalidInput`, :class:`NoTriangulation`,
:class:`FillStopped`, which carries a stopped fill's partial result) and
:class:`CancelToken`. The wire helpers live in :mod:`dot_client.wire`.
"""
from ._errors import DotError, FillStopped, InvalidInput, NoTriangulation
from ._types import (WEIGHT_PRESETS, CurveUse, FillOptions, FillPatches,
                     FillProgress, FillReport, FillResult, HolePatch,
                     HoleReport, Limits, PatchLoop, PatchReport, Progress,
                     RepairReport, Result, ServerInfo, Stats, Summary,
                     SurfaceOptions, SurfaceProgress, SurfaceReport,
                     SurfaceResult, TriangulateOptions, WeightPreset, Weights)
from ._client import CancelToken, Client

__version__ = "0.1.0"

__all__ = [
    "CancelToken", "Client", "CurveUse", "DotError", "FillOptions",
    "FillPatches", "FillProgress", "FillStopped", "FillReport", "FillResult",
    "HolePatch", "HoleReport", "InvalidInput", "Limits", "NoTriangulation",
    "PatchLoop", "PatchReport", "Progress", "RepairReport", "Result",
    "ServerInfo", "Stats", "Summary", "SurfaceOptions", "SurfaceProgress",
    "SurfaceReport", "SurfaceResult", "TriangulateOptions", "WEIGHT_PRESETS",
    "WeightPreset", "Weights",
]

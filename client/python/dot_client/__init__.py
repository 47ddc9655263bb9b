# SPDX-License-Identifier: AGPL-3.0-or-later
"""dot_client: the dot triangulation service from Python.

Optimal, intersection-free triangulation of closed 3D polygons and hole
filling of meshes, computed by a ``dot-server`` over gRPC; numpy arrays in
and out::

    import numpy as np
    import dot_client

    square = np.array([(0, 0, 0), (1, 0, 0), (1, 1, 0.5), (0, 1, 0)])
    with dot_client.Client("localhost:50051") as client:
        result = client.triangulate(square, squared_dihedral=1)
        print(result.triangles, result.summary.total_cost)

Names exported here are the API other tools script against: :class:`Client`
(``triangulate``, ``triangulate_many``, ``fill_holes``, ``fill_patches``,
``health``, ``server_info``), the options (:class:`TriangulateOptions`,
:class:`FillOptions`, :class:`Weights` and the presets
:data:`WEIGHT_PRESETS`), the results (:class:`Result`, :class:`FillResult`,
:class:`FillPatches`, :class:`HolePatch`, :class:`Summary`,
:class:`FillReport`, ...), the errors (:class:`DotError` and its
subclasses :class:`InvalidInput`, :class:`NoTriangulation`,
:class:`FillStopped`, which carries a stopped fill's partial result) and
:class:`CancelToken`. The wire helpers live in :mod:`dot_client.wire`.
"""
from ._errors import DotError, FillStopped, InvalidInput, NoTriangulation
from ._types import (WEIGHT_PRESETS, FillOptions, FillPatches, FillProgress,
                     FillReport, FillResult, HolePatch, HoleReport, Limits,
                     Progress, RepairReport, Result, ServerInfo, Stats,
                     Summary, TriangulateOptions, WeightPreset, Weights)
from ._client import CancelToken, Client

__version__ = "0.1.0"

__all__ = [
    "CancelToken", "Client", "DotError", "FillOptions", "FillPatches",
    "FillProgress", "FillStopped", "FillReport", "FillResult", "HolePatch", "HoleReport",
    "InvalidInput", "Limits", "NoTriangulation", "Progress", "RepairReport",
    "Result", "ServerInfo", "Stats", "Summary", "TriangulateOptions",
    "WEIGHT_PRESETS", "WeightPreset", "Weights",
]

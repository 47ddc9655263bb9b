# SPDX-License-Identifier: AGPL-3.0-or-later
"""The one exception family of dot_client."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, Optional

import grpc

if TYPE_CHECKING:  # pragma: no cover
    from ._types import Summary


class DotError(Exception):
    """A call failed: the gRPC status code and the server's message.

    ``code`` is a :class:`grpc.StatusCode` (``INVALID_ARGUMENT``,
    ``RESOURCE_EXHAUSTED``, ``DEADLINE_EXCEEDED``, ``CANCELLED``,
    ``UNAVAILABLE``, ``INTERNAL``, ``DATA_LOSS``, ...); ``message`` is the
    text the server (or this client) gave. ``str(error)`` is
    ``"CODE: message"``.
    """

    def __init__(self, code: grpc.StatusCode, message: str) -> None:
        super().__init__(f"{code.name}: {message}")
        self.code: grpc.StatusCode = code
        self.message: str = message

    def __reduce__(self) -> Any:
        return (DotError, (self.code, self.message))


class InvalidInput(DotError, ValueError):
    """The input was rejected by this client before any call was made.

    ``code`` is ``INVALID_ARGUMENT``, as the server would have answered.
    """

    def __init__(self, message: str) -> None:
        super().__init__(grpc.StatusCode.INVALID_ARGUMENT, message)


class NoTriangulation(DotError):
    """The polygon has no triangulation in the search space.

    Not an RPC failure (``code`` is ``OK``): the server answered with a
    Summary whose status is ``no_triangulation``; ``str(error)`` is
    ``"no triangulation: reason"``. ``summary`` carries the
    reason (``summary.message``) and the offending polygon edges
    (``summary.non_delaunay_edges``).
    """

    def __init__(self, summary: "Summary", polygon_id: Optional[str] = None) -> None:
        text = summary.message or "no triangulation exists"
        if polygon_id is not None:
            text = f"polygon {polygon_id}: {text}"
        super().__init__(grpc.StatusCode.OK, text)
        self.args = (f"no triangulation: {text}",)
        self.summary = summary


class FillStopped(DotError):
    """A fill stopped early (its time budget or the server's limit passed,
    the server drained) but kept its work: ``result`` is the whole answer,
    a :class:`FillResult` or :class:`FillPatches` holding every hole
    finished before the stop, in a valid mesh; the others are reported
    ``"stopped"`` (``result.report.stopped`` of them). ``code`` and
    ``message`` say why it stopped (``DEADLINE_EXCEEDED``,
    ``UNAVAILABLE``, ...), as for any :class:`DotError`. Catch it to keep
    the partial result::

        try:
            result = client.fill_holes(v, f, time_budget_ms=10_000)
        except dot_client.FillStopped as stop:
            result = stop.result  # the holes filled in 10 s
    """

    def __init__(self, code: grpc.StatusCode, message: str,
                 result: Any) -> None:
        super().__init__(code, message)
        self.result = result

    def __reduce__(self) -> Any:
        return (FillStopped, (self.code, self.message, self.result))


def from_rpc_error(error: grpc.RpcError) -> DotError:
    """The DotError of a failed gRPC call."""
    code = error.code() if hasattr(error, "code") else None
    details = error.details() if hasattr(error, "details") else None
    if not isinstance(code, grpc.StatusCode):
        code = grpc.StatusCode.UNKNOWN
    return DotError(code, details or str(error))

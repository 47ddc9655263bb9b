# SPDX-License-Identifier: AGPL-3.0-or-later
"""Input checks made before any call, each naming what is wrong."""
from __future__ import annotations

import math
import numbers
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from ._errors import InvalidInput

UINT32_MAX = 2**32 - 1
UINT64_MAX = 2**64 - 1


def points(name: str, value: Any, min_rows: int = 0) -> np.ndarray:
    """A finite float64 array of shape (n, 3) with n >= min_rows."""
    if value is None:
        raise InvalidInput(f"{name} is missing")
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise InvalidInput(f"{name} must be numbers of shape (n, 3): {e}") from None
    if a.ndim != 2 or a.shape[1] != 3:
        raise InvalidInput(
            f"{name} must have shape (n, 3) (one x, y, z row per vertex); "
            f"got shape {a.shape}")
    if len(a) < min_rows:
        raise InvalidInput(
            f"{name} has {len(a)} vertices; at least {min_rows} are needed")
    finite = np.isfinite(a).all(axis=1)
    if not finite.all():
        i = int(np.argmin(finite))
        raise InvalidInput(
            f"{name}[{i}] = ({a[i, 0]}, {a[i, 1]}, {a[i, 2]}) is not finite")
    return np.ascontiguousarray(a)


def number(name: str, value: Any, minimum: Optional[float] = None) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InvalidInput(f"{name} must be a number; got {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise InvalidInput(f"{name} must be finite; got {v}")
    if minimum is not None and v < minimum:
        raise InvalidInput(f"{name} must be >= {minimum}; got {v}")
    return v


def integer(name: str, value: Any, minimum: int = 0,
            maximum: int = UINT32_MAX) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise InvalidInput(f"{name} must be an integer; got {value!r}")
    v = int(value)
    if v < minimum or v > maximum:
        raise InvalidInput(
            f"{name} must be between {minimum} and {maximum}; got {v}")
    return v


def flag(name: str, value: Any) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise InvalidInput(f"{name} must be True or False; got {value!r}")
    return bool(value)


def choice(name: str, value: Any, choices: Sequence[str]) -> str:
    if not isinstance(value, str) or value.lower() not in choices:
        raise InvalidInput(
            f"{name} must be one of {', '.join(choices)}; got {value!r}")
    return value.lower()


def timeout(name: str, value: Any) -> Optional[float]:
    if value is None:
        return None
    v = number(name, value)
    if v <= 0:
        raise InvalidInput(f"{name} must be > 0 seconds (or None); got {v}")
    return v


# The words of index_lists' errors, for mesh faces and for the polylines
# of a curve network.
_FACES = {"name": "faces", "item": "face", "least": 3, "unit": "corners",
          "shape": "(F, 3) (or (F, k), k >= 3)",
          "whole": "an (F, 3) array or a list of polygons",
          "empty": "the mesh has no faces"}
_POLYLINES = {"name": "polylines", "item": "polyline", "least": 2,
              "unit": "points",
              "shape": "(P, k), k >= 2 (or be a list of polylines)",
              "whole": "a (P, k) array or a list of polylines",
              "empty": "the network has no polylines"}


def faces(value: Any, vertex_count: int) -> Union[np.ndarray, List[np.ndarray]]:
    """Faces as an int64 array (F, k), k >= 3, or a list of int64 arrays
    (polygons of mixed sizes), every index in [0, vertex_count)."""
    return _index_lists(value, vertex_count, _FACES)


def polylines(value: Any,
              vertex_count: int) -> Union[np.ndarray, List[np.ndarray]]:
    """The polylines of a curve network as :func:`faces` checks faces: an
    int64 array (P, k), k >= 2 (edges: (E, 2)), or a list of int64 arrays
    of any lengths >= 2, every index in [0, vertex_count)."""
    return _index_lists(value, vertex_count, _POLYLINES)


def _index_lists(value: Any, vertex_count: int,
                 w: Dict[str, Any]) -> Union[np.ndarray, List[np.ndarray]]:
    name, item, least, unit = w["name"], w["item"], w["least"], w["unit"]
    if value is None:
        raise InvalidInput(f"{name} is missing")
    if isinstance(value, np.ndarray) or (
            isinstance(value, Sequence) and value and
            len({len(f) if isinstance(f, (Sequence, np.ndarray)) else -1
                 for f in value}) == 1):
        a = np.asarray(value)
        if a.dtype == object:
            raise InvalidInput(f"{name} must be integer vertex indices")
        if a.size and not np.issubdtype(a.dtype, np.integer):
            if np.issubdtype(a.dtype, np.floating) and np.all(np.mod(a, 1) == 0):
                a = a.astype(np.int64)
            else:
                raise InvalidInput(
                    f"{name} must be integer vertex indices; got dtype "
                    f"{a.dtype}")
        if a.ndim != 2 or a.shape[1] < least:
            raise InvalidInput(
                f"{name} must have shape {w['shape']}; got shape {a.shape}")
        if len(a) == 0:
            raise InvalidInput(w["empty"])
        a = a.astype(np.int64)
        bad = (a < 0) | (a >= vertex_count)
        if bad.any():
            f = int(np.argmax(bad.any(axis=1)))
            v = int(a[f][bad[f]][0])
            raise InvalidInput(
                f"{item} {f} has vertex index {v}, but there are only "
                f"{vertex_count} vertices")
        return a
    if not isinstance(value, Sequence):
        raise InvalidInput(
            f"{name} must be {w['whole']}; got {type(value).__name__}")
    if len(value) == 0:
        raise InvalidInput(w["empty"])
    out: List[np.ndarray] = []
    for i, f in enumerate(value):
        try:
            a = np.asarray(f)
        except (TypeError, ValueError):
            a = np.asarray([None])
        if a.ndim != 1 or not np.issubdtype(a.dtype, np.integer):
            raise InvalidInput(f"{item} {i} must be a list of vertex indices")
        if len(a) < least:
            raise InvalidInput(
                f"{item} {i} has {len(a)} {unit}; a {item} needs at least "
                f"{least}")
        bad = (a < 0) | (a >= vertex_count)
        if bad.any():
            raise InvalidInput(
                f"{item} {i} has vertex index {int(a[bad][0])}, but there are "
                f"only {vertex_count} vertices")
        out.append(a.astype(np.int64))
    return out


def attributes(point_data: Any, corner_data: Any, vertex_count: int,
               corner_count: int) -> List[Tuple[str, bool, np.ndarray]]:
    """Attribute channels as (name, per_corner, float32 (n, d) values):
    ``point_data`` a dict of arrays with a row per vertex, ``corner_data``
    one with a row per face corner (faces in order); 1 to 16 floats a row,
    finite, at most 16 channels, names unique, 1 to 64 bytes."""
    out: List[Tuple[str, bool, np.ndarray]] = []
    for per_corner, data, rows, what in (
            (False, point_data, vertex_count, "vertex"),
            (True, corner_data, corner_count, "face corner")):
        if data is None:
            continue
        if not isinstance(data, dict):
            raise InvalidInput(
                f"{'corner' if per_corner else 'point'}_data must be a dict "
                f"of arrays; got {type(data).__name__}")
        for name, value in data.items():
            if not isinstance(name, str) or not 1 <= len(name.encode()) <= 64:
                raise InvalidInput(
                    f"attribute name {name!r} must be a string of 1 to 64 "
                    f"bytes")
            if any(name == n for n, _, _ in out):
                raise InvalidInput(f"attribute {name!r} is given twice")
            raw = np.asarray(value)
            if raw.dtype.kind not in "biuf":
                raise InvalidInput(f"attribute {name!r} must be real numbers; "
                                   f"got dtype {raw.dtype}")
            with np.errstate(over="ignore", invalid="ignore"):
                a = raw.astype(np.float32)
            if a.ndim == 1:
                a = a.reshape(-1, 1)
            if a.ndim != 2 or not 1 <= a.shape[1] <= 16 or len(a) != rows:
                raise InvalidInput(
                    f"attribute {name!r} must have shape ({rows}, d), "
                    f"1 <= d <= 16 (a row per {what}); got "
                    f"shape {a.shape}")
            finite = np.isfinite(a).all(axis=1)
            if not finite.all():
                raise InvalidInput(f"attribute {name!r} row "
                                   f"{int(np.argmin(finite))} is not finite "
                                   f"in single precision (float32, as sent)")
            out.append((name, per_corner, np.ascontiguousarray(a)))
    if len(out) > 16:
        raise InvalidInput(f"{len(out)} attribute channels; at most 16")
    return out

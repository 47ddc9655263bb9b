# SPDX-License-Identifier: AGPL-3.0-or-later
"""Polygons and meshes the tests send, and mesh checks."""
from typing import List

import numpy as np

def monkey_saddle(n: int) -> np.ndarray:
    """The boundary of a monkey saddle over the unit circle (paper)."""
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.c_[np.cos(t), np.sin(t), np.cos(3 * t)]


def trefoil(n: int) -> np.ndarray:
    """A trefoil knot: it bounds no disk, so it has no triangulation."""
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.c_[np.sin(t) + 2 * np.sin(2 * t), np.cos(t) - 2 * np.cos(2 * t),
                 -np.sin(3 * t)]


def twist(n: int) -> np.ndarray:
    """The paper's Twist curve: Θ(n²) Delaunay triangles, a slow DOT2."""
    if n % 2 == 0:
        n += 1
    p = lambda i: (i / n, (i / n) ** 2, (i / n) ** 3)  # noqa: E731
    out: List[tuple] = []
    k = 0
    while 2 * k + 1 <= n:
        out.append(p(2 * k + 1))
        if n - 1 - 2 * k >= 2:
            out.append(p(n - 1 - 2 * k))
        k += 1
    return np.array(out)


def protected_polygon() -> np.ndarray:
    """10 random vertices whose DOT needs 4 edges split (protect_edges)."""
    rng = np.random.default_rng(1)
    return np.round(rng.uniform(-1, 1, (10, 3)), 2)


def grid_with_hole(n: int, hole: slice = None):
    """An n x n vertex grid in the plane z = 0 with a square hole: vertices
    (n², 3), faces (F, 3), two triangles per cell outside the hole."""
    if hole is None:
        hole = slice(n // 2 - 2, n // 2 + 2)
    xs, ys = np.meshgrid(np.arange(n, dtype=float), np.arange(n, dtype=float))
    vertices = np.c_[xs.ravel(), ys.ravel(), np.zeros(n * n)]
    i, j = np.meshgrid(np.arange(n - 1), np.arange(n - 1), indexing="ij")
    keep = ~((i >= hole.start) & (i < hole.stop) & (j >= hole.start) &
             (j < hole.stop))
    a = (i * n + j)[keep]
    faces = np.concatenate([np.c_[a, a + 1, a + n + 1], np.c_[a, a + n + 1, a + n]])
    return vertices, faces


def box_with_hole():
    """A unit cube of 6 x 4 x 4 quads (vertices shared, outward faces) with
    one quad cut out of its top: exactly one 4-edge hole."""
    v, f = [], []
    index = {}

    def vid(p):
        p = tuple(round(c, 9) for c in p)
        if p not in index:
            index[p] = len(v)
            v.append(p)
        return index[p]

    k = 4
    for axis in range(3):
        for side in (0.0, 1.0):
            for a in range(k):
                for b in range(k):
                    if axis == 2 and side == 1.0 and a == 1 and b == 1:
                        continue  # the hole
                    quad = []
                    for da, db in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = [0.0, 0.0, 0.0]
                        u, w = (axis + 1) % 3, (axis + 2) % 3
                        p[axis] = side
                        p[u] = (a + da) / k
                        p[w] = (b + db) / k
                        quad.append(vid(p))
                    if side == 0.0:
                        quad.reverse()
                    f.append(quad)
    return np.array(v), np.array(f)


def directed_edges(faces: np.ndarray) -> set:
    return {(int(t[i]), int(t[(i + 1) % 3])) for t in faces for i in range(3)}


def border_edges(faces: np.ndarray) -> List[tuple]:
    """Directed edges without their opposite: the mesh's open border."""
    e = directed_edges(faces)
    return [d for d in e if (d[1], d[0]) not in e]

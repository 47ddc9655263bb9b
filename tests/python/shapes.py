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


def grid_with_holes(n: int, squares):
    """An n x n vertex grid in the plane z = 0 with square holes: each of
    `squares` is (i0, i1, j0, j1), the cells i0 <= i < i1, j0 <= j < j1
    cut out. Vertices (n², 3), faces (F, 3)."""
    xs, ys = np.meshgrid(np.arange(n, dtype=float), np.arange(n, dtype=float))
    vertices = np.c_[xs.ravel(), ys.ravel(), np.zeros(n * n)]
    i, j = np.meshgrid(np.arange(n - 1), np.arange(n - 1), indexing="ij")
    keep = np.ones_like(i, dtype=bool)
    for i0, i1, j0, j1 in squares:
        keep &= ~((i >= i0) & (i < i1) & (j >= j0) & (j < j1))
    a = (i * n + j)[keep]
    faces = np.concatenate([np.c_[a, a + 1, a + n + 1], np.c_[a, a + n + 1, a + n]])
    return vertices, faces


# Heights of the 10 x 10 grid of bumpy_grid_with_hole (numpy's
# default_rng(134), uniform in [-1.5, 1.5], 2 decimals), written out so the
# mesh never depends on a generator's stream.
_BUMPS = [
    1.41, 0.01, 0.13, 0.84, -0.59, 0.89, 0.75, 0.48, -0.89, -0.47, 0.31,
    -0.43, -1.38, -0.51, 0.79, -1.34, -0.67, -0.23, -1.24, 0.5, -0.72, -1.23,
    -0.08, -0.93, -0.52, -0.33, 1.29, 0.2, 0.24, 0.16, 0.97, -1.13, -1.24,
    -0.45, 0.86, -0.93, -0.05, 0.43, 1.29, -1.23, 0.43, -0.95, -1.43, 0.62,
    -1.38, -1.07, 0.6, -0.07, -0.16, -1.13, -0.64, 0.98, 1.27, -0.77, 1.48,
    1.33, 0.72, -1.47, -0.61, -0.51, -0.01, -0.4, 0.84, 1.15, -1.26, 0.47,
    -0.1, 1.45, -0.13, -0.44, 0.87, -1.09, 1.24, -0.57, 0.98, 0.2, 0.51, 0.47,
    -1.28, -1.33, 0.27, -1.11, -0.55, 0.66, -0.84, 1.2, 1.24, 0.61, 0.76, 0.99,
    -0.13, -1.22, 1.4, 1.21, 1.0, 1.33, -0.9, -0.53, 0.18, -0.83]


def wavy_grid_with_holes():
    """A wavy 300 x 300 grid with 100 square holes of 64 edges (and its
    rim): a fill of a few hundred ms whose holes phase a time budget can
    cut."""
    squares = [(i, i + 16, j, j + 16) for i in range(6, 290, 29)
               for j in range(6, 290, 29)]
    v, f = grid_with_holes(300, squares)
    v[:, 2] = 3 * np.sin(v[:, 0] / 7) * np.cos(v[:, 1] / 9)
    return v, f


def holes_phase_budgets(progress,
                        fractions=(0.05, 0.15, 0.3, 0.45, 0.6, 0.75)):
    """Time budgets (ms) that end at these fractions of the holes phase of
    a fill whose FillProgress reports are `progress`. Six, from early on:
    a later fill may run faster than the one measured (warm caches, an
    idle core), and with three the earliest ended after the holes once,
    with the suite running beside it."""
    start = next(p.elapsed_ms for p in progress if p.phase == "holes")
    end = max(p.elapsed_ms for p in progress)
    return [int(start + f * (end - start)) + 1 for f in fractions]


def bumpy_grid_with_hole():
    """A 10 x 10 grid with random heights and a 4 x 4-cell hole (16 edges)
    besides its rim. The hole has no Delaunay triangulation: FillHoles
    fills it by edge protection (one vertex inserted on a boundary edge),
    splitting the face across that edge (face 105)."""
    vertices, faces = grid_with_hole(10, slice(3, 7))
    vertices = vertices.copy()
    vertices[:, 2] = _BUMPS
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


def directed_edges(faces) -> set:
    """Directed edges of faces (triangles or polygons)."""
    return {(int(t[i]), int(t[(i + 1) % len(t)])) for t in faces
            for i in range(len(t))}


def border_edges(faces) -> List[tuple]:
    """Directed edges without their opposite: the mesh's open border."""
    e = directed_edges(faces)
    return [d for d in e if (d[1], d[0]) not in e]


def merge_coincident(vertices: np.ndarray, faces) -> list:
    """The faces with every vertex named by the first vertex at exactly its
    position (as the server's repair merges duplicates)."""
    first = {}
    target = [first.setdefault(tuple(p), i) for i, p in enumerate(vertices.tolist())]
    return [[target[int(v)] for v in f] for f in faces]


def canonical(faces) -> list:
    """Faces as a sorted list, each rotated to start at its smallest id: the
    same faces in any order compare equal."""
    out = []
    for f in faces:
        f = [int(v) for v in f]
        k = f.index(min(f))
        out.append(tuple(f[k:] + f[:k]))
    return sorted(out)

# SPDX-License-Identifier: AGPL-3.0-or-later
"""Holes with islands through Client.fill_holes against a real dot-server:
a flat grid with a square ring hole around an island is filled by one patch
joining both loops (reported on both), ``islands="off"`` joins none, and
``join`` groups are checked on both sides of the wire."""
import numpy as np
import pytest

import dot_client


def ring_grid(n=16, lo=4, hi=12, island_lo=6, island_hi=10):
    """An n x n grid of the unit square without the quads of [lo, hi)^2
    except those of [island_lo, island_hi)^2 (the island)."""
    g = np.linspace(0, 1, n + 1)
    vertices = np.array([[x, y, 0.0] for x in g for y in g])
    faces = []
    for i in range(n):
        for j in range(n):
            inside = lo <= i < hi and lo <= j < hi
            island = island_lo <= i < island_hi and island_lo <= j < island_hi
            if inside and not island:
                continue
            a, b = i * (n + 1) + j, (i + 1) * (n + 1) + j
            faces += [[a, b, b + 1], [a, b + 1, a + 1]]
    return vertices, np.array(faces)


def test_an_island_is_joined_to_its_rim_by_one_patch(client):
    v, f = ring_grid()
    r = client.fill_holes(v, f, skip_longest=True, stage="triangulate")
    by_size = {h.boundary_vertices: h for h in r.report.holes}
    rim, island = by_size[32], by_size[16]
    assert rim.joined == [island.id] and rim.joined_to is None
    assert island.joined_to == rim.id and island.joined == []
    assert rim.status == island.status == "filled"
    # A planar ring of 48 border vertices: 48 triangles, no new vertex.
    assert rim.patch_triangles == 48
    assert len(r.faces) == len(f) + 48
    assert len(r.vertices) == len(v)

    off = client.fill_holes(v, f, skip_longest=True, stage="triangulate",
                            islands="off")
    assert all(h.joined == [] and h.joined_to is None
               for h in off.report.holes)

    joined = client.fill_holes(v, f, skip_longest=True, stage="triangulate",
                               islands="off", join=[(island.id, rim.id)])
    assert np.array_equal(joined.faces, r.faces)


def test_bad_groups_are_refused(client):
    v, f = ring_grid()
    with pytest.raises(dot_client.InvalidInput, match="fewer than 2"):
        client.fill_holes(v, f, join=[(1,)])
    with pytest.raises(dot_client.InvalidInput, match="islands"):
        client.fill_holes(v, f, islands="sometimes")
    with pytest.raises(dot_client.DotError, match="no hole 9") as e:
        client.fill_holes(v, f, join=[(0, 9)])  # the server's check
    assert e.value.code.name == "INVALID_ARGUMENT"

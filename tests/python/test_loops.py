# SPDX-License-Identifier: AGPL-3.0-or-later
"""Client.triangulate_loops against a real dot-server: one surface joining
two loops, checked as a mesh (every loop edge once, every other edge
twice, Euler characteristic 0), orientation reporting, refusals."""
import numpy as np
import pytest

import dot_client


def ring(n, radius, z, turn=1.0):
    a = turn * 2 * np.pi * np.arange(n) / n
    return np.column_stack([radius * np.cos(a), radius * np.sin(a),
                            np.full(n, z) + 0.05 * np.sin(3 * a)])


def check_annulus(result, loops):
    tris = result.triangles
    directed = [(int(t[i]), int(t[(i + 1) % 3])) for t in tris
                for i in range(3)]
    assert len(set(directed)) == len(directed), "a directed edge twice"
    uses = {}
    for a, b in directed:
        uses[frozenset((a, b))] = uses.get(frozenset((a, b)), 0) + 1
    boundary = {e for e, k in uses.items() if k == 1}
    assert all(k in (1, 2) for k in uses.values())
    sizes = result.summary.loop_sizes
    assert sizes == [len(x) for x in loops]
    loop = result.summary.loop
    expected = set()
    begin = 0
    for size in sizes:
        ids = loop[begin:begin + size]
        expected |= {frozenset((int(a), int(b)))
                     for a, b in zip(ids, np.roll(ids, -1))}
        # Each loop runs its listed way along the surface.
        for a, b in zip(ids, np.roll(ids, -1)):
            assert (int(a), int(b)) in set(directed)
        begin += size
    assert boundary == expected
    vertices = len({v for t in tris for v in t})
    assert vertices - len(uses) + len(tris) == 0  # an annulus


def test_tube_between_two_rims(client):
    # Rim 1 runs against rim 0, as a tube's rims do along it.
    loops = [ring(40, 1.0, 0.0), ring(30, 0.7, 0.8, turn=-1.0)]
    r = client.triangulate_loops(loops, squared_dihedral=1,
                                 keep_loop_directions=True)
    assert r.summary.status == "ok"
    assert r.summary.reversed_loops == []
    assert np.array_equal(r.vertices[:70], np.concatenate(loops))
    check_annulus(r, loops)
    assert r.summary.solver == "DOT2"


def test_loop_given_the_other_way_is_reversed_and_reported(client):
    loops = [ring(24, 1.0, 0.0), ring(24, 0.7, 0.8)]
    r = client.triangulate_loops(loops)
    assert r.summary.reversed_loops == [1]
    check_annulus(r, loops)
    # Kept as given, the rims would need a twisted surface: none exists.
    with pytest.raises(dot_client.NoTriangulation) as e:
        client.triangulate_loops(loops, keep_loop_directions=True)
    assert "one does with it reversed" in str(e.value)


def test_malformed_loops_are_refused_before_the_call(client):
    with pytest.raises(dot_client.InvalidInput, match="loops\\[1\\]"):
        client.triangulate_loops([ring(5, 1, 0), np.zeros((2, 3))])
    with pytest.raises(dot_client.InvalidInput, match="list of"):
        client.triangulate_loops(np.zeros((6, 3)))
    with pytest.raises(dot_client.InvalidInput, match="one per loop"):
        client.triangulate_loops([ring(5, 1, 0), ring(5, 0.5, 1)],
                                 normals=[np.ones((5, 3))])
    with pytest.raises(dot_client.InvalidInput, match="normals\\[0\\] has 6 rows"):
        client.triangulate_loops([ring(5, 1, 0), ring(5, 0.5, 1)],
                                 normals=[np.ones((6, 3)), np.ones((4, 3))])
    with pytest.raises(dot_client.InvalidInput, match="sum to"):
        client.triangulate(ring(6, 1, 0), loop_sizes=[3, 4])


def test_three_loops_join_by_bridges_into_one_surface(client):
    # A wide rim below two small ones side by side: a pants.
    # The top rims run against the bottom one, as a tube's two rims do.
    loops = [ring(8, 1, 0), ring(6, 0.3, 1, turn=-1.0) + [0.45, 0, 0],
             ring(6, 0.3, 1, turn=-1.0) - [0.45, 0, 0]]
    r = client.triangulate_loops(loops)
    assert r.summary.loop_sizes == [8, 6, 6]
    assert r.summary.bridges.shape == (2, 2)
    # Genus 0 with 3 boundaries and no inner vertex: n + 2 (k - 2) faces.
    assert len(r.triangles) == 20 + 2
    edges = {}
    for t in r.triangles:
        for i in range(3):
            e = frozenset((int(t[i]), int(t[(i + 1) % 3])))
            edges[e] = edges.get(e, 0) + 1
    assert sum(1 for k in edges.values() if k == 1) == 20  # the loop edges
    assert all(k in (1, 2) for k in edges.values())


def test_forbidden_edges_steer_the_triangulation(client):
    # A unit square: area ties its two diagonals; forbidding one leaves the
    # other, through the server's own check of the chord.
    square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    for forbidden, kept in (([[0, 2]], {1, 3}), ([[1, 3]], {0, 2})):
        r = client.triangulate(square, forbidden_edges=forbidden)
        shared = set(map(int, r.triangles[0])) & set(map(int, r.triangles[1]))
        assert shared == kept
    with pytest.raises(dot_client.InvalidInput, match="forbidden_edges"):
        client.triangulate(square, forbidden_edges=[[0, 9]])
    with pytest.raises(dot_client.InvalidInput, match="pairs"):
        client.triangulate(square, forbidden_edges=[0, 2, 1])
    with pytest.raises(dot_client.DotError, match="polygon edge"):
        client.triangulate(square, forbidden_edges=[[0, 1]])

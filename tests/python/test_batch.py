# SPDX-License-Identifier: AGPL-3.0-or-later
"""Client.triangulate_many: one TriangulateBatch stream, input order, per
polygon failures, progress, cancel."""
import threading
import time

import grpc
import numpy as np
import pytest

import dot_client
from shapes import monkey_saddle, protected_polygon, trefoil, twist


def test_results_in_input_order(client):
    # Sizes differ so the server finishes them out of order.
    polygons = [monkey_saddle(n) for n in (400, 5, 120, 3, 60, 250, 9)]
    seen = []
    results = client.triangulate_many(
        polygons, squared_dihedral=1,
        progress=lambda done, total, r: seen.append((done, total, r.id)))
    assert len(results) == len(polygons)
    for p, r in zip(polygons, results):
        assert r.ok, r.error
        assert np.array_equal(r.vertices, p)
        assert r.triangles.shape == (len(p) - 2, 3)
        assert r.summary.solver == "DOT2"
    assert [d for d, _, _ in seen] == list(range(1, len(polygons) + 1))
    assert all(t == len(polygons) for _, t, _ in seen)
    assert sorted(int(i) for _, _, i in seen) == list(range(len(polygons)))


def test_normals_per_polygon_and_protected_edges(client):
    a, b = monkey_saddle(30), protected_polygon()
    up = np.tile([0, 0, 1.0], (30, 1))
    results = client.triangulate_many([a, a], [up, None], normal_deviation=1,
                                      area=0.1)
    assert results[0].ok
    assert results[0].summary.metric_costs["normal_deviation"] > 0
    assert results[1].error.code == grpc.StatusCode.INVALID_ARGUMENT
    assert "no boundary normals" in results[1].error.message
    results = client.triangulate_many([a, b], protect_edges=True,
                                      search_space="delaunay")
    assert all(r.ok for r in results)
    assert results[1].summary.inserted_count == 4
    assert np.array_equal(results[1].vertices[:10], b)


def test_a_bad_polygon_fails_alone(client):
    bad = monkey_saddle(20)
    bad[7] = bad[2]  # repeated vertex: the server refuses it
    polygons = [monkey_saddle(30), bad, trefoil(90), monkey_saddle(8)]
    results = client.triangulate_many(polygons)
    assert [r.ok for r in results] == [True, False, False, True]
    assert results[1].error.code == grpc.StatusCode.INVALID_ARGUMENT
    assert "vertex 7" in results[1].error.message
    assert isinstance(results[2].error, dot_client.NoTriangulation)
    assert results[2].summary.status == "no_triangulation"
    assert results[2].triangles.shape == (0, 3)


def test_empty_batch(client):
    assert client.triangulate_many([]) == []


@pytest.mark.parametrize("polygons, normals, words", [
    ([monkey_saddle(5), np.zeros((2, 3))], None, "polygons[1]"),
    ([monkey_saddle(5)], [None, None], "one (or None) per polygon"),
    ([monkey_saddle(5)], [np.zeros((4, 3))], "normals[0]"),
    (monkey_saddle(5), None, "list of (n, 3) arrays"),
    (7, None, "list of (n, 3) arrays"),
])
def test_invalid_batches_are_refused_before_the_call(polygons, normals, words):
    with dot_client.Client("127.0.0.1:1") as client:
        with pytest.raises(dot_client.InvalidInput) as e:
            client.triangulate_many(polygons, normals)
    assert words in e.value.message


def test_timeout_and_cancel_end_the_stream(server, client):
    slow = [twist(1501)] * 2
    with pytest.raises(dot_client.DotError) as e:
        client.triangulate_many(slow, squared_dihedral=1, no_cache=True,
                                timeout=0.2)
    assert e.value.code == grpc.StatusCode.DEADLINE_EXCEEDED
    token = dot_client.CancelToken()
    threading.Timer(0.2, token.cancel).start()
    t0 = time.monotonic()
    with pytest.raises(dot_client.DotError) as e:
        client.triangulate_many(slow, squared_dihedral=1, no_cache=True,
                                cancel=token)
    assert e.value.code == grpc.StatusCode.CANCELLED
    assert time.monotonic() - t0 < 5
    assert server.alive()
    assert client.triangulate_many([monkey_saddle(10)])[0].ok


def test_batch_over_the_limit_fails_alone(limited_server):
    with dot_client.Client(limited_server.address, timeout=30) as client:
        results = client.triangulate_many([monkey_saddle(200),
                                           monkey_saddle(20)])
    assert results[0].error.code == grpc.StatusCode.RESOURCE_EXHAUSTED
    assert results[1].ok

# SPDX-License-Identifier: AGPL-3.0-or-later
"""Client.triangulate against a real dot-server: results, options, every
error path, cancel."""
import threading
import time

import grpc
import numpy as np
import pytest

import dot_client
from shapes import monkey_saddle, protected_polygon, trefoil, twist


def check_patch(result, points):
    """A disk spanning the polygon: input vertices exactly first, int32
    triangles in range, each polygon edge once in the loop's direction."""
    n = len(points)
    assert result.vertices.dtype == np.float64
    assert result.triangles.dtype == np.int32
    assert result.vertices.shape == (result.summary.vertex_count, 3)
    assert result.triangles.shape == (result.summary.triangle_count, 3)
    assert np.array_equal(result.vertices[:n], points)
    assert result.triangles.min() >= 0
    assert result.triangles.max() < len(result.vertices)
    loop = (result.summary.loop if result.summary.inserted_count
            else np.arange(n))
    directed = {(int(t[i]), int(t[(i + 1) % 3]))
                for t in result.triangles for i in range(3)}
    for a, b in zip(loop, np.roll(loop, -1)):
        assert (int(a), int(b)) in directed
    assert len(result.triangles) == len(loop) - 2 + 0  # a disk, no interior


def test_triangulate_a_saddle(client):
    points = monkey_saddle(60)
    r = client.triangulate(points, squared_dihedral=1, validate_output=True)
    assert r.ok and r.error is None
    check_patch(r, points)
    s = r.summary
    assert s.status == "ok" and s.solver == "DOT2"
    assert s.search_space_used == "delaunay3d"
    assert s.intersecting_pairs == 0
    assert s.total_cost > 0
    assert set(s.metric_costs) == {"area", "perimeter", "normal_deviation",
                                   "shape", "dihedral", "squared_dihedral"}
    assert s.stats.n == 60 and s.stats.search_triangles > 0
    assert s.to_dict()["stats"]["n"] == 60


def test_lists_of_tuples_and_area_default(client):
    square = [(0, 0, 0), (1, 0, 0), (1, 1, 0.5), (0, 1, 0)]
    r = client.triangulate(square)
    assert r.triangles.shape == (2, 3)
    assert r.summary.solver == "DOT1"  # area alone
    assert np.array_equal(r.vertices, np.array(square, dtype=float))


def test_weights_change_the_answer(client):
    points = monkey_saddle(40)
    area = client.triangulate(points, area=1)
    maximal = client.triangulate(points, area=-1)
    assert area.summary.metric_costs["area"] < \
        maximal.summary.metric_costs["area"]


def test_normals_and_normal_deviation(client):
    points = monkey_saddle(50)
    normals = np.tile([0.0, 0.0, 1.0], (50, 1))
    r = client.triangulate(points, normals, normal_deviation=1, area=0.1)
    check_patch(r, points)
    assert r.summary.metric_costs["normal_deviation"] > 0


def test_protect_edges_puts_the_input_back_and_appends_inserted(client):
    points = protected_polygon()
    r = client.triangulate(points, protect_edges=True,
                           search_space="delaunay", squared_dihedral=1)
    s = r.summary
    assert s.inserted_count == 4
    assert len(r.vertices) == len(points) + 4
    assert len(s.loop) == len(points) + 4
    check_patch(r, points)
    # Without protection the same polygon has no Delaunay triangulation.
    with pytest.raises(dot_client.NoTriangulation) as e:
        client.triangulate(points, search_space="delaunay")
    assert len(e.value.summary.non_delaunay_edges) > 0
    assert e.value.summary.non_delaunay_edges.shape[1] == 2


def test_search_space_all_and_backends(client):
    points = monkey_saddle(12)
    r = client.triangulate(points, search_space="all", squared_dihedral=1)
    assert r.summary.search_space_used == "all"
    assert r.summary.solver == "GK2"
    t = client.triangulate(monkey_saddle(30), delaunay_backend="tetgen")
    assert t.summary.delaunay_backend == "tetgen"
    c = client.triangulate(monkey_saddle(30), delaunay_backend="CGAL")
    assert c.summary.delaunay_backend == "cgal"
    # Every triangle, Delaunay ones first: the cubic search, validated.
    d = client.triangulate(monkey_saddle(60), search_space="delaunay_first",
                           squared_dihedral=1)
    assert d.summary.search_space_used == "all_delaunay_first"
    assert d.summary.solver == "GK2-greedy"
    assert d.summary.intersecting_pairs == 0
    assert len(d.triangles) == 58


def test_cache_hit_on_a_re_solve(client):
    points = monkey_saddle(80) * 1.5
    client.triangulate(points, area=1)
    again = client.triangulate(points, squared_dihedral=1)
    assert again.summary.cache_hit
    fresh = client.triangulate(points, area=1, no_cache=True)
    assert not fresh.summary.cache_hit


def test_progress_callback(client):
    seen = []
    r = client.triangulate(twist(601), squared_dihedral=1, no_cache=True,
                           progress=seen.append, progress_interval_ms=1)
    assert r.ok
    assert seen, "no Progress message"
    assert all(isinstance(p, dot_client.Progress) for p in seen)
    assert {p.stage for p in seen} <= {"queued", "validate", "delaunay",
                                       "adjacency", "dynamic_program",
                                       "tiling"}
    assert all(0 <= p.fraction <= 1 for p in seen)


def test_large_polygon_streams_back(client):
    # 5,000 vertices: planar (the CDT path), 4,998 triangles.
    t = np.linspace(0, 2 * np.pi, 5000, endpoint=False)
    points = np.c_[np.cos(t), np.sin(t) * 0.5, np.zeros_like(t)]
    r = client.triangulate(points)
    assert r.summary.planar
    check_patch(r, points)


def test_no_triangulation_raised_or_returned(client):
    knot = trefoil(90)
    with pytest.raises(dot_client.NoTriangulation) as e:
        client.triangulate(knot)
    assert isinstance(e.value, dot_client.DotError)
    assert e.value.code == grpc.StatusCode.OK
    assert "not Delaunay-triangulable" in e.value.message
    assert str(e.value).startswith("no triangulation: ")
    r = client.triangulate(knot, raise_no_triangulation=False)
    assert not r.ok
    assert r.summary.status == "no_triangulation"
    assert r.vertices.shape == (0, 3) and r.triangles.shape == (0, 3)


def test_server_rejects_a_repeated_vertex(client):
    points = monkey_saddle(20)
    points[13] = points[4]
    with pytest.raises(dot_client.DotError) as e:
        client.triangulate(points)
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert "vertex 13" in e.value.message
    assert not isinstance(e.value, dot_client.InvalidInput)


@pytest.mark.parametrize("points, kwargs, words", [
    (np.zeros((4, 2)), {}, "shape (n, 3)"),
    (np.zeros(12), {}, "shape (n, 3)"),
    ([(0, 0, 0), (1, 0, 0)], {}, "at least 3"),
    ([(0, 0, 0), (1, 0, float("nan")), (0, 1, 0)], {}, "points[1]"),
    ([(0, 0, 0), (1, 0, 0), (0, "a", 0)], {}, "numbers"),
    (monkey_saddle(5), {"normals": np.zeros((4, 3))}, "one per vertex"),
    (monkey_saddle(5), {"area": float("inf")}, "area must be finite"),
    (monkey_saddle(5), {"shape": "1"}, "shape must be a number"),
    (monkey_saddle(5), {"search_space": "everything"}, "search_space"),
    (monkey_saddle(5), {"delaunay_backend": "qhull"}, "delaunay_backend"),
    (monkey_saddle(5), {"protect_edges": 1}, "True or False"),
    (monkey_saddle(5), {"time_budget_ms": -1}, "time_budget_ms"),
    (monkey_saddle(5), {"timeout": 0}, "timeout"),
    (monkey_saddle(5), {"progress": print, "progress_interval_ms": 0},
     "progress_interval_ms"),
])
def test_invalid_input_is_refused_before_the_call(points, kwargs, words):
    # No server at all: nothing is sent.
    with dot_client.Client("127.0.0.1:1") as client:
        normals = kwargs.pop("normals", None)
        with pytest.raises(dot_client.InvalidInput) as e:
            client.triangulate(points, normals, **kwargs)
    assert words in e.value.message
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert isinstance(e.value, ValueError)


def test_resource_exhausted_over_the_limit(limited_server):
    with dot_client.Client(limited_server.address, timeout=30) as client:
        with pytest.raises(dot_client.DotError) as e:
            client.triangulate(monkey_saddle(200))
        assert e.value.code == grpc.StatusCode.RESOURCE_EXHAUSTED
        assert client.triangulate(monkey_saddle(50)).ok


def test_timeout_cancels_a_long_call(server, client):
    t0 = time.monotonic()
    with pytest.raises(dot_client.DotError) as e:
        client.triangulate(twist(1501), squared_dihedral=1, no_cache=True,
                           timeout=0.2)
    assert e.value.code == grpc.StatusCode.DEADLINE_EXCEEDED
    assert time.monotonic() - t0 < 5
    # The client's default deadline applies too.
    with dot_client.Client(server.address, timeout=0.2) as short:
        with pytest.raises(dot_client.DotError) as e:
            short.triangulate(twist(1501), squared_dihedral=1, no_cache=True)
        assert e.value.code == grpc.StatusCode.DEADLINE_EXCEEDED
    assert server.alive() and client.health() == "SERVING"


def test_keyboard_interrupt_cancels_the_call(server, client):
    def interrupt(progress):
        raise KeyboardInterrupt

    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        client.triangulate(twist(1501), squared_dihedral=1, no_cache=True,
                           progress=interrupt, progress_interval_ms=1)
    assert time.monotonic() - t0 < 5
    assert server.alive()
    assert client.triangulate(monkey_saddle(30)).ok


def test_cancel_token_from_another_thread(client):
    token = dot_client.CancelToken()
    threading.Timer(0.2, token.cancel).start()
    t0 = time.monotonic()
    with pytest.raises(dot_client.DotError) as e:
        client.triangulate(twist(1501), squared_dihedral=1, no_cache=True,
                           cancel=token)
    assert e.value.code == grpc.StatusCode.CANCELLED
    assert time.monotonic() - t0 < 5
    assert token.cancelled
    # A cancelled token cancels the next call at once.
    with pytest.raises(dot_client.DotError) as e:
        client.triangulate(monkey_saddle(10), cancel=token)
    assert e.value.code == grpc.StatusCode.CANCELLED

# SPDX-License-Identifier: AGPL-3.0-or-later
"""Client.fill_holes against a real dot-server: stages, hole selection
(loops_through too), weights, polygons, large meshes in chunks, the
report's enum names, errors, cancel."""
import threading
import time

import grpc
import numpy as np
import pytest

import dot_client
from dot_client import wire
from dot_client._proto.dot.v1 import triangulation_pb2 as pb
from shapes import (border_edges, box_with_hole, bumpy_grid_with_hole,
                    grid_with_hole, grid_with_holes, holes_phase_budgets,
                    wavy_grid_with_holes)


def test_fill_a_box(client):
    v, quads = box_with_hole()
    assert len(border_edges(np.concatenate(
        [quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]]))) == 4
    progress = []
    r = client.fill_holes(v, quads, progress=progress.append)
    assert isinstance(r, dot_client.FillResult)
    assert r.vertices.dtype == np.float64 and r.faces.dtype == np.int32
    assert r.faces.shape[1] == 3
    rep = r.report
    assert rep.version == 2 and rep.loops == 1 and rep.filled == 1
    assert rep.closed
    assert rep.repair.triangulated_polygons == len(quads)
    assert rep.input_vertices == len(v)
    assert len(r.vertices) == rep.input_vertices + rep.added_vertices
    assert len(r.faces) == rep.input_faces + rep.added_faces
    assert np.array_equal(r.vertices[:len(v)], v)
    assert border_edges(r.faces) == []  # closed and consistently oriented
    hole = rep.holes[0]
    assert hole.status == "filled" and hole.boundary_vertices == 4
    assert hole.escalation == "delaunay"
    assert progress and progress[-1].holes_done == progress[-1].holes_total == 1
    assert rep.to_dict()["holes"][0]["status"] == "filled"


def test_stages(client):
    v, f = grid_with_hole(30, slice(8, 20))
    tri = client.fill_holes(v, f, stage="triangulate", skip_longest=True)
    refined = client.fill_holes(v, f, stage="refine", skip_longest=True)
    faired = client.fill_holes(v, f, stage="fair", skip_longest=True)
    assert tri.report.added_vertices == 0
    assert refined.report.added_vertices > 0
    assert faired.report.added_vertices == refined.report.added_vertices
    assert [h.status for h in tri.report.holes].count("filled") == 1
    assert [h.status for h in tri.report.holes].count("skipped") == 1
    assert not tri.report.closed  # the rim stays open
    # The grid is flat: the faired patch stays in the plane.
    assert np.allclose(faired.vertices[:, 2], 0, atol=1e-9)


def test_hole_selection(client):
    v, f = grid_with_hole(20)
    small = client.fill_holes(v, f, max_hole_edges=20)
    assert small.report.filled == 1 and small.report.skipped == 1
    wide = client.fill_holes(v, f, max_hole_diameter=10)
    assert wide.report.filled == 1
    hole = min(small.report.holes, key=lambda h: h.boundary_vertices).id
    only = client.fill_holes(v, f, holes=[hole], stage="triangulate")
    assert [(h.boundary_vertices, h.status) for h in only.report.holes
            if h.id == hole] == [(16, "filled")]
    assert only.report.skipped == 1
    # A hole id that names no hole is an error, not "nothing to fill".
    with pytest.raises(dot_client.DotError) as e:
        client.fill_holes(v, f, holes=[99])
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert "there is no hole 99: the mesh has 2 holes" in e.value.message


def test_list_holes_reports_sizes_and_fills_nothing(client):
    v, f = grid_with_hole(20)  # a 4 x 4 square hole, and the rim
    report = client.list_holes(v, f, max_hole_edges=20)
    assert (report.loops, report.listed, report.skipped) == (2, 1, 1)
    assert report.filled == 0 and report.added_faces == 0
    hole, rim = sorted(report.holes, key=lambda h: h.boundary_vertices)
    assert (hole.status, rim.status) == ("listed", "skipped")
    assert "more than max_edges 20" in rim.reason
    assert hole.perimeter == pytest.approx(16)
    assert hole.diameter == pytest.approx(4 * np.sqrt(2))
    assert hole.centroid == pytest.approx((10, 10, 0))
    assert rim.perimeter == pytest.approx(76)
    assert rim.centroid == pytest.approx((9.5, 9.5, 0))
    # A fill reports the same sizes.
    filled = client.fill_holes(v, f, max_hole_edges=20)
    assert [h.perimeter for h in filled.report.holes] == \
        [h.perimeter for h in report.holes]


# Three square holes in a 16 x 16 grid, and the rim.
HOLES = [(2, 4, 2, 4), (2, 4, 10, 13), (9, 13, 5, 8)]


def loop_vertices(vertices, faces):
    """The border's vertex sets, one per hole of grid_with_holes (the
    square's corners and edges), and the rim's."""
    on_border = {v for e in border_edges(faces) for v in e}
    n = int(round(np.sqrt(len(vertices))))
    out = []
    for i0, i1, j0, j1 in HOLES:
        out.append({i * n + j for i in range(i0, i1 + 1)
                    for j in range(j0, j1 + 1)} & on_border)
    out.append(on_border - set().union(*out))
    return out


def test_loops_through_fills_exactly_the_named_loops(client):
    v, f = grid_with_holes(16, HOLES)
    loops = loop_vertices(v, f)
    assert [len(x) for x in loops] == [8, 10, 14, 60]
    # One vertex of the first hole and one of the third (not corners).
    named = [2 * 16 + 3, 9 * 16 + 6]
    assert named[0] in loops[0] and named[1] in loops[2]
    for stage in ("triangulate", "refine", "fair"):
        r = client.fill_holes(v, f, stage=stage, loops_through=named)
        rep = r.report
        assert (rep.loops, rep.filled, rep.skipped) == (4, 2, 2), stage
        by_size = {h.boundary_vertices: h for h in rep.holes}
        assert by_size[8].status == by_size[14].status == "filled"
        for size in (10, 60):
            assert by_size[size].status == "skipped"
            assert by_size[size].reason == \
                "through none of the requested vertices"
            assert by_size[size].escalation == ""
        # The named loops are closed, the others still open.
        left = {x for e in border_edges(r.faces) for x in e}
        assert left == loops[1] | loops[3], stage
    # With the other rules: a loop must pass each one given.
    r = client.fill_holes(v, f, stage="triangulate", loops_through=named,
                          max_hole_edges=10)
    assert [h.boundary_vertices for h in r.report.holes
            if h.status == "filled"] == [8]


def test_loops_through_refusals(client):
    v, f = grid_with_holes(16, HOLES)
    with pytest.raises(dot_client.DotError) as e:
        client.fill_holes(v, f, loops_through=[7 * 16 + 7])  # inside
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert "vertex 119 is on no border loop" in e.value.message
    with pytest.raises(dot_client.InvalidInput) as e:
        client.fill_holes(v, f, loops_through=[3, 256])
    assert e.value.message == ("loops_through[1] = 256 is not a vertex of "
                               "the mesh (it has 256)")
    with pytest.raises(dot_client.InvalidInput, match="loops_through must be "
                       "a list of vertex ids"):
        client.fill_holes(v, f, loops_through=3)
    with pytest.raises(dot_client.InvalidInput,
                       match=r"loops_through\[0\] must be between 0"):
        client.fill_holes(v, f, loops_through=[-1])


def test_hole_status_and_escalation_names(client):
    # Every value of the wire's enums has its readable name.
    names = {pb.HoleStatus.Name(s): dot_client.HoleReport.from_proto(
        pb.HoleReport(status=s)).status for s in pb.HoleStatus.values()}
    assert names == {"HOLE_STATUS_UNSPECIFIED": "unspecified",
                     "HOLE_STATUS_FILLED": "filled",
                     "HOLE_STATUS_SKIPPED": "skipped",
                     "HOLE_STATUS_NO_TRIANGULATION": "no_triangulation",
                     "HOLE_STATUS_FAILED": "failed",
                     "HOLE_STATUS_LISTED": "listed",
                     "HOLE_STATUS_STOPPED": "stopped"}
    names = {pb.Escalation.Name(x): dot_client.HoleReport.from_proto(
        pb.HoleReport(escalation=x)).escalation for x in pb.Escalation.values()}
    assert names == {"ESCALATION_NONE": "",
                     "ESCALATION_DELAUNAY": "delaunay",
                     "ESCALATION_PROTECTED_EDGES": "protected_edges",
                     "ESCALATION_ALL_TRIANGLES": "all_triangles",
                     "ESCALATION_DELAUNAY_FIRST": "delaunay_first"}
    # A value this client does not know reads as its number.
    assert dot_client.HoleReport.from_proto(pb.HoleReport(status=9)).status \
        == "9"
    # Live: edge protection, and a hole no patch can fill.
    v, f = bumpy_grid_with_hole()
    r = client.fill_holes(v, f, stage="triangulate", skip_longest=True)
    hole = [h for h in r.report.holes if h.status == "filled"]
    assert [(h.escalation, h.split_faces, h.boundary_inserted)
            for h in hole] == [("protected_edges", [105], 1)]
    rim = [h for h in r.report.holes if h.status == "skipped"]
    assert [h.escalation for h in rim] == [""]
    assert r.report.to_dict()["holes"][hole[0].id]["escalation"] == \
        "protected_edges"
    g, gf = grid_with_hole(12)
    r = client.fill_holes(g, gf, stage="triangulate", loops_through=[0])
    rim = [h for h in r.report.holes if h.boundary_vertices == 44]
    # The flat grid's rim: the patches over every triangle that avoid the
    # mesh's chords all lie on the grid itself.
    assert [(h.status, h.escalation) for h in rim] == \
        [("failed", "delaunay_first")]
    assert "intersects the mesh" in rim[0].reason


def pierced_grid(x_from):
    """grid_with_hole(16) with a thin closed tetrahedron through its hole
    along y = 8, from x = x_from to 9.6: every patch meets it; from
    x_from < 6 on it crosses the grid too."""
    v, f = grid_with_hole(16, slice(6, 10))
    tip = np.array([[x_from, 8, -2], [9.6, 8, 2], [9.6, 8, -2], [9.6, 8.3, 0]])
    n = len(v)
    tet = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]) + n
    return np.concatenate([v, tip]), np.concatenate([f, tet])


def test_allow_input_intersections(client):
    v, f = pierced_grid(1.6)
    plain = client.fill_holes(v, f, stage="triangulate", skip_longest=True)
    assert plain.report.filled == 0
    (hole,) = [h for h in plain.report.holes if h.status == "failed"]
    assert "intersects the mesh" in hole.reason
    r = client.fill_holes(v, f, stage="triangulate", skip_longest=True,
                          allow_input_intersections=True)
    assert r.report.filled == 1
    (hole,) = [h for h in r.report.holes if h.status == "filled"]
    assert hole.intersecting_pairs > 0 and hole.input_pairs_near > 0
    assert "already intersects itself" in hole.reason
    # A clean input near the hole: the opt-in does not apply.
    v, f = pierced_grid(7.0)
    r = client.fill_holes(v, f, stage="triangulate", skip_longest=True,
                          allow_input_intersections=True)
    assert r.report.filled == 0
    assert any("does not intersect itself near the hole" in h.reason
               for h in r.report.holes)
    with pytest.raises(dot_client.InvalidInput):
        dot_client.FillOptions(allow_input_intersections="yes")


def test_weights_and_options(client):
    v, f = grid_with_hole(20)
    r = client.fill_holes(v, f, area=1, skip_longest=True, stage="refine",
                          absolute_weights=True, density=2,
                          fairing_continuity=2, time_budget_ms=10000,
                          memory_budget_bytes=1 << 28)
    assert r.report.filled == 1
    with pytest.raises(dot_client.InvalidInput, match="every metric weight"):
        client.fill_holes(v, f, area=0, shape=0)


def test_no_repair_keeps_the_input_as_sent(client):
    v, f = grid_with_hole(16)
    r = client.fill_holes(v, f, no_repair=True, skip_longest=True)
    assert np.array_equal(r.vertices[:len(v)], v)
    assert np.array_equal(r.faces[:len(f)], f)  # nothing split here
    assert r.report.repair.merged_vertices == 0


def test_polygons_of_mixed_sizes(client):
    v, quads = box_with_hole()
    mixed = [list(q) for q in quads[:10]]
    for q in quads[10:]:
        mixed += [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
    r = client.fill_holes(v, mixed)
    assert r.report.closed
    assert r.report.repair.triangulated_polygons == 10


def test_large_mesh_in_chunks(client):
    # 100,489 vertices and 199,640 faces in (about 5 request messages of
    # at most 1 MiB); back in several 1 MiB chunks each way.
    v, f = grid_with_hole(317, slice(150, 156))
    requests = list(wire.fill_requests("x", wire.pb.FillOptions(), v, f))
    assert len(requests) >= 5
    assert all(r.ByteSize() <= wire.REQUEST_BYTES + 64 for r in requests)
    t0 = time.monotonic()
    r = client.fill_holes(v, f, skip_longest=True, stage="triangulate")
    elapsed = time.monotonic() - t0
    assert len(f) == 199640
    assert r.report.filled == 1
    assert len(r.faces) == len(f) + r.report.added_faces
    assert np.array_equal(r.vertices, v)
    assert elapsed < 30


def test_server_errors(client, limited_server):
    with dot_client.Client(limited_server.address, timeout=30) as small:
        big_v, big_f = grid_with_hole(40)
        with pytest.raises(dot_client.DotError) as e:
            small.fill_holes(big_v, big_f)
        assert e.value.code == grpc.StatusCode.RESOURCE_EXHAUSTED
        assert "limit" in e.value.message
    # An edge of three faces: not manifold, not repairable.
    fan = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0, -1, 0]],
                   dtype=float)
    for no_repair in (False, True):
        with pytest.raises(dot_client.DotError) as e:
            client.fill_holes(fan, [[0, 1, 2], [0, 1, 3], [0, 1, 4]],
                              no_repair=no_repair)
        assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
        assert "edge 0-1 is shared by 3 faces" in e.value.message
    # Faces that are all degenerate: nothing is left, which is an error (it
    # was answered OK, closed, with an empty mesh).
    flat = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0]], dtype=float)
    with pytest.raises(dot_client.DotError) as e:
        client.fill_holes(flat, [[0, 1, 2]])
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert "nothing is left of the mesh after repair" in e.value.message


@pytest.mark.parametrize("vertices, faces, kwargs, words", [
    (np.zeros((3, 3)), np.zeros((0, 3), int), {}, "no faces"),
    (np.zeros((3, 3)), [[0, 1, 3]], {}, "vertex index 3"),
    (np.zeros((3, 3)), [[0, 1, -1]], {}, "vertex index -1"),
    (np.zeros((3, 3)), [[0, 1]], {}, "shape (F, 3)"),
    (np.zeros((4, 3)), [[0, 1, 2], [0, 1]], {}, "face 1 has 2 corners"),
    (np.zeros((3, 3)), [[0, 1, 2.5]], {}, "integer"),
    (np.zeros((3, 2)), [[0, 1, 2]], {}, "vertices must have shape"),
    (np.array([[0, 0, np.inf]] * 3), [[0, 1, 2]], {}, "not finite"),
    (np.zeros((3, 3)), [[0, 1, 2]], {"stage": "paint"}, "stage"),
    (np.zeros((3, 3)), [[0, 1, 2]], {"max_hole_edges": -1}, "max_hole_edges"),
    (np.zeros((3, 3)), [[0, 1, 2]], {"max_hole_diameter": -1.0},
     "max_hole_diameter"),
    (np.zeros((3, 3)), [[0, 1, 2]], {"holes": "1,2"}, "hole ids"),
    (np.zeros((3, 3)), [[0, 1, 2]], {"fairing_continuity": 3},
     "fairing_continuity"),
    (np.zeros((3, 3)), [[0, 1, 2]], {"density": 500}, "density"),
])
def test_invalid_meshes_are_refused_before_the_call(vertices, faces, kwargs,
                                                    words):
    with dot_client.Client("127.0.0.1:1") as client:
        with pytest.raises(dot_client.InvalidInput) as e:
            client.fill_holes(vertices, faces, **kwargs)
    assert words in e.value.message


def test_timeout_and_cancel(server, client):
    v, f = grid_with_hole(317, slice(100, 200))
    with pytest.raises(dot_client.DotError) as e:
        client.fill_holes(v, f, skip_longest=True, timeout=0.3)
    assert e.value.code == grpc.StatusCode.DEADLINE_EXCEEDED
    token = dot_client.CancelToken()
    threading.Timer(0.3, token.cancel).start()
    with pytest.raises(dot_client.DotError) as e:
        client.fill_holes(v, f, skip_longest=True, cancel=token)
    assert e.value.code == grpc.StatusCode.CANCELLED
    assert server.alive()
    small_v, small_f = grid_with_hole(10)
    assert client.fill_holes(small_v, small_f, skip_longest=True).report.filled


def test_progress_reports_the_phases_in_order(client):
    v, f = wavy_grid_with_holes()
    seen = []
    r = client.fill_holes(v, f, skip_longest=True, stage="triangulate",
                          progress=seen.append)
    assert r.report.filled == 100
    order = ["repair", "loops", "holes", "merge"]
    phases = [order.index(p.phase) for p in seen]
    assert phases == sorted(phases) and 2 in phases
    holes = [p for p in seen if p.phase == "holes"]
    assert all(p.holes_total == 100 for p in holes)
    assert all(p.eta_ms >= 0 for p in holes)
    assert [p.elapsed_ms for p in seen] == sorted(p.elapsed_ms for p in seen)


def test_a_stopped_fill_keeps_the_holes_it_finished(client):
    v, f = wavy_grid_with_holes()
    # Timed on a warm server (the first fill also warms its caches, and a
    # budget measured on it ended every later fill in CI once).
    client.fill_holes(v, f, skip_longest=True)
    seen = []
    client.fill_holes(v, f, skip_longest=True, progress=seen.append)
    # Budgets that end inside the holes phase (timing decides which do:
    # at least one must).
    stops = []
    for budget in holes_phase_budgets(seen):
        try:
            client.fill_holes(v, f, skip_longest=True, time_budget_ms=budget)
        except dot_client.FillStopped as stop:
            stops.append(stop)
        except dot_client.DotError as e:  # stopped before the holes
            assert e.code == grpc.StatusCode.DEADLINE_EXCEEDED, e
    assert stops, "no budget ended inside the holes phase"
    for stop in stops:
        assert stop.code == grpc.StatusCode.DEADLINE_EXCEEDED
        assert "time_budget_ms" in stop.message
        r = stop.result
        rep = r.report
        assert rep.stopped > 0 and not rep.closed
        assert rep.filled + rep.stopped == 100 and rep.skipped == 1
        assert sum(h.status == "stopped" for h in rep.holes) == rep.stopped
        assert len(r.vertices) == rep.input_vertices + rep.added_vertices
        assert len(r.faces) == rep.input_faces + rep.added_faces
        # Every hole not filled keeps its 64 border edges; the rim its own.
        assert len(border_edges(r.faces)) == 4 * 299 + 64 * rep.stopped

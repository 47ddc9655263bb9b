# SPDX-License-Identifier: AGPL-3.0-or-later
"""Client.surface_network against a real dot-server: curve networks into
surfaces (a cube's edges into a closed box, two rims into a tube by a
user cycle, an open box by skip_longest, welded end points), stages,
normals, the request stream, errors before and from the call, cancel."""
import threading

import grpc
import numpy as np
import pytest

import dot_client
from dot_client import wire
from dot_client._proto.dot.v1 import triangulation_pb2 as pb
from dot_client._proto.dot.v1 import triangulation_pb2_grpc as pb_grpc
from shapes import border_edges, directed_edges

CORNERS = np.array([(x, y, z) for x in (0.0, 1.0) for y in (0.0, 1.0)
                    for z in (0.0, 1.0)])
# The cube's 12 edges: corner pairs that differ in one coordinate.
CUBE_EDGES = [(a, b) for a in range(8) for b in range(a + 1, 8)
              if int(np.abs(CORNERS[a] - CORNERS[b]).sum()) == 1]


def cube_network(segments=4, shared_corners=True):
    """The unit cube's 12 edges as polylines of `segments` pieces: the 8
    corners are vertices 0..7, each edge's inner points follow. Without
    `shared_corners` every polyline has its own copies of its two corners
    (its points one after another), met only by equal coordinates."""
    vertices = [tuple(c) for c in CORNERS] if shared_corners else []
    lines = []
    for a, b in CUBE_EDGES:
        line = []
        for k in range(segments + 1):
            if shared_corners and k in (0, segments):
                line.append(a if k == 0 else b)
                continue
            t = k / segments
            line.append(len(vertices))
            vertices.append(tuple((1 - t) * CORNERS[a] + t * CORNERS[b]))
        lines.append(line)
    return np.array(vertices), lines


def rims(n=24):
    """Two circles of n points, radius 1, at heights 0 and 2, each a closed
    polyline (its first vertex repeated at its end)."""
    t = 2 * np.pi * np.arange(n) / n
    v = np.concatenate([np.c_[np.cos(t), np.sin(t), np.zeros(n)],
                        np.c_[np.cos(t), np.sin(t), np.full(n, 2.0)]])
    return v, [list(range(n)) + [0], list(range(n, 2 * n)) + [n]]


def edges_of(lines):
    return {frozenset((int(a), int(b))) for line in lines
            for a, b in zip(line, line[1:])}


def euler(faces):
    """V - E + F of the faces (V: the vertices they use)."""
    undirected = {frozenset(e) for e in directed_edges(faces)}
    return len(np.unique(faces)) - len(undirected) + len(faces)


def check_surface(result, vertices, lines, borders=0):
    """The contract: the network's vertices first, exactly; triangles
    consistently oriented (each directed edge once); every curve edge a
    mesh edge; `borders` border edges."""
    assert result.vertices.dtype == np.float64
    assert result.faces.dtype == np.int32 and result.faces.shape[1] == 3
    rep = result.report
    assert rep.input_vertices == len(vertices)
    assert rep.mesh_vertices == len(result.vertices)
    assert rep.mesh_faces == len(result.faces)
    assert np.array_equal(result.vertices[:len(vertices)], vertices)
    directed = [(int(t[i]), int(t[(i + 1) % 3])) for t in result.faces
                for i in range(3)]
    assert len(directed) == len(set(directed)), "a directed edge twice"
    mesh_edges = {frozenset(e) for e in directed}
    assert edges_of(lines) <= mesh_edges, "a curve edge is missing"
    assert len(border_edges(result.faces)) == borders
    assert rep.intersecting_pairs == 0


# -- against a server --------------------------------------------------------


def test_cube_edges_become_a_closed_box(client):
    v, lines = cube_network(4)
    seen = []
    r = client.surface_network(v, lines, progress=seen.append)
    assert isinstance(r, dot_client.SurfaceResult)
    check_surface(r, v, lines)
    rep = r.report
    assert isinstance(rep, dot_client.SurfaceReport) and rep.version == 1
    assert len(rep.curves) == 12 and rep.junctions == 8
    assert rep.merged_vertices == 0 and rep.dangling == []
    assert len(rep.patches) == 6 and rep.surfaced == 6 and rep.failed == 0
    assert rep.closed and rep.non_manifold_curves == 0 and rep.faired_whole
    assert euler(r.faces) == 2
    assert len(r.vertices) > len(v)  # refined
    for p in rep.patches:
        assert isinstance(p, dot_client.PatchReport)
        assert p.status == "surfaced" and p.reason == ""
        assert p.boundary_vertices == 16 and p.triangles > 0 and p.faired
        assert len(p.loops) == 1 and len(p.loops[0].curves) == 4
        assert len(p.loops[0].vertices) == 16
        assert {int(x) for x in p.loops[0].vertices} <= set(range(len(v)))
    assert sum(p.triangles for p in rep.patches) == len(r.faces)
    # Each curve in the report: 5 vertex ids from a corner to a corner.
    assert all(len(c) == 5 and c[0] < 8 and c[-1] < 8 for c in rep.curves)
    assert sorted(frozenset((int(c[0]), int(c[-1]))) for c in rep.curves) \
        == sorted(frozenset(e) for e in CUBE_EDGES)
    # Every curve is used twice, once each way.
    uses = [(u.curve, u.reversed) for p in rep.patches for u in
            p.loops[0].curves]
    assert sorted(uses) == sorted((c, w) for c in range(12)
                                  for w in (False, True))
    assert seen and all(isinstance(s, dot_client.SurfaceProgress)
                        for s in seen)
    assert all(s.patches_total == 6 for s in seen)
    done = [s.patches_done for s in seen]
    assert done == sorted(done) and done[-1] <= 6
    assert rep.to_dict()["patches"][0]["status"] == "surfaced"


def test_stages(client):
    v, lines = cube_network(4)
    tri = client.surface_network(v, lines, stage="triangulate")
    refined = client.surface_network(v, lines, stage="refine")
    faired = client.surface_network(v, lines)  # "fair", the default
    for r in (tri, refined, faired):
        check_surface(r, v, lines)
        assert r.report.closed and r.report.surfaced == 6
    assert len(tri.vertices) == len(v)  # the triangulate stage adds none
    assert not any(p.refined_vertices for p in tri.report.patches)
    assert len(refined.vertices) > len(v)
    assert len(faired.vertices) == len(refined.vertices)
    assert not refined.report.faired_whole and faired.report.faired_whole
    # The refined box keeps its flat faces; fairing moves the new vertices.
    on_faces = np.minimum(np.abs(refined.vertices),
                          np.abs(refined.vertices - 1)).min(axis=1)
    assert np.allclose(on_faces, 0, atol=1e-9)
    assert not np.array_equal(faired.vertices, refined.vertices)


def test_options_object_and_keywords(client):
    v, lines = cube_network(2)
    options = dot_client.SurfaceOptions(stage="refine", density=2,
                                        fairing_continuity=2)
    r = client.surface_network(v, lines, options=options,
                               weights="minimal_area", stage="triangulate")
    check_surface(r, v, lines)
    assert len(r.vertices) == len(v)  # the keyword replaced the stage
    r = client.surface_network(v, lines, squared_dihedral=1, area=0.1,
                               absolute_weights=True, time_budget_ms=60000)
    check_surface(r, v, lines)


def test_end_points_with_equal_coordinates_are_welded(client):
    v, lines = cube_network(3, shared_corners=False)
    r = client.surface_network(v, lines, stage="triangulate")
    rep = r.report
    # 24 polyline ends on 8 corners: 16 welded to the first copy.
    assert rep.merged_vertices == 16 and rep.junctions == 8
    assert rep.closed and rep.surfaced == 6
    assert np.array_equal(r.vertices[:len(v)], v)
    first = {}
    for i, p in enumerate(v.tolist()):
        first.setdefault(tuple(p), i)
    welded = [[first[tuple(v[i].tolist())] for i in line] for line in lines]
    check_surface(r, v, welded)
    used = set(np.unique(r.faces).tolist())
    assert not used & (set(range(len(v))) - set(first.values())), \
        "a welded copy is used"


def test_stroke_ends_that_nearly_meet_are_welded_when_asked(client):
    v, lines = cube_network(3, shared_corners=False)
    ends = sorted({line[0] for line in lines} | {line[-1] for line in lines})
    rng = np.random.default_rng(7)
    v = v.copy()
    v[ends] += rng.uniform(-0.003, 0.003, (len(ends), 3))  # a sketch's miss
    with pytest.raises(dot_client.DotError):  # every stroke dangles
        client.surface_network(v, lines, stage="triangulate")
    r = client.surface_network(v, lines, stage="triangulate",
                               weld_distance=0.02)
    assert r.report.merged_vertices == 16 and r.report.junctions == 8
    assert r.report.closed and r.report.surfaced == 6
    assert np.array_equal(r.vertices[:len(v)], v)  # every point as sent
    assert r.report.intersecting_pairs == 0


def test_user_cycles_join_two_rims_into_a_tube(client):
    v, lines = rims(24)
    # Alone, each closed rim bounds a disk.
    disks = client.surface_network(v, lines, stage="triangulate")
    assert disks.report.surfaced == 2 and not disks.report.closed
    assert euler(disks.faces) == 2  # two disks
    # One patch of two loops, the rims run against each other: a tube.
    bottom, top = list(range(24)), list(range(47, 23, -1))
    r = client.surface_network(v, lines, cycles=[[bottom, top]])
    check_surface(r, v, lines, borders=48)
    rep = r.report
    assert len(rep.patches) == 1 and rep.surfaced == 1, rep.patches
    assert len(rep.patches[0].loops) == 2
    assert rep.patches[0].boundary_vertices == 48
    assert euler(r.faces) == 0  # an annulus
    assert not rep.closed


def test_skip_longest_leaves_an_open_box(client):
    v, lines = cube_network(3)
    r = client.surface_network(v, lines, skip_longest=True,
                               stage="triangulate")
    check_surface(r, v, lines, borders=12)  # the open square's rim
    rep = r.report
    assert rep.surfaced == 5 and not rep.closed
    assert sorted(p.status for p in rep.patches) == ["skipped"] + \
        ["surfaced"] * 5


def test_a_circle_on_a_face_is_its_island_or_a_hole(client):
    v, lines = cube_network(3)
    n = 24
    t = 2 * np.pi * np.arange(n) / n
    circle = np.c_[0.5 + 0.3 * np.cos(t), 0.5 + 0.3 * np.sin(t), np.ones(n)]
    lines = lines + [list(range(len(v), len(v) + n)) + [len(v)]]
    v = np.concatenate([v, circle])
    inset = client.surface_network(v, lines)  # islands="inset", the default
    check_surface(inset, v, lines)
    rep = inset.report
    assert rep.closed and rep.surfaced == 7 and euler(inset.faces) == 2
    assert sorted(len(p.loops) for p in rep.patches) == [1] * 6 + [2]
    assert any("an island of it" in note for note in rep.notes)
    hole = client.surface_network(v, lines, islands="hole")
    check_surface(hole, v, lines, borders=n)
    assert not hole.report.closed and hole.report.surfaced == 6
    assert euler(hole.faces) == 1
    off = client.surface_network(v, lines, islands="off", stage="triangulate")
    assert [len(p.loops) for p in off.report.patches] == [1] * 7
    assert not off.report.closed


def test_walls_make_a_third_patch_only_when_asked(client):
    # Two unit cubes side by side: their 20 edges, the square x = 1 shared.
    corners = np.array([(x, y, z) for x in (0.0, 1.0, 2.0)
                        for y in (0.0, 1.0) for z in (0.0, 1.0)])
    lines = [[a, b] for a in range(12) for b in range(a + 1, 12)
             if np.abs(corners[a] - corners[b]).sum() == 1]
    assert len(lines) == 20
    box = client.surface_network(corners, lines, stage="triangulate")
    assert box.report.surfaced == 10 and box.report.closed
    assert box.report.non_manifold_curves == 0
    walls = client.surface_network(corners, lines, stage="triangulate",
                                   walls=True)
    assert walls.report.surfaced == 11 and walls.report.closed
    assert walls.report.non_manifold_curves == 4
    wall = walls.report.patches[-1]
    assert all(corners[v][0] == 1.0 for v in wall.loops[0].vertices)
    assert walls.report.intersecting_pairs == 0


def test_normals_travel_as_the_normal_channel(client):
    v, lines = cube_network(3)
    outward = v - 0.5
    outward /= np.linalg.norm(outward, axis=1)[:, None]
    r = client.surface_network(v, lines, normals=outward, stage="refine",
                               weights={"normal_deviation": 1, "area": 0.01})
    check_surface(r, v, lines)
    assert r.report.closed and r.report.surfaced == 6
    # One orientation for the whole box: every face out, or every face in.
    a, b, c = (r.vertices[r.faces[:, k]] for k in range(3))
    n = np.cross(b - a, c - a)
    side = np.sign(np.einsum("ij,ij->i", n, (a + b + c) / 3 - 0.5))
    assert abs(side.sum()) == len(side)


def test_server_refusals_name_the_problem(client):
    # A path bounds nothing.
    path = np.array([[0, 0, 0], [1, 0, 0], [2, 1, 0]], dtype=float)
    with pytest.raises(dot_client.DotError) as e:
        client.surface_network(path, [[0, 1, 2]])
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert "bounds no patch" in e.value.message
    assert not isinstance(e.value, dot_client.InvalidInput)  # the server's
    # Two curves that cross away from a vertex.
    square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    with pytest.raises(dot_client.DotError) as e:
        client.surface_network(square, [[0, 1, 2, 3, 0], [0, 2], [1, 3]])
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    # A user cycle whose vertices no curve joins.
    v, lines = cube_network(2)
    with pytest.raises(dot_client.DotError) as e:
        client.surface_network(v, lines, cycles=[[[0, 7, 3]]])
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert "no curve joins" in e.value.message


def test_the_server_names_an_out_of_range_polyline_index(server):
    # Past the client's own check, straight onto the wire.
    v, lines = cube_network(2)
    lines[1] = [lines[1][0], 99]
    requests = wire.surface_requests("bad", pb.SurfaceOptions(), v,
                                     [np.array(x) for x in lines])
    with grpc.insecure_channel(server.address) as channel:
        stub = pb_grpc.TriangulatorStub(channel)
        with pytest.raises(grpc.RpcError) as e:
            list(stub.SurfaceNetwork(requests, timeout=30))
    assert e.value.code() == grpc.StatusCode.INVALID_ARGUMENT
    assert "polyline 1 has vertex index 99" in e.value.details()


def test_timeout_cancel_and_progress_errors_cancel_the_call(server, client):
    v, lines = cube_network(4)
    with pytest.raises(dot_client.DotError) as e:
        client.surface_network(v, lines, timeout=0.001)
    assert e.value.code == grpc.StatusCode.DEADLINE_EXCEEDED
    token = dot_client.CancelToken()
    token.cancel()
    with pytest.raises(dot_client.DotError) as e:
        client.surface_network(v, lines, cancel=token)
    assert e.value.code == grpc.StatusCode.CANCELLED

    def stop(progress):
        raise KeyError("stop")
    with pytest.raises(KeyError):
        client.surface_network(v, lines, progress=stop)
    # A call cancelled while the server works on it.
    big_v, big_lines = cube_network(60)  # about 3 s of work
    token = dot_client.CancelToken()
    timer = threading.Timer(0.2, token.cancel)
    timer.start()
    try:
        with pytest.raises(dot_client.DotError) as e:
            client.surface_network(big_v, big_lines, cancel=token)
        assert e.value.code == grpc.StatusCode.CANCELLED
    finally:
        timer.cancel()
    assert server.alive()
    assert client.surface_network(v, lines, stage="triangulate").report.closed


# -- before any call ---------------------------------------------------------

CUBE_V, CUBE_LINES = cube_network(2)


@pytest.mark.parametrize("vertices, polylines, kwargs, words", [
    (CUBE_V, CUBE_LINES[:1] + [[0, 99]], {},
     "polyline 1 has vertex index 99, but there are only 20 vertices"),
    (CUBE_V, [[0, 1], [2, -1]], {}, "polyline 1 has vertex index -1"),
    (CUBE_V, [[0, 1, 2], [3]], {},
     "polyline 1 has 1 points; a polyline needs at least 2"),
    (CUBE_V, [], {}, "the network has no polylines"),
    (CUBE_V, np.zeros((0, 2), int), {}, "the network has no polylines"),
    (CUBE_V, np.array([[0], [1]]), {}, "polylines must have shape (P, k)"),
    (CUBE_V, [[0, 1], [0, 1.5, 2]], {},
     "polyline 1 must be a list of vertex indices"),
    (CUBE_V, [[0, 1.5]], {}, "polylines must be integer vertex indices"),
    (CUBE_V, "0 1", {}, "polylines must be"),
    (CUBE_V, None, {}, "polylines is missing"),
    (CUBE_V[:, :2], CUBE_LINES, {}, "vertices must have shape (n, 3)"),
    (np.where(np.arange(60).reshape(20, 3) == 4, np.nan, CUBE_V),
     CUBE_LINES, {}, "vertices[1]"),
    (CUBE_V, CUBE_LINES, {"normals": np.ones((3, 3))},
     "normals has 3 rows; expected one per vertex (20)"),
    (CUBE_V, CUBE_LINES, {"cycles": [[[0, 1, 50]]]},
     "cycles[0][0][2] = 50 is not a vertex of the network (it has 20)"),
    (CUBE_V, CUBE_LINES, {"cycles": [[0, 1, 2]]}, "cycles[0]"),
    (CUBE_V, CUBE_LINES, {"cycles": [[]]}, "cycles[0] has no loops"),
    (CUBE_V, CUBE_LINES, {"cycles": [[[]]]}, "cycles[0][0] has no vertices"),
    (CUBE_V, CUBE_LINES, {"cycles": [[[0, -1]]]}, "cycles[0][0][1]"),
    (CUBE_V, CUBE_LINES, {"stage": "paint"}, "stage must be one of"),
    (CUBE_V, CUBE_LINES, {"density": 500}, "density"),
    (CUBE_V, CUBE_LINES, {"fairing_continuity": 3}, "fairing_continuity"),
    (CUBE_V, CUBE_LINES, {"weights": {"area": 0}}, "every metric weight"),
    (CUBE_V, CUBE_LINES, {"weights": "shiny"}, "no weights preset"),
    (CUBE_V, CUBE_LINES, {"skip_longest": 1}, "skip_longest"),
    (CUBE_V, CUBE_LINES, {"islands": "auto"}, "islands must be one of"),
    (CUBE_V, CUBE_LINES, {"walls": "yes"}, "walls"),
    (CUBE_V, CUBE_LINES, {"weld_distance": -1}, "weld_distance"),
    (CUBE_V, CUBE_LINES, {"weld_distance": float("nan")}, "weld_distance"),
    (CUBE_V, CUBE_LINES, {"time_budget_ms": -1}, "time_budget_ms"),
])
def test_invalid_networks_are_refused_before_the_call(vertices, polylines,
                                                      kwargs, words):
    with dot_client.Client("127.0.0.1:1") as client:
        with pytest.raises(dot_client.InvalidInput) as e:
            client.surface_network(vertices, polylines, **kwargs)
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert words in e.value.message, e.value.message


def test_options_are_checked_when_made():
    o = dot_client.SurfaceOptions(cycles=[[np.arange(4), (5, 6, 7)]],
                                  stage="REFINE", density=2)
    assert o.cycles == ((((0, 1, 2, 3), (5, 6, 7)),))
    assert o.stage == "refine"
    m = o.to_proto()
    assert m.stage == pb.FILL_STAGE_REFINE and m.density == 2
    assert m.islands == pb.NETWORK_ISLANDS_INSET
    assert dot_client.SurfaceOptions(islands="HOLE").to_proto().islands == \
        pb.NETWORK_ISLANDS_HOLE
    assert [list(loop.vertices) for loop in m.cycles[0].loops] == \
        [[0, 1, 2, 3], [5, 6, 7]]
    assert not m.HasField("weights") and not m.HasField("fairing_continuity")
    m = dot_client.SurfaceOptions.merged(None, area=1,
                                         fairing_continuity=0).to_proto()
    assert m.weights.area == 1 and m.weights.squared_dihedral == 0
    assert m.HasField("fairing_continuity") and m.fairing_continuity == 0
    with pytest.raises(TypeError, match="no option max_hole_edges"):
        dot_client.SurfaceOptions.merged(None, max_hole_edges=3)


def test_surface_requests_slice_the_network():
    v = np.arange(30, dtype=float).reshape(10, 3)
    lines = [[0, 1], [1, 2, 3], [3, 4, 5, 6, 7, 0]]
    normals = np.ones((10, 3), dtype=np.float32)
    options = pb.SurfaceOptions(skip_longest=True)
    m = list(wire.surface_requests("net", options, v,
                                   [np.array(x) for x in lines],
                                   max_bytes=96,
                                   channels=[("normal", False, normals)]))
    assert m[0].id == "net" and m[0].options.skip_longest
    assert all(not x.id and not x.HasField("options") for x in m[1:])
    chunks = [x.network for x in m]
    assert [len(c.vertices) // 3 for c in chunks if c.vertices] == [4, 4, 2]
    faces = [c for c in chunks if c.triangles]
    assert [list(c.face_sizes) for c in faces] == [[2, 3, 6]]
    assert list(faces[0].triangles) == [i for x in lines for i in x]
    assert faces[0].first_vertex == 10
    normal = [c.attribute for c in chunks if c.HasField("attribute")]
    assert normal and all(a.name == "normal" and a.dims == 3 and
                          not a.per_corner for a in normal)
    assert sum(len(a.values) for a in normal) == 30
    # An (E, 2) array: one polyline per edge, face sizes 2.
    m = list(wire.surface_requests("", options, v, np.array([[0, 1], [1, 2]])))
    assert len(m) == 2 and list(m[1].network.face_sizes) == [2, 2]


def test_assemble_surface_checks_the_answer():
    v = np.eye(3)

    def response(**kw):
        return pb.SurfaceNetworkResponse(**kw)

    def report(vertices=4, faces=2):
        return response(report=pb.SurfaceReport(
            version=1, input_vertices=3, surfaced=1, mesh_vertices=vertices,
            mesh_faces=faces))
    mesh = [response(mesh=pb.MeshChunk(first_vertex=0,
                                       vertices=v.ravel().tolist() + [1, 1, 1])),
            response(mesh=pb.MeshChunk(first_vertex=4, first_triangle=0,
                                       triangles=[0, 1, 3, 1, 2, 3]))]
    seen = []
    r = wire.assemble_surface(
        [response(progress=pb.SurfaceProgress(patches_total=1))] + mesh +
        [report()], v, on_progress=seen.append)
    assert r.vertices.shape == (4, 3) and r.faces.tolist() == [[0, 1, 3],
                                                               [1, 2, 3]]
    assert r.report.surfaced == 1 and seen[0].patches_total == 1
    assert r.report.mesh_vertices == 4 and r.report.mesh_faces == 2
    with pytest.raises(dot_client.DotError, match="without a report"):
        wire.assemble_surface(mesh, v)
    with pytest.raises(dot_client.DotError, match="incomplete mesh: 4 "
                       "vertices and 2 triangles received, the server "
                       "announced 4 and 3"):
        wire.assemble_surface(mesh + [report(faces=3)], v)
    with pytest.raises(dot_client.DotError, match="refers to vertex 7"):
        wire.assemble_surface(
            [mesh[0], response(mesh=pb.MeshChunk(triangles=[0, 1, 7])),
             report(faces=1)], v)
    # The whole mesh comes back, the network's vertices too.
    with pytest.raises(dot_client.DotError, match="mesh starts at vertex 3"):
        wire.assemble_surface(
            [response(mesh=pb.MeshChunk(first_vertex=3, vertices=[1, 1, 1])),
             mesh[1], report()], v)
    with pytest.raises(dot_client.DotError, match="fewer vertices than the "
                       "network sent"):
        wire.assemble_surface(mesh + [report()], np.zeros((5, 3)))

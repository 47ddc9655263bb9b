# SPDX-License-Identifier: AGPL-3.0-or-later
"""The recorded response streams of tests/golden/ (scripts/record_golden.py)
reassembled by dot_client.wire give exactly the meshes and patches stored
beside them (computed by dotctl --local, no wire involved), and the
recorded FillHoles uploads are what dot_client.wire.fill_requests makes.
The C++ client replays the same files (tests/client/golden_stream_test.cc)."""
import json
import os

import grpc
import numpy as np
import pytest

import dot_client
from dot_client import wire
from dot_client._proto.dot.v1 import triangulation_pb2 as pb
from shapes import canonical

GOLDEN = os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "golden")


def load(name, message_type, kind="stream"):
    with open(os.path.join(GOLDEN, f"{name}.{kind}"), "rb") as f:
        messages = wire.read_length_prefixed(f, message_type)
    with open(os.path.join(GOLDEN, name + ".json")) as f:
        return messages, json.load(f)


def test_triangulate_stream():
    messages, doc = load("triangulate", pb.TriangulateResponse)
    assert [m.WhichOneof("payload") for m in messages] == doc["stream"]
    points = np.array(doc["request"]["points"])
    assert doc["request"]["options"]["omit_input_vertices"]
    progress = []
    r = wire.assemble_triangulate(messages, points, on_progress=progress.append)
    expected = doc["expected"]
    assert np.array_equal(r.vertices, np.array(expected["vertices"]))
    assert np.array_equal(r.triangles, np.array(expected["triangles"]))
    assert r.triangles.dtype == np.int32
    assert r.summary.inserted_count == expected["inserted_count"] > 0
    assert r.summary.loop.tolist() == expected["loop"]
    assert r.id == doc["request"]["id"]
    assert len(progress) == doc["stream"].count("progress")


def test_triangulate_loops_stream():
    messages, doc = load("triangulate_loops", pb.TriangulateResponse)
    assert [m.WhichOneof("payload") for m in messages] == doc["stream"]
    points = np.array(doc["request"]["points"])
    r = wire.assemble_triangulate(messages, points)
    expected = doc["expected"]
    assert np.array_equal(r.vertices, np.array(expected["vertices"]))
    assert np.array_equal(r.triangles, np.array(expected["triangles"]))
    assert r.summary.loop_sizes == expected["loop_sizes"] \
        == doc["request"]["loop_sizes"]
    assert r.summary.loop.tolist() == expected["loop"]
    assert r.summary.bridges.reshape(-1).tolist() == expected["bridges"]
    assert r.summary.bridges.shape == (2, 2)


def test_fill_holes_stream():
    messages, doc = load("fill_holes", pb.FillHolesResponse)
    assert [m.WhichOneof("payload") for m in messages] == doc["stream"]
    assert doc["stream"][-1] == "report"
    progress = []
    r = wire.assemble_fill(messages, on_progress=progress.append)
    expected = doc["expected"]
    assert np.array_equal(r.vertices, np.array(expected["vertices"]))
    assert np.array_equal(r.faces, np.array(expected["faces"]))
    for key in ("loops", "filled", "added_vertices", "added_faces", "closed"):
        assert getattr(r.report, key) == expected[key], key
    assert r.report.version == 2
    assert [h.status for h in r.report.holes] == ["filled"]
    hole = r.report.holes[0]
    assert len(hole.centroid) == 3 and hole.perimeter > 0 < hole.diameter
    assert progress and progress[-1].holes_done == 1
    chunks = [m.mesh for m in messages if m.HasField("mesh")]
    assert sum(1 for c in chunks if c.vertices) >= 2  # 1 KiB chunks
    assert sum(1 for c in chunks if c.triangles) >= 2


def fill_options(request):
    """The FillOptions message of a recorded request's "options"."""
    o = dict(request["options"])
    answer = o.pop("answer")
    return dot_client.FillOptions(**o).to_proto(answer)


@pytest.mark.parametrize("name", ["fill_holes", "fill_holes_patches"])
def test_the_recorded_upload_is_what_the_client_sends(name):
    # fill_requests made the FillHoles upload the stream answers, in
    # MeshChunk slices of upload_bytes; the first message carries id and
    # options.
    requests, doc = load(name, pb.FillHolesRequest, "requests")
    request = doc["request"]
    vertices = np.array(request["vertices"])
    faces = np.array(request["faces"])
    made = list(wire.fill_requests(request["id"], fill_options(request),
                                   vertices, faces,
                                   max_bytes=request["upload_bytes"]))
    assert made == requests
    assert requests[0].id == request["id"]
    assert requests[0].options == fill_options(request)
    assert all(not m.id and not m.HasField("options") for m in requests[1:])
    # Several slices of each kind, each starting where the last ended.
    slices = [m.mesh for m in requests]
    with_vertices = [c for c in slices if c.vertices]
    with_faces = [c for c in slices if c.triangles]
    assert len(with_vertices) >= 2 and len(with_faces) >= 2
    assert with_vertices + with_faces == slices  # vertices first
    at = 0
    for c in with_vertices:
        assert c.first_vertex == at
        at += len(c.vertices) // 3
    assert at == len(vertices)
    at = 0
    for c in with_faces:
        assert c.first_triangle == at and c.first_vertex == len(vertices)
        at += len(c.triangles) // 3
    assert at == len(faces)
    assert np.array_equal(
        np.concatenate([c.vertices for c in with_vertices]).reshape(-1, 3),
        vertices)
    assert np.array_equal(
        np.concatenate([c.triangles for c in with_faces]).reshape(-1, 3),
        faces)


def test_fill_holes_patches_stream():
    messages, doc = load("fill_holes_patches", pb.FillHolesResponse)
    assert [m.WhichOneof("payload") for m in messages] == doc["stream"]
    assert doc["stream"][-1] == "report" and "mesh" not in doc["stream"]
    assert doc["request"]["options"]["answer"] == "patches"
    expected = doc["expected"]
    progress = []
    r = wire.assemble_patches(messages, on_progress=progress.append)
    assert progress
    # One patch over several 1 KiB messages, each continuing the last.
    patch_messages = [m.patch for m in messages if m.HasField("patch")]
    assert len(patch_messages) >= 2
    assert len(r.patches) == len(expected["patches"]) == 1
    for got, want in zip(r.patches, expected["patches"]):
        assert got.hole == want["hole"]
        assert all(m.hole == want["hole"] for m in patch_messages)
        assert got.first_vertex == want["first_vertex"] == \
            len(doc["request"]["vertices"])
        assert np.array_equal(got.vertices, np.array(want["vertices"]))
        assert np.array_equal(got.faces, np.array(want["faces"]))
        assert got.faces.dtype == np.int32
        assert {k: v.tolist() for k, v in got.replaced_faces.items()} == \
            {x["face"]: x["triangles"] for x in want["replaced_faces"]}
        assert got.replaced_faces  # edge protection split a face
    for key in ("loops", "filled", "skipped", "added_vertices", "added_faces",
                "closed"):
        assert getattr(r.report, key) == expected[key], key
    names = {"HOLE_STATUS_FILLED": "filled", "HOLE_STATUS_SKIPPED": "skipped",
             "ESCALATION_PROTECTED_EDGES": "protected_edges",
             "ESCALATION_NONE": ""}
    assert [(h.id, h.status, h.escalation, h.split_faces)
            for h in r.report.holes] == [
        (h["id"], names[h["status"]], names[h["escalation"]],
         h["split_faces"]) for h in expected["holes"]]
    # The patches applied to the mesh as sent are dotctl's filled mesh.
    whole = expected["whole_mesh"]
    vertices, faces = r.apply(np.array(doc["request"]["vertices"]),
                              np.array(doc["request"]["faces"]))
    assert np.array_equal(vertices, np.array(whole["vertices"]))
    assert canonical(faces) == canonical(whole["faces"])


# Damaged copies of the recorded stream fail with the C++ client's words.

def triangulate_parts():
    messages, doc = load("triangulate", pb.TriangulateResponse)
    chunks = [m for m in messages if m.HasField("mesh")]
    summary = [m for m in messages if m.HasField("summary")]
    return chunks, summary, np.array(doc["request"]["points"])


def expect_loss(stream, points, words):
    with pytest.raises(dot_client.DotError) as e:
        wire.assemble_triangulate(stream, points)
    assert e.value.code == grpc.StatusCode.DATA_LOSS
    assert words in e.value.message


def test_damaged_triangulate_streams():
    chunks, summary, points = triangulate_parts()
    assert len(chunks) >= 3  # recorded with 1 KiB chunks
    expect_loss(chunks, points, "stream ended without a summary")
    expect_loss(chunks[:-1] + summary, points, "incomplete mesh")
    expect_loss(chunks + summary, points[:0], "input vertices are known")
    expect_loss(chunks[:1] + chunks + summary, points,
                "out of order: vertex")
    expect_loss(chunks[:1] + chunks[:0:-1] + summary, points,
                "out of order: triangle")


def test_damaged_fill_streams():
    messages, _ = load("fill_holes", pb.FillHolesResponse)
    with pytest.raises(dot_client.DotError) as e:
        wire.assemble_fill(messages[:-1])
    assert e.value.code == grpc.StatusCode.INTERNAL
    assert "without a report" in e.value.message
    no_faces = [m for m in messages if not (m.HasField("mesh") and
                                            len(m.mesh.triangles))]
    with pytest.raises(dot_client.DotError) as e:
        wire.assemble_fill(no_faces)
    assert e.value.message.startswith("bad mesh from the server: incomplete")


def test_damaged_patch_streams():
    messages, _ = load("fill_holes_patches", pb.FillHolesResponse)
    patches = [m for m in messages if m.HasField("patch")]
    report = [m for m in messages if m.HasField("report")]
    assert len(patches) >= 2 and len(report) == 1

    def refused(stream):
        with pytest.raises(dot_client.DotError) as e:
            wire.assemble_patches(stream)
        assert e.value.code == grpc.StatusCode.INTERNAL
        return e.value.message

    assert "without a report" in refused(patches)
    first = patches[0].patch
    assert refused(patches[:1] + patches + report) == (
        f"bad mesh from the server: the patch of hole 1 starts at vertex "
        f"{first.first_vertex}, not "
        f"{first.first_vertex + len(first.vertices) // 3}: it does not "
        f"continue where the last message ended")
    assert "does not continue" in refused(patches[:1] + patches[2:] + report)
    # Read as a mesh answer, a patches answer has no mesh (the report's
    # counts name one): refused, not an empty mesh.
    with pytest.raises(dot_client.DotError) as e:
        wire.assemble_fill(messages)
    assert e.value.message == ("bad mesh from the server: mesh starts at "
                               "vertex 161 but only 0 input vertices are "
                               "known")

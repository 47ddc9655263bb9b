# SPDX-License-Identifier: AGPL-3.0-or-later
"""The recorded response streams of tests/golden/ (scripts/record_golden.py)
reassembled by dot_client.wire give exactly the meshes stored beside them
(computed by dotctl --local, no wire involved). The C++ client replays the
same files (tests/client/golden_stream_test.cc)."""
import json
import os

import grpc
import numpy as np
import pytest

import dot_client
from dot_client import wire
from dot_client._proto.dot.v1 import triangulation_pb2 as pb

GOLDEN = os.path.join(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))), "golden")


def load(name, message_type):
    with open(os.path.join(GOLDEN, name + ".stream"), "rb") as f:
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
    assert progress and progress[-1].holes_done == 1
    chunks = [m.mesh for m in messages if m.HasField("mesh")]
    assert sum(1 for c in chunks if c.vertices) >= 2  # 1 KiB chunks
    assert sum(1 for c in chunks if c.triangles) >= 2


def test_the_recorded_request_is_what_the_client_sends():
    # fill_requests made the FillHoles request the stream answers; the
    # first message carries id and options.
    _, doc = load("fill_holes", pb.FillHolesResponse)
    requests = list(wire.fill_requests(
        doc["request"]["id"], pb.FillOptions(stage=pb.FILL_STAGE_FAIR),
        np.array(doc["request"]["vertices"]),
        np.array(doc["request"]["faces"])))
    assert requests[0].id == "golden-fill"
    assert requests[0].options.stage == pb.FILL_STAGE_FAIR
    assert len(requests) == 2  # the vertices, then the faces


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

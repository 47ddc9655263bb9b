# SPDX-License-Identifier: AGPL-3.0-or-later
"""dot_client.wire: the MeshAssembler's checks and the FillHoles request
stream, as proto/wire/wire.cc and fill_wire.cc make and check them."""
import io

import numpy as np
import pytest

from dot_client import wire
from dot_client._proto.dot.v1 import triangulation_pb2 as pb


def chunk(first_vertex=0, vertices=(), first_triangle=0, triangles=()):
    return pb.MeshChunk(first_vertex=first_vertex, vertices=list(vertices),
                        first_triangle=first_triangle,
                        triangles=list(triangles))


def test_assembles_across_chunks_with_the_input_put_back():
    a = wire.MeshAssembler()
    a.add(chunk(3, [9, 9, 9]))
    a.add(chunk(4, [8, 8, 8]))
    a.add(chunk(5, [], 0, [0, 1, 3, 1, 2, 3]))
    a.add(chunk(5, [], 2, [2, 0, 4, 0, 3, 4]))
    inp = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]])
    v, t = a.finish(5, 4, inp)
    assert v.shape == (5, 3) and np.array_equal(v[:3], inp)
    assert v[3].tolist() == [9, 9, 9] and v[4].tolist() == [8, 8, 8]
    assert t.dtype == np.int32 and t.shape == (4, 3)


def test_no_vertex_chunk_means_all_vertices_are_the_input():
    a = wire.MeshAssembler()
    a.add(chunk(3, [], 0, [0, 1, 2]))
    v, t = a.finish(3, 1, np.eye(3))
    assert np.array_equal(v, np.eye(3))


@pytest.mark.parametrize("chunks, words", [
    ([chunk(0, [1, 2])], "mesh chunk with a partial vertex or triangle"),
    ([chunk(0, [], 0, [1, 2])], "mesh chunk with a partial vertex or triangle"),
    ([chunk(0, [1, 2, 3]), chunk(2, [1, 2, 3])],
     "mesh chunk out of order: vertex 2 after 1"),
    ([chunk(0, [], 1, [0, 0, 0])],
     "mesh chunk out of order: triangle 1 after 0"),
])
def test_add_refuses(chunks, words):
    a = wire.MeshAssembler()
    with pytest.raises(wire.AssemblyError) as e:
        for c in chunks:
            a.add(c)
    assert str(e.value) == words


def test_finish_refuses():
    a = wire.MeshAssembler()
    a.add(chunk(0, [0, 0, 0, 1, 0, 0]))
    with pytest.raises(wire.AssemblyError, match="incomplete mesh: 2 vertices "
                       "and 0 triangles received, the server announced 3 "
                       "and 0"):
        a.finish(3, 0)
    a = wire.MeshAssembler()
    a.add(chunk(0, [0, 0, 0] * 3, 0, [0, 1, 7]))
    with pytest.raises(wire.AssemblyError,
                       match="mesh triangle refers to vertex 7"):
        a.finish(3, 1)
    a = wire.MeshAssembler()
    a.add(chunk(0, [0, 0, 0] * 3, 0, [0, 1, 2**32 - 1]))
    with pytest.raises(wire.AssemblyError,
                       match="mesh triangle refers to vertex -1"):
        a.finish(3, 1)
    a = wire.MeshAssembler()
    a.add(chunk(4, [0, 0, 0]))
    with pytest.raises(wire.AssemblyError, match="mesh starts at vertex 4 "
                       "but only 2 input vertices are known"):
        a.finish(5, 0, np.zeros((2, 3)))


def test_fill_requests_as_make_fill_requests():
    options = pb.FillOptions(stage=pb.FILL_STAGE_REFINE)
    v = np.arange(30, dtype=float).reshape(10, 3)
    f = np.array([[0, 1, 2]] * 7)
    # max_bytes 96: 4 vertices and 19 indices (6 faces) per message.
    m = list(wire.fill_requests("id", options, v, f, max_bytes=96))
    assert [len(x.vertices) // 3 for x in m] == [4, 4, 2, 0, 0]
    assert [len(x.faces) // 3 for x in m] == [0, 0, 0, 6, 1]
    assert m[0].id == "id" and m[0].options.stage == pb.FILL_STAGE_REFINE
    assert all(not x.id and not x.HasField("options") for x in m[1:])
    assert all(not x.face_sizes for x in m)
    assert np.array_equal(np.concatenate([x.vertices for x in m]), v.ravel())
    # Polygons: face sizes sent, a face never split across messages.
    polys = [[0, 1, 2, 3], [0, 1, 2], [4, 5, 6, 7, 8], [1, 2, 3, 4]]
    m = list(wire.fill_requests("id", options, v, polys, max_bytes=48))
    faces = [x for x in m if x.faces]
    assert [list(x.face_sizes) for x in faces] == [[4, 3], [5, 4]]
    quads = np.array([[0, 1, 2, 3]] * 5)
    m = list(wire.fill_requests("id", options, v, quads, max_bytes=48))
    faces = [x for x in m if x.faces]
    assert [list(x.face_sizes) for x in faces] == [[4, 4], [4, 4], [4]]


def test_length_prefixed_round_trip():
    messages = [pb.TriangulateResponse(id=str(i)) for i in range(3)]
    buf = io.BytesIO()
    wire.write_length_prefixed(buf, (m.SerializeToString() for m in messages))
    back = wire.read_length_prefixed(buf.getvalue(), pb.TriangulateResponse)
    assert [m.id for m in back] == ["0", "1", "2"]
    with pytest.raises(ValueError, match="truncated"):
        wire.read_length_prefixed(buf.getvalue()[:-1], pb.TriangulateResponse)

# SPDX-License-Identifier: AGPL-3.0-or-later
"""dot_client.wire: the MeshAssembler's and PatchReader's checks and the
FillHoles request stream, as proto/wire/wire.cc and fill_wire.cc make and
check them."""
import io

import numpy as np
import pytest

import dot_client
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


def test_fill_requests_as_fill_request_writer():
    options = pb.FillOptions(stage=pb.FILL_STAGE_REFINE)
    v = np.arange(30, dtype=float).reshape(10, 3)
    f = np.array([[0, 1, 2]] * 7)
    # max_bytes 96: 4 vertices and 19 indices (6 faces) per message.
    m = list(wire.fill_requests("id", options, v, f, max_bytes=96))
    assert [len(x.mesh.vertices) // 3 for x in m] == [4, 4, 2, 0, 0]
    assert [x.mesh.first_vertex for x in m] == [0, 4, 8, 10, 10]
    assert [len(x.mesh.triangles) // 3 for x in m] == [0, 0, 0, 6, 1]
    assert [x.mesh.first_triangle for x in m] == [0, 0, 0, 0, 6]
    assert m[0].id == "id" and m[0].options.stage == pb.FILL_STAGE_REFINE
    assert all(not x.id and not x.HasField("options") for x in m[1:])
    assert all(not x.mesh.face_sizes for x in m)
    assert np.array_equal(np.concatenate([x.mesh.vertices for x in m]),
                          v.ravel())
    # No field of revision 1 (vertices 3, faces 4, face_sizes 5) is set:
    # every message is id, options and mesh only.
    for x in m:
        assert {d.number for d, _ in x.ListFields()} <= {1, 2, 6}
    # Polygons: face sizes sent, a face never split across messages.
    polys = [[0, 1, 2, 3], [0, 1, 2], [4, 5, 6, 7, 8], [1, 2, 3, 4]]
    m = list(wire.fill_requests("id", options, v, polys, max_bytes=48))
    faces = [x.mesh for x in m if x.mesh.triangles]
    assert [list(x.face_sizes) for x in faces] == [[4, 3], [5, 4]]
    assert [x.first_triangle for x in faces] == [0, 2]
    assert all(x.first_vertex == 10 for x in faces)
    quads = np.array([[0, 1, 2, 3]] * 5)
    m = list(wire.fill_requests("id", options, v, quads, max_bytes=48))
    faces = [x.mesh for x in m if x.mesh.triangles]
    assert [list(x.face_sizes) for x in faces] == [[4, 4], [4, 4], [4]]
    assert [x.first_triangle for x in faces] == [0, 2, 4]
    # A polygon larger than a message still goes, alone.
    m = list(wire.fill_requests("id", options, v, [list(range(10))] * 2,
                                max_bytes=24))
    assert [list(x.mesh.face_sizes) for x in m if x.mesh.triangles] == \
        [[10], [10]]


def test_fill_requests_are_made_lazily():
    # Messages are made as the stream asks for them: the first (vertices)
    # does not touch the faces yet.
    touched = []

    class Faces(list):
        def __iter__(self):
            touched.append(True)
            return super().__iter__()

    v = np.zeros((1000, 3))
    requests = wire.fill_requests("id", pb.FillOptions(), v,
                                  Faces([[0, 1, 2], [0, 2, 3, 4]]),
                                  max_bytes=24)
    first = next(requests)
    assert first.id == "id" and len(first.mesh.vertices) == 3
    assert not touched
    rest = list(requests)
    assert touched and len(rest) == 999 + 2  # vertex slices, then faces


def patch(hole=0, first_vertex=10, vertices=(), faces=(), replaced=()):
    return pb.HolePatch(hole=hole, first_vertex=first_vertex,
                        vertices=list(vertices), faces=list(faces),
                        replaced_faces=[pb.ReplacedFace(face=f, triangles=t)
                                        for f, t in replaced])


def test_patch_reader_joins_continued_patches():
    r = wire.PatchReader()
    r.add(patch(4, 10, [1, 1, 1, 2, 2, 2], [0, 1, 10]))
    r.add(patch(4, 12, [3, 3, 3], [10, 11, 12], [(7, [0, 10, 2, 10, 1, 2])]))
    r.add(patch(6, 13, [], [5, 6, 7]))
    a, b = r.finish()
    assert (a.hole, a.first_vertex, b.hole, b.first_vertex) == (4, 10, 6, 13)
    assert a.vertices.tolist() == [[1, 1, 1], [2, 2, 2], [3, 3, 3]]
    assert a.faces.tolist() == [[0, 1, 10], [10, 11, 12]]
    assert a.faces.dtype == np.int32
    assert {k: t.tolist() for k, t in a.replaced_faces.items()} == \
        {7: [[0, 10, 2], [10, 1, 2]]}
    assert b.vertices.shape == (0, 3) and b.replaced_faces == {}


@pytest.mark.parametrize("messages, words", [
    ([patch(3, 10, [1, 2])],
     "a patch message of hole 3 has a partial vertex or triangle"),
    ([patch(3, 10, [], [1, 2])],
     "a patch message of hole 3 has a partial vertex or triangle"),
    ([patch(3, 10, [0, 0, 0]), patch(3, 10, [0, 0, 0])],
     "the patch of hole 3 starts at vertex 10, not 11: it does not continue "
     "where the last message ended"),
    ([patch(3, 10, [0, 0, 0]), patch(3, 12)],
     "the patch of hole 3 starts at vertex 12, not 11: it does not continue "
     "where the last message ended"),
    ([patch(3, 10, [0, 0, 0]), patch(5, 12)],
     "the patch of hole 5 starts at vertex 12, not 11: it does not continue "
     "where the last message ended"),
    ([patch(5, 10, [0, 0, 0]), patch(3, 11)],
     "the patch of hole 3 comes after hole 5's: patches come in hole order"),
    ([patch(3, 10, [0, 0, 0], [0, 1, 11])],
     "the patch of hole 3 names vertex 11, but only 11 exist"),
    ([patch(3, 10, [], [], [(5, [1, 2])])],
     "replaced face 5 has a partial triangle"),
])
def test_patch_reader_refuses(messages, words):
    r = wire.PatchReader()
    with pytest.raises(wire.AssemblyError) as e:
        for m in messages:
            r.add(m)
    assert str(e.value) == words


def test_patch_reader_checks_the_first_patch_against_the_upload():
    r = wire.PatchReader(sent_vertices=10)
    with pytest.raises(wire.AssemblyError) as e:
        r.add(patch(0, 999, [0, 0, 0]))
    assert str(e.value) == ("the patch of hole 0 starts at vertex 999, not "
                            "10: it does not continue where the last message "
                            "ended")


def test_assemble_patches_needs_a_report():
    stream = [pb.FillHolesResponse(patch=patch(0, 3, [0, 0, 0], [0, 1, 3]))]
    with pytest.raises(dot_client.DotError, match="without a report"):
        wire.assemble_patches(stream)
    stream.append(pb.FillHolesResponse(report=pb.FillReport(version=2)))
    (p,) = wire.assemble_patches(stream).patches
    assert p.faces.tolist() == [[0, 1, 3]]
    bad = [pb.FillHolesResponse(patch=patch(0, 3, [0, 0])), stream[-1]]
    with pytest.raises(dot_client.DotError) as e:
        wire.assemble_patches(bad)
    assert e.value.message == ("bad mesh from the server: a patch message of "
                               "hole 0 has a partial vertex or triangle")


def test_length_prefixed_round_trip():
    messages = [pb.TriangulateResponse(id=str(i)) for i in range(3)]
    buf = io.BytesIO()
    wire.write_length_prefixed(buf, (m.SerializeToString() for m in messages))
    back = wire.read_length_prefixed(buf.getvalue(), pb.TriangulateResponse)
    assert [m.id for m in back] == ["0", "1", "2"]
    with pytest.raises(ValueError, match="truncated"):
        wire.read_length_prefixed(buf.getvalue()[:-1], pb.TriangulateResponse)

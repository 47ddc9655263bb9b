# SPDX-License-Identifier: AGPL-3.0-or-later
"""Client.fill_patches (FillHoles answering FILL_ANSWER_PATCHES) against a
real dot-server: the patches, applied to the mesh as sent, rebuild the
whole-mesh answer; duplicates the server merged are named by their first
copy; large patches continue over several messages."""
import numpy as np
import pytest

import dot_client
from dot_client import wire
from dot_client._proto.dot.v1 import triangulation_pb2 as pb
from conftest import Server
from shapes import (border_edges, box_with_hole, bumpy_grid_with_hole,
                    canonical, grid_with_hole, grid_with_holes,
                    merge_coincident)


def check_numbering(patches, sent_vertices):
    """New vertices numbered on from the sent mesh, patch after patch; new
    faces over ids that exist."""
    at = sent_vertices
    for p in patches:
        assert p.first_vertex == at
        assert p.vertices.dtype == np.float64 and p.vertices.shape[1] == 3
        assert p.faces.dtype == np.int32 and p.faces.shape[1] == 3
        at += len(p.vertices)
    for p in patches:
        assert p.faces.min() >= 0 and p.faces.max() < at


@pytest.mark.parametrize("stage", ["triangulate", "refine", "fair"])
@pytest.mark.parametrize("no_repair", [False, True])
def test_patches_rebuild_the_whole_mesh_answer(client, stage, no_repair):
    # A clean triangle mesh whose hole needs edge protection (a face beside
    # it is split), and one with three plain holes.
    for v, f, skip in (bumpy_grid_with_hole() + (True,),
                       grid_with_holes(16, [(2, 4, 2, 4), (9, 13, 5, 8)])
                       + (True,)):
        whole = client.fill_holes(v, f, stage=stage, skip_longest=skip,
                                  no_repair=no_repair)
        answer = client.fill_patches(v, f, stage=stage, skip_longest=skip,
                                     no_repair=no_repair)
        assert isinstance(answer, dot_client.FillPatches)
        filled = [h.id for h in whole.report.holes if h.status == "filled"]
        assert [p.hole for p in answer.patches] == filled
        assert answer.report.filled == whole.report.filled == len(filled) > 0
        check_numbering(answer.patches, len(v))
        split = {h.id: h.split_faces for h in whole.report.holes}
        for p in answer.patches:
            assert sorted(p.replaced_faces) == sorted(split[p.hole])
        vertices, faces = answer.apply(v, f)
        assert np.array_equal(vertices, whole.vertices)
        assert faces.dtype == np.int32
        assert canonical(faces) == canonical(whole.faces)
        # A face that was not replaced keeps its index, as in the mesh
        # answer (split faces are replaced in place there by their first
        # piece).
        assert np.array_equal(faces[:len(f)], whole.faces[:len(f)])


def test_replaced_faces_of_edge_protection(client):
    v, f = bumpy_grid_with_hole()
    answer = client.fill_patches(v, f, stage="triangulate", skip_longest=True)
    (patch,) = answer.patches
    assert list(patch.replaced_faces) == [105]
    pieces = patch.replaced_faces[105]
    assert pieces.dtype == np.int32 and pieces.shape == (2, 3)
    # The inserted vertex is the patch's one new vertex; the two pieces
    # share it and together keep face 105's corners.
    assert len(patch.vertices) == 1 and patch.first_vertex == len(v)
    assert all(len(v) in t for t in pieces.tolist())
    assert set(pieces.ravel()) - {len(v)} == set(f[105])
    vertices, faces = answer.apply(v, f)
    assert sorted(border_edges(faces)) == sorted(border_edges(
        client.fill_holes(v, f, stage="triangulate",
                          skip_longest=True).faces))


def test_duplicates_and_quads_are_named_as_sent(client):
    # Every quad with its own four vertices, as an STL export: the server
    # merges them, and the patch names each merged vertex by its first
    # copy.
    v, quads = box_with_hole()
    soup_v = v[quads.ravel()]
    soup_f = np.arange(len(soup_v)).reshape(-1, 4)
    answer = client.fill_patches(soup_v, soup_f, stage="fair")
    rep = answer.report
    assert rep.filled == 1 and rep.closed
    assert rep.repair.merged_vertices == len(soup_v) - len(v)
    assert rep.repair.triangulated_polygons == len(soup_f)
    check_numbering(answer.patches, len(soup_v))
    first_copy = {}
    for i, p in enumerate(soup_v.tolist()):
        first_copy.setdefault(tuple(p), i)
    for p in answer.patches:
        for i in p.faces.ravel():
            if i < len(soup_v):
                assert i == first_copy[tuple(soup_v[i])]
    vertices, faces = answer.apply(soup_v, soup_f)
    assert isinstance(faces, list)  # quads and triangles
    assert len(faces) == len(soup_f) + rep.added_faces
    assert len(border_edges(faces)) > 0  # the soup's seams are still split
    merged = merge_coincident(vertices, faces)
    assert border_edges(merged) == []  # closed, consistently wound


def test_loops_through_patches(client):
    v, f = grid_with_holes(16, [(2, 4, 2, 4), (2, 4, 10, 13), (9, 13, 5, 8)])
    answer = client.fill_patches(
        v, f, options=dot_client.FillOptions(stage="refine",
                                             loops_through=(2 * 16 + 3,)))
    assert answer.report.filled == 1 and answer.report.skipped == 3
    (patch,) = answer.patches
    hole = [h for h in answer.report.holes if h.id == patch.hole][0]
    assert hole.boundary_vertices == 8
    touched = {int(i) for i in patch.faces.ravel() if i < len(v)}
    assert 2 * 16 + 3 in touched and len(touched) == 8
    _, faces = answer.apply(v, f)
    assert len(border_edges(faces)) == len(border_edges(f)) - 8


@pytest.fixture(scope="module")
def small_chunks():
    """A server that answers in 1 KiB messages."""
    s = Server("--chunk-kb", "1")
    yield s
    s.stop()


def test_a_large_patch_continues_over_messages(client, small_chunks):
    v, f = grid_with_hole(30, slice(8, 20))
    options = dot_client.FillOptions(stage="fair", skip_longest=True)
    with dot_client.Client(small_chunks.address, timeout=60) as small:
        requests = wire.fill_requests("big", options.to_proto("patches"), v, f)
        messages = list(small._stub.FillHoles(requests, timeout=60))
        answer = small.fill_patches(v, f, options=options)
    patch_messages = [m.patch for m in messages if m.HasField("patch")]
    assert len(patch_messages) >= 3
    assert len({m.hole for m in patch_messages}) == 1
    assert all(m.id == "big" for m in messages)
    assert not any(m.HasField("mesh") for m in messages)
    # Each message continues the last: first_vertex moves on by the
    # vertices already sent.
    at = patch_messages[0].first_vertex
    for m in patch_messages:
        assert m.first_vertex == at
        at += len(m.vertices) // 3
    replayed = wire.assemble_patches(messages)
    (patch,) = replayed.patches
    assert np.array_equal(patch.vertices, answer.patches[0].vertices)
    assert np.array_equal(patch.faces, answer.patches[0].faces)
    whole = client.fill_holes(v, f, options=options)
    vertices, faces = replayed.apply(v, f)
    assert np.array_equal(vertices, whole.vertices)
    assert canonical(faces) == canonical(whole.faces)


def test_apply_refuses_patches_of_another_mesh(client):
    v, f = grid_with_hole(12)
    answer = client.fill_patches(v, f, stage="refine", skip_longest=True)
    assert answer.patches[0].vertices.size > 0
    with pytest.raises(ValueError, match="starts at vertex 144, but 143 "
                       "vertices precede it"):
        answer.apply(v[:-1], f[f.max(axis=1) < 143])
    with pytest.raises(ValueError, match="replaces face 3, but the mesh has 2"):
        dot_client.FillPatches(
            [dot_client.HolePatch(0, 4, np.zeros((0, 3)),
                                  np.zeros((0, 3), np.int32),
                                  {3: np.array([[0, 1, 2]], np.int32)})],
            answer.report).apply(np.eye(4)[:, :3], [[0, 1, 2], [1, 2, 3]])
    with pytest.raises(ValueError, match="refers to vertex 9, but the mesh "
                       "with the patches has 4 vertices"):
        dot_client.FillPatches(
            [dot_client.HolePatch(0, 4, np.zeros((0, 3)),
                                  np.array([[0, 1, 9]], np.int32))],
            answer.report).apply(np.eye(4)[:, :3], [[0, 1, 2], [1, 2, 3]])


def test_the_request_asks_for_patches():
    v, f = grid_with_hole(8)
    requests = list(wire.fill_requests(
        "", dot_client.FillOptions(loops_through=[3]).to_proto("patches"),
        v, f))
    assert requests[0].options.answer == pb.FILL_ANSWER_PATCHES
    assert list(requests[0].options.loops_through) == [3]
    assert dot_client.FillOptions().to_proto().answer == pb.FILL_ANSWER_MESH

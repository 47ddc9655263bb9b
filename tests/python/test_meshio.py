# SPDX-License-Identifier: AGPL-3.0-or-later
"""meshio meshes through a real dot-server: fill_holes(meshio.Mesh) gives
a meshio.Mesh back (OFF, PLY, OBJ and VTU files written and read again),
the mesh as read with the patches added, point data interpolated into the
new points, cell data kept and defaulted, faces split by edge protection
replaced (in place in triangle blocks, removed from quad blocks), sets
kept, duplicate points named as the mesh uses them (welded where a rim
crosses a seam); a stopped fill's partial mesh; read_mesh; list_holes of
a mesh; bad meshes refused before the call; and dot_client without
meshio."""
import os
import subprocess
import sys

import grpc
import numpy as np
import pytest

import dot_client
from shapes import (border_edges, box_with_hole, bumpy_grid_with_hole,
                    grid_with_hole)

meshio = pytest.importorskip("meshio")


def linear(points: np.ndarray) -> np.ndarray:
    """Colours on a 0..255 scale that follow the position on the 16 x 16
    grid (harmonic interpolation on a flat patch keeps them)."""
    return np.c_[points[:, 0] / 15 * 255, points[:, 1] / 15 * 255,
                 np.full(len(points), 128.0)]


def surface(mesh) -> list:
    """Every surface cell of a meshio mesh, block after block."""
    return [list(c) for b in mesh.cells if b.type in ("triangle", "quad",
                                                      "polygon")
            for c in b.data.tolist()]


def rim(n: int = 16) -> list:
    """The border edges of the n x n grid's outer rim (left open by
    skip_longest)."""
    v, f = grid_with_hole(n, slice(0, 0))
    return sorted(border_edges(f))


def test_ply_round_trip_carries_colours_and_normals(client, tmp_path):
    v, f = grid_with_hole(16)
    rgb = np.rint(linear(v)).astype(np.uint8)
    original = meshio.Mesh(v, [("triangle", f)], point_data={
        "nx": np.zeros(len(v)), "ny": np.zeros(len(v)), "nz": np.ones(len(v)),
        "red": rgb[:, 0], "green": rgb[:, 1], "blue": rgb[:, 2]})
    original.write(tmp_path / "scan.ply")
    mesh = meshio.read(tmp_path / "scan.ply")

    filled = client.fill_holes(mesh, skip_longest=True)
    assert isinstance(filled, meshio.Mesh)
    assert isinstance(filled, dot_client.FilledMesh)
    assert filled.report.filled == 1 and filled.report.notes == []
    added = len(filled.points) - len(v)
    assert added == filled.report.added_vertices > 0
    # The mesh as read, then what the fill adds: only the rim stays open.
    assert np.array_equal(filled.points[:len(v)], v)
    (block,) = filled.cells
    assert block.type == "triangle"
    assert np.array_equal(block.data[:len(f)], f)
    assert len(block.data) == len(f) + filled.report.added_faces
    assert sorted(border_edges(block.data)) == rim()

    filled.write(tmp_path / "closed.ply")
    back = meshio.read(tmp_path / "closed.ply")
    assert np.array_equal(back.points, filled.points)
    for key in ("red", "green", "blue"):
        assert back.point_data[key].dtype == np.uint8
        assert np.array_equal(back.point_data[key][:len(v)],
                              mesh.point_data[key])
    new = back.points[len(v):]
    got = np.c_[[back.point_data[k][len(v):] for k in ("red", "green",
                                                       "blue")]].T
    assert np.abs(got - linear(new)).max() <= 1.0  # rounded to bytes
    # "nx ny nz" travel as the service's normal channel: the patch's own
    # unit normals (the flat grid's +z).
    normals = np.c_[[back.point_data[k][len(v):] for k in ("nx", "ny",
                                                           "nz")]].T
    np.testing.assert_allclose(normals, np.tile([0, 0, 1], (added, 1)),
                               atol=1e-6)


def test_vtu_round_trip_keeps_cell_data_and_point_data_dtypes(client,
                                                              tmp_path):
    v, f = grid_with_hole(16)
    lines = np.array([[0, 1], [1, 2]])
    velocity = np.c_[v[:, 0], -v[:, 1], np.zeros(len(v))]
    mesh = meshio.Mesh(
        v, [("line", lines), ("triangle", f)],
        point_data={"temperature": v[:, 0] * 2.0 + 1.0,
                    "velocity": velocity,
                    "label": np.arange(len(v), dtype=np.int32)},
        cell_data={"material": [np.array([7, 7], dtype=np.int32),
                                np.arange(len(f), dtype=np.int32) % 4]})
    mesh.write(tmp_path / "part.vtu")
    read = meshio.read(tmp_path / "part.vtu")
    # What VTU cannot hold, added in memory: booleans, sets.
    read.point_data["seed"] = np.zeros(len(v), dtype=bool)
    read.point_sets = {"corner": np.array([0])}
    read.cell_sets = {"first": [np.array([0]), np.array([0, 1])]}

    filled = client.fill_holes(read, skip_longest=True, stage="refine")
    added = len(filled.points) - len(v)
    new_faces = filled.report.added_faces
    assert added > 0 and new_faces > 0
    # Blocks, in order; the line block untouched, the triangles appended.
    assert [b.type for b in filled.cells] == ["line", "triangle"]
    assert np.array_equal(filled.cells[0].data, lines)
    assert len(filled.cells[1].data) == len(f) + new_faces
    # Point data: the mesh's rows exact, the new points interpolated
    # (a linear field on a flat patch: exact in single precision), dtypes
    # kept; what the service cannot carry (booleans) is zero and noted.
    pd = filled.point_data
    assert pd["temperature"].dtype == np.float64
    np.testing.assert_allclose(pd["temperature"],
                               filled.points[:, 0] * 2 + 1, rtol=1e-5)
    np.testing.assert_allclose(pd["velocity"][len(v):, :2],
                               filled.points[len(v):, :2] * [1, -1],
                               atol=1e-4)
    assert pd["label"].dtype == np.int32
    assert np.array_equal(pd["label"][:len(v)], np.arange(len(v)))
    assert pd["label"][len(v):].min() >= 0  # blended from the rim's
    assert pd["seed"].dtype == bool and not pd["seed"].any()
    assert any("'seed'" in n and "not carried" in n
               for n in filled.report.notes)
    # Cell data: each cell keeps its row; new triangles get zeros (noted).
    material = filled.cell_data["material"]
    assert np.array_equal(material[0], [7, 7])
    assert np.array_equal(material[1][:len(f)], np.arange(len(f)) % 4)
    assert not material[1][len(f):].any()
    assert any("'material'" in n for n in filled.report.notes)
    # Sets unchanged; the file round trip keeps everything.
    assert np.array_equal(filled.point_sets["corner"], [0])
    assert [s.tolist() for s in filled.cell_sets["first"]] == [[0], [0, 1]]
    del filled.point_data["seed"]
    filled.point_sets, filled.cell_sets = {}, {}
    filled.write(tmp_path / "closed.vtu")
    back = meshio.read(tmp_path / "closed.vtu")
    assert np.array_equal(back.points, filled.points)
    assert np.array_equal(back.cells[1].data, filled.cells[1].data)
    assert np.array_equal(back.cell_data["material"][1], material[1])


def test_off_and_obj_files(client, tmp_path):
    v, f = grid_with_hole(16)
    meshio.Mesh(v, [("triangle", f)]).write(tmp_path / "grid.off")
    filled = client.fill_holes(meshio.read(tmp_path / "grid.off"),
                               skip_longest=True)
    filled.write(tmp_path / "closed.off")
    back = meshio.read(tmp_path / "closed.off")
    assert sorted(border_edges(back.cells[0].data)) == rim()
    np.testing.assert_allclose(back.points, filled.points)

    # OBJ: "obj:vn" travels as normals, "obj:vt" (UVs per point) is
    # blended; the group ids (cell data) of new triangles are 0.
    uv = v[:, :2] / 15
    obj = meshio.Mesh(v, [("triangle", f)],
                      point_data={"obj:vn": np.tile([0.0, 0, 1], (len(v), 1)),
                                  "obj:vt": uv})
    obj.write(tmp_path / "grid.obj")
    read = meshio.read(tmp_path / "grid.obj")
    filled = client.fill_holes(read, skip_longest=True)
    new = filled.points[len(v):]
    np.testing.assert_allclose(filled.point_data["obj:vt"][len(v):],
                               new[:, :2] / 15, atol=1e-5)
    np.testing.assert_allclose(filled.point_data["obj:vn"][len(v):],
                               np.tile([0, 0, 1], (len(new), 1)), atol=1e-6)
    filled.write(tmp_path / "closed.obj")
    assert len(meshio.read(tmp_path / "closed.obj").points) == \
        len(filled.points)


def test_a_split_triangle_is_replaced_in_place(client):
    """Edge protection splits face 105 of the bumpy grid: its first piece
    takes its place (its cell data, its sets), the other is appended with
    the same data, then the patch's triangles with zeros."""
    v, f = bumpy_grid_with_hole()
    ids = np.arange(len(f), dtype=np.int64) + 1000
    mesh = meshio.Mesh(v, [("triangle", f)], cell_data={"id": [ids]},
                       cell_sets={"split": [np.array([3, 105])]})
    filled = client.fill_holes(mesh, stage="triangulate", skip_longest=True)
    (hole,) = [h for h in filled.report.holes if h.status == "filled"]
    assert hole.split_faces == [105]
    triangles = filled.cells[0].data
    assert len(triangles) == len(f) + filled.report.added_faces
    assert np.array_equal(np.delete(triangles[:len(f)], 105, axis=0),
                          np.delete(f, 105, axis=0))
    assert len(v) in triangles[105]  # the inserted vertex
    data = filled.cell_data["id"][0]
    assert np.array_equal(data[:len(f)], ids)
    assert data[len(f)] == 1105  # the second piece
    assert not data[len(f) + 1:].any()
    assert filled.cell_sets["split"][0].tolist() == [3, 105, len(f)]
    assert sorted(border_edges(triangles)) == sorted(border_edges(
        client.fill_holes(v, f, stage="triangulate",
                          skip_longest=True).faces))


def test_a_split_quad_is_removed_and_its_pieces_appended(client):
    """The same grid as quads: the split quad leaves its block (the later
    quads move up, their data and sets with them) and its pieces join the
    new triangle block with its data."""
    v, f = bumpy_grid_with_hole()
    quads = np.c_[f[:len(f) // 2, :2], f[:len(f) // 2, 2],
                  f[len(f) // 2:, 2]]
    mesh = meshio.Mesh(v, [("quad", quads)],
                       cell_data={"id": [np.arange(len(quads)) + 1000]},
                       cell_sets={"some": [np.array([10, 40, 70])]})
    r = client.fill_holes(mesh, stage="triangulate", skip_longest=True)
    (hole,) = [h for h in r.report.holes if h.status == "filled"]
    assert hole.escalation == "protected_edges"
    # (split_faces counts the repaired mesh's triangles; quad 40 holds
    # triangle 105.)
    assert [b.type for b in r.cells] == ["quad", "triangle"]
    assert np.array_equal(r.cells[0].data, np.delete(quads, 40, axis=0))
    assert np.array_equal(r.cell_data["id"][0],
                          np.delete(np.arange(len(quads)), 40) + 1000)
    pieces = r.cell_data["id"][1]
    assert pieces.tolist() == [1040] * 3 + [0] * (len(pieces) - 3)
    assert len(v) in r.cells[1].data[:3]  # around the inserted vertex
    assert r.cell_sets["some"][0].tolist() == [10, 69]
    assert r.cell_sets["some"][1].tolist() == [0, 1, 2]
    assert sorted(border_edges(surface(r))) == rim(10)


def test_quads_stay_quads_and_facet_normals_are_computed(client):
    v, quads = box_with_hole()
    mesh = meshio.Mesh(v, [("quad", quads)])
    filled = client.fill_holes(mesh)
    assert filled.report.filled == 1
    assert [b.type for b in filled.cells] == ["quad", "triangle"]
    assert np.array_equal(filled.cells[0].data, quads)
    assert border_edges(surface(filled)) == []

    # STL: meshio merges its points and calls the facets' normals
    # "facet_normals": new triangles get theirs.
    tris = np.concatenate([quads[:, :3], quads[:, [0, 2, 3]]])
    stl = meshio.Mesh(v, [("triangle", tris)],
                      cell_data={"facet_normals": [np.zeros((len(tris), 3))]})
    filled = client.fill_holes(stl)
    normals = filled.cell_data["facet_normals"][0][len(tris):]
    np.testing.assert_allclose(normals, np.tile([0, 0, 1], (len(normals), 1)),
                               atol=1e-9)
    assert filled.report.notes == []


def test_a_stopped_fill_gives_the_mesh_of_the_holes_it_finished(
        client, monkeypatch):
    """FillStopped's result is a FilledMesh too. (The stop is simulated:
    the answer of a whole fill raised as a stop's partial answer; the
    server's stops are test_fill_holes'.)"""
    v, f = grid_with_hole(16)
    real = dot_client.Client._fill

    def stopped(self, *args, **kwargs):
        answer = real(self, *args, **kwargs)
        raise dot_client.FillStopped(grpc.StatusCode.DEADLINE_EXCEEDED,
                                     "time_budget_ms passed", answer)

    monkeypatch.setattr(dot_client.Client, "_fill", stopped)
    with pytest.raises(dot_client.FillStopped) as e:
        client.fill_holes(meshio.Mesh(v, [("triangle", f)]),
                          skip_longest=True)
    assert e.value.code == grpc.StatusCode.DEADLINE_EXCEEDED
    partial = e.value.result
    assert isinstance(partial, dot_client.FilledMesh)
    assert partial.report.filled == 1
    assert sorted(border_edges(partial.cells[0].data)) == rim()


def test_duplicate_points_are_named_as_the_faces_around_the_hole_use_them(
        client):
    """The server merges points at the same place and names them by their
    first copy; a hole whose rim uses other copies closes against those,
    with nothing welded."""
    v, f = grid_with_hole(16)
    rim_points = np.unique(np.array(border_edges(f)).ravel())
    copies = np.arange(len(v), len(v) + len(rim_points))
    lookup = np.arange(len(v))
    lookup[rim_points] = copies  # the faces use the copies, not the first
    mesh = meshio.Mesh(np.concatenate([v, v[rim_points]]),
                       [("triangle", lookup[f])])
    filled = client.fill_holes(mesh, skip_longest=True)
    assert filled.report.filled == 1 and filled.report.notes == []
    triangles = filled.cells[0].data
    assert np.array_equal(triangles[:len(f)], lookup[f])
    assert not np.isin(triangles, rim_points).any()
    assert len(border_edges(triangles)) == 60  # the outer rim


def test_a_seam_across_a_hole_is_welded_where_the_rim_crosses_it(client):
    """Points split along a seam (x = 8: the faces right of it use
    copies, with their own UVs) that crosses the hole: where the rim meets
    both copies of a point the hole can only close if they are one, so
    the two are welded (and said so); elsewhere the seam stays."""
    v, f = grid_with_hole(16)
    seam = np.flatnonzero(v[:, 0] == 8)
    copies = np.arange(len(v), len(v) + len(seam))
    right = f.copy()
    lookup = np.arange(len(v))
    lookup[seam] = copies
    east = (v[f][:, :, 0] > 8).any(axis=1)
    right[east] = lookup[f[east]]
    points = np.concatenate([v, v[seam]])
    uv = np.c_[points[:, 0] / 15, points[:, 1] / 15]
    uv[len(v):, 0] += 1  # the other chart
    mesh = meshio.Mesh(points, [("triangle", right)],
                       point_data={"uv": uv})
    filled = client.fill_holes(mesh, skip_longest=True)
    assert filled.report.filled == 1
    triangles = filled.cells[0].data

    def on_hole(edge):  # an edge of the 4 x 4 hole's square rim
        (xa, ya, _), (xb, yb, _) = points[list(edge)]
        inside = 6 <= min(xa, xb, ya, yb) and max(xa, xb, ya, yb) <= 10
        return inside and ((xa == xb and xa in (6, 10)) or
                           (ya == yb and ya in (6, 10)))

    # The hole is closed; the outer rim and the seam's two sides (a cut
    # in the mesh as sent, 11 edges each) stay open.
    def where(edges):  # edges as the places they join (welds rename)
        return sorted(tuple(map(tuple, filled.points[list(e)].tolist()))
                      for e in edges)

    after = border_edges(triangles)
    assert where(after) == where(e for e in border_edges(right)
                                 if not on_hole(e))
    assert len(after) == 60 + 2 * 11
    (note,) = filled.report.notes
    assert note.startswith("2 duplicate points welded")
    welded = [x for x in copies if x in right and x not in triangles]
    assert len(welded) == 2  # where the rim crosses the seam
    assert sorted(v[seam[np.isin(copies, welded)], 1].tolist()) == [6, 10]
    assert np.array_equal(filled.point_data["uv"][:len(points)], uv)


def test_read_mesh_raises_where_meshio_would_exit(tmp_path, capsys):
    v, f = grid_with_hole(8)
    meshio.Mesh(v, [("triangle", f)]).write(tmp_path / "good.off")
    mesh = dot_client.read_mesh(tmp_path / "good.off")
    assert np.array_equal(mesh.cells[0].data, f)
    (tmp_path / "junk.ply").write_text("nonsense\n")
    (tmp_path / "spaces.off").write_text("OFF\n4  4 0\n0 0 0\n")
    for name, why in [("junk.ply", "Expected ply$"),
                      ("spaces.off", "ValueError: too many values"),
                      ("missing.off", "File .*missing.off not found")]:
        with pytest.raises(dot_client.InvalidInput,
                           match=f"meshio cannot read .*{name}: {why}"):
            dot_client.read_mesh(tmp_path / name)
    assert capsys.readouterr().out == ""  # meshio's prints, in the error


def test_list_holes_of_a_mesh(client):
    v, f = grid_with_hole(16)
    report = client.list_holes(meshio.Mesh(v, [("triangle", f)]),
                               skip_longest=True)
    assert [(h.boundary_vertices, h.status) for h in report.holes] == [
        (60, "skipped"), (16, "listed")]


@pytest.mark.parametrize("make, kwargs, message", [
    (lambda v, f: meshio.Mesh(v, [("triangle", f)]), {"faces": [[0, 1, 2]]},
     "give a meshio.Mesh alone"),
    (lambda v, f: meshio.Mesh(v, [("triangle", f)]),
     {"point_data": {"c": np.zeros(64)}}, "give a meshio.Mesh alone"),
    (lambda v, f: meshio.Mesh(v, [("line", f[:, :2])]), {},
     "no surface cells"),
    (lambda v, f: meshio.Mesh(v[:, :2], [("triangle", f)]), {},
     "points must be 3D"),
    (lambda v, f: meshio.Mesh(v, [("triangle", f + len(v))]), {},
     "vertex"),
])
def test_bad_meshes_are_refused_before_the_call(client, make, kwargs,
                                                message):
    v, f = grid_with_hole(8)
    with pytest.raises(dot_client.InvalidInput, match=message):
        client.fill_holes(make(v, f), **kwargs)


def test_arrays_still_work_and_meshio_is_optional(client, tmp_path):
    v, f = grid_with_hole(8)
    r = client.fill_holes(v, f, skip_longest=True)
    assert isinstance(r, dot_client.FillResult)
    with pytest.raises(dot_client.InvalidInput, match="faces is missing"):
        client.fill_holes(v)
    # Without meshio (its import made to fail), dot_client imports and
    # fills arrays; FilledMesh says what it needs.
    script = (
        "import sys; sys.modules['meshio'] = None\n"
        "import dot_client\n"
        "from dot_client import *\n"
        "try:\n"
        "    dot_client.read_mesh\n"
        "except ImportError as e:\n"
        "    print(e)\n"
        "import numpy as np\n"
        f"c = dot_client.Client({client.address!r}, timeout=60)\n"
        "v = np.array([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1.0)])\n"
        "r = c.fill_holes(v, [(0, 2, 1), (0, 1, 3), (1, 2, 3)])\n"
        "print(r.report.filled)\n")
    out = subprocess.run([sys.executable, "-c", script], env=dict(
        os.environ, PYTHONPATH=os.pathsep.join(sys.path)),
        capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == [
        "dot_client.read_mesh needs meshio (Debian: python3-meshio): "
        "import of meshio halted; None in sys.modules", "1"]

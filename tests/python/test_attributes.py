# SPDX-License-Identifier: AGPL-3.0-or-later
"""Attributes through a real dot-server: point_data and corner_data sent,
carried through the fill and interpolated into new vertices and corners,
in the whole mesh and in patches; polygons kept; bad channels refused
before the call; the upload's slices read back whole."""
import numpy as np
import pytest

import dot_client
from dot_client import wire
from shapes import box_with_hole, grid_with_hole


def linear(points: np.ndarray) -> np.ndarray:
    """A field that harmonic interpolation on a flat patch keeps exactly."""
    return np.c_[points[:, 0] / 16, points[:, 1] / 16,
                 np.full(len(points), 0.5)].astype(np.float32)


def test_point_and_corner_data_are_interpolated_into_new_vertices(client):
    v, f = grid_with_hole(16)
    uv = linear(v[f.reshape(-1)])[:, :2]  # per corner, in face order
    r = client.fill_holes(v, f, skip_longest=True,
                          point_data={"color": linear(v)},
                          corner_data={"uv": uv})
    assert r.report.filled == 1 and r.report.added_vertices > 0
    color, corners = r.point_data["color"], r.corner_data["uv"]
    assert color.dtype == np.float32 and color.shape == (len(r.vertices), 3)
    assert corners.shape == (3 * len(r.faces), 2)
    # The input's values exactly, the new vertices' on the linear field.
    assert np.array_equal(color[:len(v)], linear(v))
    np.testing.assert_allclose(color, linear(r.vertices), atol=1e-4)
    np.testing.assert_allclose(corners, linear(r.vertices[
        r.faces.reshape(-1)])[:, :2], atol=1e-4)


def test_colours_on_a_0_to_255_scale_stay_on_it(client):
    """Values blend with positive weights: new colours stay within the
    rim's range whatever its scale (no clamp to [0, 1])."""
    v, f = grid_with_hole(16)
    bytes_ = (linear(v) * 255).astype(np.int32)
    r = client.fill_holes(v, f, skip_longest=True,
                          point_data={"color": bytes_})
    new = r.point_data["color"][len(v):]
    assert len(new) > 0
    assert new.max() > 1.5 and new.min() >= bytes_.min() - 1e-3
    assert new.max() <= bytes_.max() + 1e-3


def test_polygons_are_kept_on_request(client):
    v, quads = box_with_hole()
    r = client.fill_holes(v, quads, keep_polygons=True)
    assert r.report.filled == 1
    assert isinstance(r.faces, list)
    sizes = [len(face) for face in r.faces]
    assert sizes.count(4) + len(r.report.holes[0].split_faces) == len(quads)
    assert sizes[len(quads):] == [3] * (len(r.faces) - len(quads))


def test_patches_carry_every_channel_at_their_corners(client):
    v, f = grid_with_hole(16)
    uv = linear(v[f.reshape(-1)])[:, :2]
    p = client.fill_patches(v, f, skip_longest=True, stage="refine",
                            point_data={"color": linear(v)},
                            corner_data={"uv": uv})
    assert len(p.patches) == 1
    patch = p.patches[0]
    vertices = np.concatenate([v, patch.vertices])
    corners = vertices[patch.faces.reshape(-1)]
    assert patch.corner_data["uv"].shape == (3 * len(patch.faces), 2)
    np.testing.assert_allclose(patch.corner_data["uv"],
                               linear(corners)[:, :2], atol=1e-4)
    np.testing.assert_allclose(patch.corner_data["color"], linear(corners),
                               atol=1e-4)
    for face, triangles in patch.replaced_faces.items():
        on = patch.replaced_corner_data[face]["uv"]
        np.testing.assert_allclose(
            on, linear(vertices[triangles.reshape(-1)])[:, :2], atol=1e-4)


@pytest.mark.parametrize("point_data, corner_data, message", [
    ({"c": np.zeros((3, 3))}, None, "must have shape (256, d)"),
    ({"c": np.zeros((3, 3))}, None, "a row per vertex"),
    ({"c": np.zeros(256, dtype=complex)}, None, "must be real numbers"),
    ({"c": np.full(256, 1e300)}, None, "not finite in single precision"),
    (None, {"uv": np.zeros((5, 2))}, "a row per face corner"),
    ({"c": np.full((256, 1), np.nan)}, None, "row 0 is not finite"),
    ({"c": np.zeros((256, 17))}, None, "1 <= d <= 16"),
    ({"": np.zeros(256)}, None, "1 to 64 bytes"),
    ({"c": np.zeros(256)}, {"c": np.zeros(0)}, "'c' is given twice"),
    ([1], None, "point_data must be a dict"),
])
def test_bad_channels_are_refused_before_the_call(client, point_data,
                                                  corner_data, message):
    v, f = grid_with_hole(16)
    with pytest.raises(dot_client.InvalidInput, match=message.replace(
            "(", r"\(").replace(")", r"\)")):
        client.fill_holes(v, f, point_data=point_data,
                          corner_data=corner_data)


def test_the_uploads_slices_read_back_whole():
    v, quads = box_with_hole()
    faces = [np.asarray(q) for q in quads[:5]] + [
        np.asarray(t) for q in quads[5:] for t in ([q[0], q[1], q[2]],
                                                   [q[0], q[2], q[3]])]
    corners = sum(len(face) for face in faces)
    channels = [("color", False, linear(v)),
                ("uv", True, np.arange(2 * corners, dtype=np.float32)
                 .reshape(-1, 2))]
    requests = list(wire.fill_requests("x", wire.pb.FillOptions(), v, faces,
                                       max_bytes=200, channels=channels))
    assert len(requests) > 10
    soup = wire.SoupAssembler()
    for i, m in enumerate(requests):
        soup.add(m.mesh, f"message {i}")
    vertices, got, data = soup.finish(len(v))
    assert np.array_equal(vertices, v)
    assert [list(a) for a in got] == [list(a) for a in faces]
    assert data["color"][0] is False
    assert np.array_equal(data["color"][1], channels[0][2])
    assert data["uv"][0] is True
    assert np.array_equal(data["uv"][1], channels[1][2])

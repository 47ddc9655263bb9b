# SPDX-License-Identifier: AGPL-3.0-or-later
"""The typed options (Weights, TriangulateOptions, FillOptions) and the
weight presets: defaults, checks, the keyword arguments that replace their
fields, and the requests they make."""
import dataclasses

import numpy as np
import pytest

import dot_client
from dot_client import (WEIGHT_PRESETS, FillOptions, TriangulateOptions,
                        Weights)
from dot_client._proto.dot.v1 import triangulation_pb2 as pb
from shapes import grid_with_hole, monkey_saddle


def test_defaults_are_the_services():
    t = TriangulateOptions()
    assert t.weights == Weights() and t.weights.is_zero()
    assert (t.search_space, t.delaunay_backend) == ("auto", "default")
    assert not (t.protect_edges or t.validate_output or t.no_cache)
    request = pb.TriangulateRequest()
    t.to_proto(request)
    assert request.weights == pb.MetricWeights()
    assert request.options == pb.Options()
    f = FillOptions()
    assert (f.stage, f.weights, f.holes, f.loops_through) == \
        ("fair", None, (), ())
    message = f.to_proto()
    assert not message.HasField("weights")  # the hole-filling default
    assert not message.HasField("fairing_continuity")
    assert message.stage == pb.FILL_STAGE_FAIR
    assert message.answer == pb.FILL_ANSWER_MESH
    assert f.to_dict()["loops_through"] == []


def test_options_are_frozen_and_replaced():
    f = FillOptions(stage="refine")
    with pytest.raises(dataclasses.FrozenInstanceError):
        f.stage = "fair"  # type: ignore[misc]
    g = dataclasses.replace(f, loops_through=[4, 5])
    assert g.loops_through == (4, 5) and f.loops_through == ()
    assert g.stage == "refine"


def test_every_field_reaches_the_message():
    f = FillOptions(stage="Triangulate", weights={"area": 2, "shape": 0.5},
                    absolute_weights=True, max_hole_edges=30,
                    max_hole_diameter=2.5, skip_longest=True, holes=[1, -1],
                    loops_through=np.array([7, 9]), density=3,
                    fairing_continuity=0, no_repair=True, time_budget_ms=500,
                    memory_budget_bytes=1 << 33)
    m = f.to_proto("patches")
    assert m == pb.FillOptions(
        stage=pb.FILL_STAGE_TRIANGULATE,
        weights=pb.MetricWeights(area=2, shape=0.5), absolute_weights=True,
        max_hole_edges=30, max_hole_diameter=2.5, skip_longest=True,
        holes=[1, -1], loops_through=[7, 9], density=3, fairing_continuity=0,
        no_repair=True, time_budget_ms=500, memory_budget_bytes=1 << 33,
        answer=pb.FILL_ANSWER_PATCHES)
    t = TriangulateOptions(weights="smooth", search_space="DELAUNAY",
                           protect_edges=True, delaunay_backend="cgal",
                           validate_output=True, time_budget_ms=9,
                           memory_budget_bytes=10, no_cache=True)
    request = pb.TriangulateRequest()
    t.to_proto(request)
    assert request.weights == pb.MetricWeights(squared_dihedral=1, shape=0.01)
    assert request.options == pb.Options(
        search_space=pb.SEARCH_SPACE_DELAUNAY, protect_edges=True,
        delaunay_backend=pb.DELAUNAY_BACKEND_CGAL, validate_output=True,
        time_budget_ms=9, memory_budget_bytes=10, no_cache=True)


@pytest.mark.parametrize("make, words", [
    (lambda: Weights(area="1"), "area must be a number"),
    (lambda: Weights(shape=float("nan")), "shape must be finite"),
    (lambda: Weights.of("smoothest"), "there is no weights preset 'smoothest'"
     "; the presets are minimal_area, smooth, follow_normals"),
    (lambda: Weights.of({"areas": 1}), "unknown metric areas in weights"),
    (lambda: Weights.of(3), "weights must be a dot_client.Weights"),
    (lambda: TriangulateOptions(search_space="some"), "search_space must be "
     "one of auto, delaunay, all"),
    (lambda: TriangulateOptions(delaunay_backend="qhull"),
     "delaunay_backend must be one of default, cgal, tetgen"),
    (lambda: TriangulateOptions(protect_edges=1), "protect_edges must be True"),
    (lambda: FillOptions(stage="default"), "stage must be one of triangulate, "
     "refine, fair"),
    (lambda: FillOptions(weights=Weights()), "every metric weight is zero"),
    (lambda: FillOptions(holes="1"), "holes must be a list of hole ids"),
    (lambda: FillOptions(loops_through=[2**32]), "loops_through[0] must be "
     "between 0 and 4294967295"),
    (lambda: FillOptions(density=0.01), "density must be between 0.1 and 100"),
    (lambda: FillOptions(fairing_continuity=3), "fairing_continuity must be "
     "between 0 and 2"),
    (lambda: FillOptions(max_hole_diameter=-1), "max_hole_diameter must be >= "
     "0"),
    (lambda: FillOptions.merged(TriangulateOptions()),
     "options must be a dot_client.FillOptions; got TriangulateOptions"),
])
def test_bad_options_are_refused_when_made(make, words):
    with pytest.raises(dot_client.InvalidInput) as e:
        make()
    assert words in e.value.message


def test_keyword_arguments_replace_fields():
    base = FillOptions(stage="refine", weights="minimal_area", holes=[2])
    merged = FillOptions.merged(base, squared_dihedral=1, skip_longest=True,
                                holes=None)
    assert merged.weights == Weights(area=1, squared_dihedral=1)
    assert merged.skip_longest and merged.holes == (2,)  # None: not given
    assert merged.stage == "refine"
    # Single weights over unset weights: the others count 0.
    assert FillOptions.merged(None, area=1).weights == Weights(area=1)
    # `weights` first, then single metrics.
    assert FillOptions.merged(base, weights="smooth", area=0.5).weights == \
        Weights(squared_dihedral=1, area=0.5)
    assert TriangulateOptions.merged(None, weights="smooth").weights == \
        WEIGHT_PRESETS["smooth"].triangulate
    assert FillOptions.merged(None) == FillOptions()
    with pytest.raises(TypeError, match="FillOptions has no option stages"):
        FillOptions.merged(None, stages="fair")


def test_weight_presets():
    assert list(WEIGHT_PRESETS) == ["minimal_area", "smooth",
                                    "follow_normals"]
    for name, preset in WEIGHT_PRESETS.items():
        assert preset.label and preset.description
        assert Weights.of(name) == preset.triangulate
        assert Weights.of(name.upper(), "fill") == preset.fill
        assert not preset.fill.is_zero()
    # The same table drives the client's calls.
    assert TriangulateOptions(weights="follow_normals").weights.normal_deviation == 1


def test_the_smooth_fill_preset_is_the_service_default(client):
    v, f = grid_with_hole(20, slice(5, 12))
    v = v.copy()
    v[:, 2] = 0.02 * (v[:, 0] - 10) ** 2  # curved, so weights matter
    default = client.fill_holes(v, f, stage="triangulate", skip_longest=True)
    smooth = client.fill_holes(v, f, stage="triangulate", skip_longest=True,
                               weights="smooth")
    area = client.fill_holes(v, f, stage="triangulate", skip_longest=True,
                             weights="minimal_area")
    assert np.array_equal(default.faces, smooth.faces)
    assert [h.cost for h in default.report.holes] == \
        [h.cost for h in smooth.report.holes]
    assert not np.array_equal(default.faces, area.faces)


def test_options_objects_and_keywords_make_one_request(client):
    points = monkey_saddle(40)
    options = TriangulateOptions(weights=Weights(squared_dihedral=1),
                                 search_space="delaunay")
    by_object = client.triangulate(points, options=options)
    by_keywords = client.triangulate(points, squared_dihedral=1,
                                     search_space="delaunay")
    assert np.array_equal(by_object.triangles, by_keywords.triangles)
    assert by_object.summary.solver == "DOT2"
    # A keyword replaces the object's field: area alone is DOT1.
    assert client.triangulate(points, options=options, squared_dihedral=0,
                              area=1).summary.solver == "DOT1"
    many = client.triangulate_many([points, points[::2]], options=options)
    assert np.array_equal(many[0].triangles, by_object.triangles)
    v, f = grid_with_hole(12)
    a = client.fill_holes(v, f, options=FillOptions(stage="refine",
                                                    skip_longest=True))
    b = client.fill_holes(v, f, stage="refine", skip_longest=True)
    assert np.array_equal(a.faces, b.faces)
    assert np.array_equal(a.vertices, b.vertices)

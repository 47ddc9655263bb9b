// SPDX-License-Identifier: AGPL-3.0-or-later
// Every output on the paper's curve families is a valid, intersection-free
// disk spanning the polygon; knots end in "no triangulation".
#include <gtest/gtest.h>

#include <string>
#include <tuple>

#include "dot/dot.h"

namespace dot {
namespace {

using CurveCase = std::tuple<Curve, int, bool>;  // curve, n, bi-triangle

class CurveOutputTest : public ::testing::TestWithParam<CurveCase> {};

TEST_P(CurveOutputTest, OutputIsValidAndIntersectionFree) {
  const auto [curve, n, bi] = GetParam();
  Problem p{MakeCurve(curve, n), {}, {}, {}, {}};
  p.weights[bi ? Metric::kSquaredDihedral : Metric::kArea] = 1;
  Options o;
  o.space = SearchSpace::kDelaunay;  // a fallback to 'all' would hide failures
  const Result r = Triangulate(p, o);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_EQ(r.space_used, SpaceUsed::kDelaunay3d);
  EXPECT_EQ(r.solver, bi ? Solver::kDot2 : Solver::kDot1);
  EXPECT_EQ(r.triangles.size(), r.polygon.size() - 2);
  const MeshReport report = ValidateMesh(r.vertices, r.polygon, r.triangles);
  EXPECT_TRUE(report.valid()) << report.first_problem;
  EXPECT_EQ(report.intersecting_pairs, 0);
  EXPECT_TRUE(report.disk);
  EXPECT_TRUE(report.boundary_is_polygon);
  // Reported costs are the metrics of the returned triangles.
  const MetricValues m = EvaluateMetrics(r.vertices, {}, r.triangles);
  EXPECT_DOUBLE_EQ(r.total_cost, WeightedTotal(p.weights, m));
  EXPECT_GT(r.stats.tetrahedra, 0);
  EXPECT_GE(r.stats.search_triangles, r.stats.delaunay_triangles);
  EXPECT_GT(r.stats.table_bytes, 0);
}

std::string CaseName(const ::testing::TestParamInfo<CurveCase>& info) {
  const auto [curve, n, bi] = info.param;
  return std::string(CurveName(curve)) + "_" + std::to_string(n) +
         (bi ? "_dot2" : "_dot1");
}

INSTANTIATE_TEST_SUITE_P(PaperCurves, CurveOutputTest,
                         ::testing::Combine(::testing::ValuesIn(kPaperCurves),
                                            ::testing::Values(25, 50, 301, 1001,
                                                              2001),
                                            ::testing::Bool()),
                         CaseName);

TEST(CurveTest, TrefoilHasNoTriangulation) {
  for (int n : {40, 120, 600}) {
    Problem p{MakeCurve(Curve::kTrefoil, n), {}, {}, {}, {}};
    Options o;
    o.space = SearchSpace::kDelaunay;
    o.protect_edges = true;
    const Result r = Triangulate(p, o);
    EXPECT_EQ(r.status.code, StatusCode::kNoTriangulation) << n;
    EXPECT_TRUE(r.non_delaunay_edges.empty());
    EXPECT_EQ(r.status.message, "polygon is not Delaunay-triangulable");
    EXPECT_TRUE(r.triangles.empty());
  }
}

TEST(CurveTest, CoarseSpiralNeedsEdgeProtection) {
  // At 15 samples the spiral's chords skip past its other arm.
  Problem p{MakeCurve(Curve::kSpiral, 15), {}, {}, {}, {}};
  Options o;
  o.space = SearchSpace::kDelaunay;
  const Result before = Triangulate(p, o);
  EXPECT_EQ(before.status.code, StatusCode::kNoTriangulation);
  EXPECT_FALSE(before.non_delaunay_edges.empty());
  o.protect_edges = true;
  const Result after = Triangulate(p, o);
  ASSERT_TRUE(after.status.ok()) << after.status.message;
  EXPECT_FALSE(after.inserted.empty());
  const MeshReport report =
      ValidateMesh(after.vertices, after.polygon, after.triangles);
  EXPECT_TRUE(report.valid()) << report.first_problem;
}

}  // namespace
}  // namespace dot

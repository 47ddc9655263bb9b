// SPDX-License-Identifier: AGPL-3.0-or-later
// Every malformed input is rejected with a message naming what is wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "dot/dot.h"

namespace dot {
namespace {

Problem Square() {
  return {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0}}, {}, {}, {}, {}};
}

void ExpectRejected(const Problem& p, const std::string& fragment,
                    StatusCode code = StatusCode::kInvalidArgument,
                    const Options& o = {}) {
  const Result r = Triangulate(p, o);
  EXPECT_EQ(r.status.code, code) << r.status.message;
  EXPECT_NE(r.status.message.find(fragment), std::string::npos)
      << "message: " << r.status.message << "\nexpected: " << fragment;
  EXPECT_TRUE(r.triangles.empty());
}

TEST(InputTest, TooFewVertices) {
  ExpectRejected({{{0, 0, 0}, {1, 0, 0}}, {}, {}, {}, {}},
                 "polygon has 2 vertices; at least 3 are needed");
  ExpectRejected({}, "polygon has 0 vertices");
}

TEST(InputTest, EdgeFaceNormalsAndForbiddenEdges) {
  Problem p = Square();
  p.edge_face_normals = {{0, 0, 1}};
  ExpectRejected(p, "1 edge face normals given for 4 vertices");
  p.edge_face_normals = {{0, 0, 1}, {}, {0, 0, NAN}, {0, 0, 1}};
  ExpectRejected(p, "edge face normal 2 (0, 0, nan) is not finite");
  p.edge_face_normals.clear();
  p.forbidden_edges = {{0, 4}};
  ExpectRejected(p, "forbidden edge 0-4 does not join two distinct vertices");
  p.forbidden_edges = {{3, 0}};
  ExpectRejected(p, "forbidden edge 3-0 is a polygon edge");
  // Both diagonals of a quadrilateral forbidden: nothing is left.
  p.forbidden_edges = {{0, 2}, {1, 3}};
  Options all;
  all.space = SearchSpace::kAll;
  EXPECT_EQ(Triangulate(p, all).status.code, StatusCode::kNoTriangulation);
  p.forbidden_edges = {{0, 2}};
  const Result r = Triangulate(p, all);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  for (const Triangle& t : r.triangles) {
    EXPECT_FALSE((t[0] == 0 || t[1] == 0 || t[2] == 0) &&
                 (t[0] == 2 || t[1] == 2 || t[2] == 2));
  }
}

TEST(InputTest, NonFiniteCoordinates) {
  Problem p = Square();
  p.vertices[2].y = std::numeric_limits<double>::quiet_NaN();
  ExpectRejected(p, "vertex 2 has a non-finite coordinate (1, nan, 0.5)");
  p.vertices[2].y = std::numeric_limits<double>::infinity();
  ExpectRejected(p, "vertex 2 has a non-finite coordinate (1, inf, 0.5)");
}

TEST(InputTest, ConsecutiveDuplicate) {
  Problem p = Square();
  p.vertices.insert(p.vertices.begin() + 2, p.vertices[1]);
  ExpectRejected(p, "vertices 1 and 2 are consecutive duplicates (1, 0, 0)");
  Problem wrap = Square();
  wrap.vertices.push_back(wrap.vertices[0]);
  ExpectRejected(wrap, "vertices 4 and 0 are consecutive duplicates");
}

TEST(InputTest, RepeatedVertex) {
  Problem p = Square();
  p.vertices.push_back({2, 2, 2});
  p.vertices.push_back(p.vertices[1]);
  p.vertices.push_back({3, 0, 1});
  ExpectRejected(p, "vertex 5 repeats vertex 1 (1, 0, 0)");
}

TEST(InputTest, Collinear) {
  ExpectRejected({{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}, {}, {}, {}, {}},
                 "all 4 vertices are collinear");
  ExpectRejected({{{0, 0, 0}, {1, 0, 0}, {0.5, 1e-12, 0}}, {}, {}, {}, {}},
                 "all 3 vertices are collinear");
}

TEST(InputTest, Normals) {
  Problem p = Square();
  p.normals = {{0, 0, 1}, {0, 0, 1}};
  ExpectRejected(p, "2 boundary normals given for 4 vertices");
  p.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 0}, {0, 0, 1}};
  ExpectRejected(p, "boundary normal 2 (0, 0, 0) is zero or not finite");
  Problem q = Square();
  q.weights[Metric::kNormalDeviation] = 1;
  ExpectRejected(q, "normal_deviation has a weight but no boundary normals");
}

TEST(InputTest, NonFiniteWeight) {
  Problem p = Square();
  p.weights[Metric::kPerimeter] = std::numeric_limits<double>::infinity();
  ExpectRejected(p, "weight of metric perimeter is not finite");
}

TEST(InputTest, MemoryBudget) {
  Problem p{MakeCurve(Curve::kMonkey, 500), {}, {}, {}, {}};
  Options o;
  o.memory_budget_bytes = 1000;
  ExpectRejected(p, "exceeds the budget", StatusCode::kResourceExhausted, o);
  o.space = SearchSpace::kAll;
  o.all_space_hard_limit = 100;
  o.memory_budget_bytes = int64_t{1} << 40;
  ExpectRejected(p, "search space 'all' is limited to 100 vertices",
                 StatusCode::kResourceExhausted, o);
}

TEST(InputTest, EstimateGrowsWithTrianglesAndBiTriangleMetrics) {
  EXPECT_GT(EstimateTableBytes(1000, false), 0);
  EXPECT_EQ(EstimateTableBytes(2000, false),
            2 * EstimateTableBytes(1000, false));
  EXPECT_GT(EstimateTableBytes(1000, true), EstimateTableBytes(1000, false));
}

TEST(InputTest, ZeroWeightsMeanArea) {
  const Result r = Triangulate(Square());
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_DOUBLE_EQ(r.total_cost, r.metric_costs[Metric::kArea]);
}

TEST(InputTest, NegativeDelaunayThreadSettings) {
  Options o;
  o.delaunay_threads = -1;
  ExpectRejected(Square(), "delaunay_threads must be >= 0",
                 StatusCode::kInvalidArgument, o);
  o = {};
  o.parallel_delaunay_min_points = -5;
  ExpectRejected(Square(), "parallel_delaunay_min_points must be >= 0",
                 StatusCode::kInvalidArgument, o);
}

}  // namespace
}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
// The adjacency puts every edge's lists in a canonical order, so results
// never depend on the order a backend lists its faces in; it refuses
// polygons beyond its vertex limit.
#include "solve/adjacency.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "dot/dot.h"
#include "search_space/delaunay_cgal.h"
#include "solve/solvers.h"

namespace dot {
namespace {

std::vector<Triangle> Sorted(std::vector<Triangle> faces) {
  std::sort(faces.begin(), faces.end());
  return faces;
}

// The optimal triangles (as sorted vertex triples) of a candidate list.
std::vector<Triangle> SolveOver(const std::vector<Vec3>& loop,
                                const std::vector<Triangle>& faces, bool bi) {
  Adjacency adj;
  EXPECT_TRUE(
      BuildAdjacency(static_cast<int32_t>(loop.size()), faces, {}, &adj).ok());
  std::vector<double> w;
  std::vector<Vec3> unit;
  for (const Triangle& f : faces) {
    w.push_back(PerTriangleMetrics(loop, {}, f)[Metric::kArea]);
    unit.push_back(UnitNormal(loop, f));
  }
  DpSolution sol;
  const Status s = bi ? SolveDot2(adj, std::vector<double>(w.size(), 0), unit,
                                  {}, {0, 1}, {}, &sol)
                      : SolveDot1(adj, w, {}, &sol);
  EXPECT_TRUE(s.ok()) << s.message;
  std::vector<Triangle> out;
  for (int32_t t : sol.triangles) out.push_back(faces[t]);
  return Sorted(out);
}

// Ties between equal-cost triangulations (the symmetric curves have many)
// must break the same way however the backend happens to list its faces.
TEST(DelaunayBackendsTest, ResultsDoNotDependOnFaceOrder) {
  for (Curve c : kPaperCurves) {
    const std::vector<Vec3> loop =
        MakeCurve(c, c == Curve::kMonkey ? 840 : 240);
    std::vector<Triangle> faces;
    int64_t tets = 0;
    ASSERT_TRUE(CgalDelaunayFaces(loop, {}, &faces, &tets).ok());
    std::vector<Triangle> shuffled = faces;
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(5));
    for (bool bi : {false, true}) {
      EXPECT_EQ(SolveOver(loop, faces, bi), SolveOver(loop, shuffled, bi))
          << CurveName(c) << (bi ? " DOT2" : " DOT1");
    }
  }
}

TEST(AdjacencyTest, RefusesPolygonsBeyondTheVertexLimit) {
  Adjacency adj;
  const Status s = BuildAdjacency(kMaxVertices + 1, {}, {}, &adj);
  EXPECT_EQ(s.code, StatusCode::kResourceExhausted);
  EXPECT_NE(s.message.find("the limit is 16777215"), std::string::npos)
      << s.message;
}

TEST(AdjacencyTest, ListsInnerAndOuterTrianglesOfEachEdge) {
  // A square fan: triangles (0,1,2), (0,2,3) over positions 0..3.
  Adjacency adj;
  ASSERT_TRUE(BuildAdjacency(4, {{0, 1, 2}, {0, 2, 3}}, {}, &adj).ok());
  ASSERT_GE(adj.root, 0);
  EXPECT_EQ(adj.edge_lo[adj.root], 0);
  EXPECT_EQ(adj.edge_hi[adj.root], 3);
  EXPECT_TRUE(adj.missing_polygon_edges.empty());
  // Edges by increasing span: the four polygon edges, then [0, 2], then the
  // root [0, 3] (a polygon edge too, closing the loop).
  ASSERT_EQ(adj.edge_count(), 5);
  for (int32_t e = 0; e < adj.edge_count(); ++e) {
    if (e > 0) {
      EXPECT_LE(adj.edge_hi[e - 1] - adj.edge_lo[e - 1],
                adj.edge_hi[e] - adj.edge_lo[e]);
    }
  }
  int32_t diagonal = -1;
  for (int32_t e = 0; e < adj.edge_count(); ++e) {
    if (adj.edge_lo[e] == 0 && adj.edge_hi[e] == 2) diagonal = e;
  }
  ASSERT_GE(diagonal, 0);
  // [0, 2] is the long edge of triangle 0 and short edge (slot 0) of 1.
  EXPECT_EQ(adj.inner_begin[diagonal + 1] - adj.inner_begin[diagonal], 1);
  EXPECT_EQ(adj.inner[adj.inner_begin[diagonal]], 0);
  EXPECT_EQ(adj.outer_begin[diagonal + 1] - adj.outer_begin[diagonal], 1);
  EXPECT_EQ(adj.outer[adj.outer_begin[diagonal]], 2 * 1 + 0);
}

TEST(AdjacencyTest, ReportsMissingPolygonEdges) {
  Adjacency adj;
  // Positions 0..4; no candidate contains polygon edge 2-3.
  ASSERT_TRUE(BuildAdjacency(5, {{0, 1, 2}, {0, 2, 4}}, {}, &adj).ok());
  EXPECT_EQ(adj.missing_polygon_edges, (std::vector<int32_t>{2, 3}));
}

}  // namespace
}  // namespace dot

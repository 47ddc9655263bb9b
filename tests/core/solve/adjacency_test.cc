// SPDX-License-Identifier: AGPL-3.0-or-later
// The adjacency matches its definition (brute force), puts every edge's
// lists in a canonical order, so results never depend on the order a
// backend lists its faces in, and refuses what it cannot index.
#include "solve/adjacency.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
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
                                std::vector<Triangle> faces, bool bi) {
  Adjacency adj;
  EXPECT_TRUE(
      BuildAdjacency(static_cast<int32_t>(loop.size()), &faces, {}, &adj).ok());
  CandidateWeights w;
  std::vector<Vec3> unit;
  for (const Triangle& f : faces) {
    w.push_back(PerTriangleMetrics(loop, {}, f)[Metric::kArea]);
    unit.push_back(UnitNormal(loop, f));
  }
  DpSolution sol;
  const Status s = bi ? SolveDot2(adj, CandidateWeights(w.size(), 0.0),
                                  CandidateNormals(unit), {}, {0, 1}, {}, &sol)
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

// Checks the adjacency against its definition, by brute force over the
// (sorted) candidates.
void ExpectMatchesDefinition(int32_t n, const std::vector<Triangle>& tris,
                             const Adjacency& adj) {
  ASSERT_TRUE(std::is_sorted(tris.begin(), tris.end()));
  std::map<std::pair<int32_t, int32_t>, int32_t> id;
  for (int32_t e = 0; e < adj.edge_count(); ++e) {
    ASSERT_LT(adj.edge_lo[e], adj.edge_hi[e]);
    ASSERT_TRUE(id.emplace(std::pair{adj.edge_lo[e], adj.edge_hi[e]}, e).second)
        << "edge listed twice";
  }
  std::vector<std::vector<int32_t>> inner(adj.edge_count()),
      outer(adj.edge_count());
  for (int32_t t = 0; t < static_cast<int32_t>(tris.size()); ++t) {
    const auto [a, b, c] = tris[t];
    const int32_t ab = id.at({a, b}), bc = id.at({b, c}), ac = id.at({a, c});
    EXPECT_EQ(adj.tri_edges[3 * t], ab);
    EXPECT_EQ(adj.tri_edges[3 * t + 1], bc);
    EXPECT_EQ(adj.tri_edges[3 * t + 2], ac);
    // Children before parents: the dynamic programs' one forward pass.
    EXPECT_LT(ab, ac);
    EXPECT_LT(bc, ac);
    inner[ac].push_back(t);
    outer[ab].push_back(2 * t);
    outer[bc].push_back(2 * t + 1);
  }
  auto third = [&](int32_t slot) {
    const Triangle& t = tris[slot / 2];
    return slot % 2 == 0 ? t[2] : t[0];
  };
  for (int32_t e = 0; e < adj.edge_count(); ++e) {
    // Canonical: by the third vertex.
    std::sort(inner[e].begin(), inner[e].end(),
              [&](int32_t x, int32_t y) { return tris[x][1] < tris[y][1]; });
    std::sort(outer[e].begin(), outer[e].end(),
              [&](int32_t x, int32_t y) { return third(x) < third(y); });
    EXPECT_EQ(std::vector<int32_t>(adj.inner.begin() + adj.inner_begin[e],
                                   adj.inner.begin() + adj.inner_begin[e + 1]),
              inner[e]);
    EXPECT_EQ(std::vector<int32_t>(adj.outer.begin() + adj.outer_begin[e],
                                   adj.outer.begin() + adj.outer_begin[e + 1]),
              outer[e]);
  }
  const auto root = id.find({0, n - 1});
  EXPECT_EQ(adj.root, root == id.end() ? -1 : root->second);
  if (adj.root >= 0) {
    EXPECT_EQ(adj.root, adj.edge_count() - 1);
  }
}

TEST(AdjacencyTest, MatchesItsDefinitionOnDelaunayFaces) {
  for (Curve c : {Curve::kMobius, Curve::kSpiral, Curve::kMoment}) {
    const std::vector<Vec3> loop = MakeCurve(c, 60);
    std::vector<Triangle> faces;
    int64_t tets = 0;
    ASSERT_TRUE(CgalDelaunayFaces(loop, {}, &faces, &tets).ok());
    std::shuffle(faces.begin(), faces.end(), std::mt19937(7));
    Adjacency adj;
    ASSERT_TRUE(BuildAdjacency(60, &faces, {}, &adj).ok());
    ExpectMatchesDefinition(60, faces, adj);
    // Already sorted input is kept as it is.
    const std::vector<Triangle> sorted = faces;
    Adjacency again;
    ASSERT_TRUE(BuildAdjacency(60, &faces, {}, &again).ok());
    EXPECT_EQ(faces, sorted);
    EXPECT_EQ(again.tri_edges, adj.tri_edges);
  }
}

TEST(AdjacencyTest, RefusesTriplesThatAreNotAscendingPositions) {
  for (Triangle bad : {Triangle{0, 2, 1}, Triangle{0, 1, 5}, Triangle{-1, 0, 2},
                       Triangle{1, 1, 2}}) {
    std::vector<Triangle> tris = {{0, 1, 2}, bad};
    Adjacency adj;
    const Status s = BuildAdjacency(5, &tris, {}, &adj);
    EXPECT_EQ(s.code, StatusCode::kInternal);
    EXPECT_NE(s.message.find("candidate triangle 1"), std::string::npos)
        << s.message;
  }
}

TEST(AdjacencyTest, RefusesPolygonsBeyondTheVertexLimit) {
  Adjacency adj;
  std::vector<Triangle> none;
  const Status s = BuildAdjacency(kMaxVertices + 1, &none, {}, &adj);
  EXPECT_EQ(s.code, StatusCode::kResourceExhausted);
  EXPECT_NE(s.message.find("the limit is 16777215"), std::string::npos)
      << s.message;
}

TEST(AdjacencyTest, ListsInnerAndOuterTrianglesOfEachEdge) {
  // A square fan: triangles (0,1,2), (0,2,3) over positions 0..3.
  Adjacency adj;
  std::vector<Triangle> fan = {{0, 1, 2}, {0, 2, 3}};
  ASSERT_TRUE(BuildAdjacency(4, &fan, {}, &adj).ok());
  ASSERT_GE(adj.root, 0);
  EXPECT_EQ(adj.edge_lo[adj.root], 0);
  EXPECT_EQ(adj.edge_hi[adj.root], 3);
  EXPECT_TRUE(adj.missing_polygon_edges.empty());
  // The four polygon edges and [0, 2]; the root [0, 3] (a polygon edge
  // too, closing the loop) comes last.
  ASSERT_EQ(adj.edge_count(), 5);
  EXPECT_EQ(adj.root, 4);
  ExpectMatchesDefinition(4, fan, adj);
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
  std::vector<Triangle> tris = {{0, 1, 2}, {0, 2, 4}};
  ASSERT_TRUE(BuildAdjacency(5, &tris, {}, &adj).ok());
  EXPECT_EQ(adj.missing_polygon_edges, (std::vector<int32_t>{2, 3}));
}

}  // namespace
}  // namespace dot

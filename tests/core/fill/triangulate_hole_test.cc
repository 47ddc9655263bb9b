// SPDX-License-Identifier: AGPL-3.0-or-later
// TriangulateHole: the DOT patch of one loop, the mesh's own edges never
// reused, the faces around the hole priced, split faces stitched.
#include <gtest/gtest.h>

#include <filesystem>

#include "dot/dot.h"
#include "fixtures/filled_mesh.h"
#include "fixtures/meshes.h"
#include "mesh/topology.h"

namespace dot {
namespace {

// A tetrahedron a b c d without its top faces: the hole a-b-c-d is a
// saddle whose cheaper diagonal a-c is already the bottom's edge, so the
// only manifold patch uses b-d.
TEST(TriangulateHoleTest, AnEdgeTheMeshHasIsNeverAddedAgain) {
  const MeshData m{{{0, 0, 0}, {1, 0, 0.5}, {1, 1, 0}, {0, 1, 0.5}},
                   {{0, 2, 1}, {0, 3, 2}}};
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(m, &loops).ok());
  ASSERT_EQ(loops.size(), 1u);
  for (Metric metric : {Metric::kArea, Metric::kSquaredDihedral}) {
    FillOptions o;
    o.weights = {};
    o.weights[metric] = 1;
    HolePatch patch;
    HoleReport report;
    const auto topo = BuildMeshTopology(m);
    ASSERT_TRUE(
        TriangulateHole(m, *topo, loops[0], o, {}, 4, &patch, &report).ok());
    ASSERT_EQ(patch.faces.size(), 2u);
    for (const Triangle& t : patch.faces) {
      const bool has_a = t[0] == 0 || t[1] == 0 || t[2] == 0;
      const bool has_c = t[0] == 2 || t[1] == 2 || t[2] == 2;
      EXPECT_FALSE(has_a && has_c) << MetricName(metric);
    }
    const FillResult r = FillHoles(m, o);
    testing::ExpectFilledMesh(m, r, /*closed=*/true, "tetrahedron");
  }
}

// mech-holes-shark has a hole with boundary edges on no Delaunay triangle:
// edge protection inserts vertices on them and the faces across are split,
// leaving no T-junction (the result is closed and edge-manifold).
TEST(TriangulateHoleTest, ProtectedEdgesAreStitchedIntoTheMesh) {
  const std::string path = testing::MeshPath("mech-holes-shark.off");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " missing";
  PolygonSoup soup;
  ASSERT_TRUE(ReadPolygonSoupFile(path, &soup).ok());
  MeshData m;
  RepairReport repair;
  ASSERT_TRUE(RepairMesh(soup, &m, &repair).ok());
  FillOptions o;
  o.stage = FillStage::kTriangulate;
  const FillResult r = FillHoles(m, o);
  testing::ExpectFilledMesh(m, r, /*closed=*/true, "shark");
  int protected_holes = 0;
  for (const HoleReport& h : r.report.holes) {
    if (h.escalation != Escalation::kProtectedEdges) continue;
    ++protected_holes;
    EXPECT_GT(h.boundary_inserted, 0);
    EXPECT_FALSE(h.split_faces.empty());
  }
  EXPECT_GE(protected_holes, 1);
}

// The faces across the boundary take part in DOT2: with them the patch
// meets its surroundings at smaller angles than without them.
TEST(TriangulateHoleTest, TheSurroundingFacesArePriced) {
  const MeshData torus = testing::BumpyTorus(40, 20);
  const MeshData m = testing::WithoutFaces(torus, [&](int32_t f) {
    const Triangle& t = torus.triangles[f];
    const int i = t[0] / 20, j = t[0] % 20;
    return i >= 10 && i < 16 && j >= 2 && j < 9;
  });
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(m, &loops).ok());
  ASSERT_EQ(loops.size(), 1u);
  const auto topo = BuildMeshTopology(m);
  FillOptions o;
  o.stage = FillStage::kTriangulate;
  HolePatch patch;
  HoleReport with;
  ASSERT_TRUE(
      TriangulateHole(m, *topo, loops[0], o, {}, 10000, &patch, &with).ok());
  // The same loop as a bare polygon (no faces around it).
  Problem bare;
  for (int32_t v : loops[0].vertices) bare.vertices.push_back(m.vertices[v]);
  bare.weights = o.weights;
  double edge = 0;
  for (size_t i = 0; i < bare.vertices.size(); ++i) {
    edge += Distance(bare.vertices[i],
                     bare.vertices[(i + 1) % bare.vertices.size()]);
  }
  edge /= bare.vertices.size();
  bare.weights[Metric::kArea] /= edge * edge;
  Options space;
  space.space = SearchSpace::kDelaunay;
  const Result plain = Triangulate(bare, space);
  ASSERT_TRUE(plain.status.ok()) << plain.status.message;
  // Price both with the faces around: DOT's own patch is optimal for that.
  Problem priced = bare;
  for (int32_t f : loops[0].faces) {
    priced.edge_face_normals.push_back(UnitNormal(m.vertices, m.triangles[f]));
  }
  std::vector<Triangle> mapped;
  for (const Triangle& t : patch.faces) {
    Triangle u;
    for (int k = 0; k < 3; ++k) {
      u[k] = static_cast<int32_t>(
          std::find(loops[0].vertices.begin(), loops[0].vertices.end(), t[k]) -
          loops[0].vertices.begin());
    }
    mapped.push_back(u);
  }
  const double cost_with = WeightedTotal(
      priced.weights,
      EvaluateMetrics(priced.vertices, {}, mapped, priced.edge_face_normals));
  const double cost_plain = WeightedTotal(
      priced.weights, EvaluateMetrics(priced.vertices, {}, plain.triangles,
                                      priced.edge_face_normals));
  EXPECT_NEAR(cost_with, with.cost, 1e-9 * std::max(1.0, cost_with));
  EXPECT_LE(cost_with, cost_plain + 1e-12);
}

}  // namespace
}  // namespace dot

namespace dot {
namespace {

// The chords FillHoles re-solves without: of a patch whose two faces lie on
// the grid over faces it keeps (an L-shaped hole's notch), the one edge the
// two share; their border edges are not chords.
TEST(TriangulateHoleTest,
     IntersectingChordsAreTheInnerEdgesOfFacesThatMeetTheMesh) {
  const int n = 6;
  const MeshData m =
      testing::WithoutFaces(testing::FlatGrid(n), [&](int32_t f) {
        const int quad = f / 2, i = quad / n, j = quad % n;
        return (i == 2 || i == 3) && (j == 2 || j == 3) && !(i == 3 && j == 3);
      });
  auto id = [&](int i, int j) { return i * (n + 1) + j; };
  const auto topology = BuildMeshTopology(m);
  HolePatch patch;
  patch.faces = {{id(2, 2), id(4, 3), id(3, 4)},
                 {id(4, 3), id(4, 4), id(3, 4)}};
  const auto first_new = static_cast<int32_t>(m.vertices.size());
  int64_t pairs = 0;
  ASSERT_TRUE(
      PatchIntersections(m, *topology, first_new, patch, {}, &pairs).ok());
  EXPECT_GT(pairs, 0);
  std::vector<std::pair<int32_t, int32_t>> chords;
  ASSERT_TRUE(
      IntersectingChords(m, *topology, first_new, patch, {}, &chords).ok());
  ASSERT_EQ(chords.size(), 1u);
  EXPECT_EQ(std::minmax(chords[0].first, chords[0].second),
            std::minmax(id(4, 3), id(3, 4)));
  // A patch inside the hole meets nothing: no chord.
  patch.faces = {{id(2, 2), id(3, 2), id(3, 3)},
                 {id(2, 2), id(3, 3), id(2, 3)}};
  ASSERT_TRUE(
      IntersectingChords(m, *topology, first_new, patch, {}, &chords).ok());
  EXPECT_TRUE(chords.empty());
}

// `avoid` forbids chords as the mesh's own edges are: the saddle whose only
// manifold patch uses b-d has none once b-d is avoided.
TEST(TriangulateHoleTest, AvoidedChordsAreNeverUsed) {
  const MeshData m{{{0, 0, 0}, {1, 0, 0.5}, {1, 1, 0}, {0, 1, 0.5}},
                   {{0, 2, 1}, {0, 3, 2}}};
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(m, &loops).ok());
  ASSERT_EQ(loops.size(), 1u);
  const auto topology = BuildMeshTopology(m);
  FillOptions o;
  HolePatch patch;
  HoleReport report;
  ASSERT_TRUE(
      TriangulateHole(m, *topology, {&loops[0]}, o, {}, 4, &patch, &report)
          .ok());
  const Status s = TriangulateHole(m, *topology, {&loops[0]}, o, {}, 4, &patch,
                                   &report, {{1, 3}});
  EXPECT_EQ(s.code, StatusCode::kNoTriangulation) << s.message;
}

}  // namespace
}  // namespace dot

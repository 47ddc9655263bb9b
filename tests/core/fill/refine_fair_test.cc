// SPDX-License-Identifier: AGPL-3.0-or-later
// Refinement reaches the density of the surroundings; fairing keeps a plane
// flat and follows a sphere.
#include <gtest/gtest.h>

#include <cmath>

#include "dot/dot.h"
#include "fixtures/filled_mesh.h"

namespace dot {
namespace {

using testing::GridWithSquareHole;
using testing::SphereWithCapCut;

const HoleReport& Filled(const FillResult& r) {
  for (const HoleReport& h : r.report.holes) {
    if (h.status == HoleStatus::kFilled) return h;
  }
  return r.report.holes.at(0);
}

double MeanEdge(const MeshData& m, size_t first_face, size_t last_face) {
  double sum = 0;
  int count = 0;
  for (size_t f = first_face; f < last_face; ++f) {
    const Triangle& t = m.triangles[f];
    for (int k = 0; k < 3; ++k) {
      sum += Distance(m.vertices[t[k]], m.vertices[t[(k + 1) % 3]]);
      ++count;
    }
  }
  return sum / count;
}

TEST(RefineFairTest, RefinementReachesTheSurroundingDensity) {
  const MeshData m = GridWithSquareHole(30, 8, 22);
  FillOptions o;
  o.stage = FillStage::kRefine;
  o.selection.skip_longest = true;  // the grid's rim
  const FillResult r = FillHoles(m, o);
  testing::ExpectFilledMesh(m, r, /*closed=*/false, "grid");
  ASSERT_EQ(r.report.filled, 1);
  EXPECT_GT(Filled(r).refined_vertices, 50);
  const double around = MeanEdge(m, 0, m.triangles.size());
  const double patch =
      MeanEdge(r.mesh, m.triangles.size(), r.mesh.triangles.size());
  std::printf("mean edge: surroundings %.4f, refined patch %.4f\n", around,
              patch);
  EXPECT_LT(patch, 2.0 * around);
  EXPECT_GT(patch, 0.5 * around);
  // Unrefined, the patch spans the hole with long edges.
  o.stage = FillStage::kTriangulate;
  const FillResult coarse = FillHoles(m, o);
  EXPECT_GT(
      MeanEdge(coarse.mesh, m.triangles.size(), coarse.mesh.triangles.size()),
      2.0 * around);
}

TEST(RefineFairTest, FairingKeepsAPlaneFlat) {
  const MeshData m = GridWithSquareHole(30, 8, 22);
  for (int continuity : {0, 1, 2}) {
    FillOptions o;
    o.fairing_continuity = continuity;
    o.selection.skip_longest = true;
    const FillResult r = FillHoles(m, o);
    testing::ExpectFilledMesh(m, r, /*closed=*/false, "grid");
    ASSERT_EQ(r.report.filled, 1);
    EXPECT_TRUE(Filled(r).faired) << Filled(r).reason;
    for (size_t v = m.vertices.size(); v < r.mesh.vertices.size(); ++v) {
      EXPECT_NEAR(r.mesh.vertices[v].z, 0, 1e-9) << continuity;
    }
  }
}

// The faired patch follows the sphere; the flat DOT patch does not.
TEST(RefineFairTest, FairingFollowsASphere) {
  const MeshData m = SphereWithCapCut(40, 80, 0.85);
  auto worst = [&](const FillResult& r) {
    double d = 0;
    for (size_t v = m.vertices.size(); v < r.mesh.vertices.size(); ++v) {
      d = std::max(d, std::fabs(Norm(r.mesh.vertices[v]) - 1));
    }
    // Centroids of the new faces measure flat patches too.
    for (size_t f = m.triangles.size(); f < r.mesh.triangles.size(); ++f) {
      const Triangle& t = r.mesh.triangles[f];
      const Vec3 c =
          (1.0 / 3) * (r.mesh.vertices[t[0]] + r.mesh.vertices[t[1]] +
                       r.mesh.vertices[t[2]]);
      d = std::max(d, std::fabs(Norm(c) - 1));
    }
    return d;
  };
  FillOptions o;
  const FillResult faired = FillHoles(m, o);
  testing::ExpectFilledMesh(m, faired, /*closed=*/true, "sphere");
  ASSERT_TRUE(faired.report.holes[0].faired);
  o.stage = FillStage::kTriangulate;
  const FillResult flat = FillHoles(m, o);
  std::printf("largest distance from the sphere: faired %.4f, DOT only %.4f\n",
              worst(faired), worst(flat));
  EXPECT_LT(worst(faired), 0.02);
  EXPECT_GT(worst(flat), 0.05);
}

// A floating square just inside the sphere's cap: the faired patch would
// pierce it, so fairing is undone and the refined patch, which stays below
// the square, is kept (and said so).
TEST(RefineFairTest, FairingThatWouldIntersectIsUndone) {
  MeshData m = SphereWithCapCut(40, 80, 0.85);
  const auto s = static_cast<int32_t>(m.vertices.size());
  for (const Vec3& p : {Vec3{0.96, -0.2, -0.2}, Vec3{0.96, 0.2, -0.2},
                        Vec3{0.96, 0.2, 0.2}, Vec3{0.96, -0.2, 0.2}}) {
    m.vertices.push_back(p);
  }
  m.triangles.push_back({s, s + 1, s + 2});
  m.triangles.push_back({s, s + 2, s + 3});
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(m, &loops).ok());
  FillOptions o;
  for (const HoleLoop& l : loops) {
    if (l.vertices.size() > 4) o.selection.ids.push_back(l.id);
  }
  ASSERT_EQ(o.selection.ids.size(), 1u);
  // The square floats over the hole, as an island would: here it is only
  // an obstacle, filled around, not joined.
  o.islands = IslandMode::kOff;
  const FillResult r = FillHoles(m, o);
  testing::ExpectFilledMesh(m, r, /*closed=*/false, "sphere and square");
  ASSERT_EQ(r.report.filled, 1);
  const HoleReport& h = r.report.holes[o.selection.ids[0]];
  EXPECT_FALSE(h.faired);
  EXPECT_GT(h.refined_vertices, 0);
  EXPECT_NE(h.reason.find("fairing undone"), std::string::npos) << h.reason;
  // Without the square the same hole is faired.
  const FillResult alone = FillHoles(SphereWithCapCut(40, 80, 0.85));
  EXPECT_TRUE(alone.report.holes[0].faired);
}

}  // namespace
}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
// Search space 'auto': when no Delaunay triangulation exists, the optimum
// over all triangles is accepted only when it is intersection-free.
#include <gtest/gtest.h>

#include <random>

#include "dot/dot.h"

namespace dot {
namespace {

struct Found {
  std::vector<Vec3> polygon;
  Result all;  // the unrestricted optimum
};

// Random hexagons (seeded) with no Delaunay triangulation whose
// all-triangles optimum does (`intersecting`) or does not self-intersect.
bool FindHexagon(bool intersecting, Found* out) {
  std::mt19937_64 rng(intersecting ? 11 : 12);
  std::uniform_real_distribution<double> u(-1, 1);
  Options delaunay, all;
  delaunay.space = SearchSpace::kDelaunay;
  all.space = SearchSpace::kAll;
  for (int attempt = 0; attempt < 200000; ++attempt) {
    std::vector<Vec3> p(6);
    for (Vec3& v : p) v = {u(rng), u(rng), u(rng)};
    Problem problem{p, {}, {}, {}, {}};
    if (Triangulate(problem, delaunay).status.code !=
        StatusCode::kNoTriangulation) {
      continue;
    }
    Result r = Triangulate(problem, all);
    if (!r.status.ok() || (r.intersecting_pairs > 0) != intersecting) continue;
    *out = {p, std::move(r)};
    return true;
  }
  return false;
}

TEST(AutoFallbackTest, SelfIntersectingOptimumIsNotOk) {
  Found f;
  ASSERT_TRUE(FindHexagon(true, &f));
  const Result r = Triangulate({f.polygon, {}, {}, {}, {}});
  EXPECT_EQ(r.status.code, StatusCode::kNoTriangulation);
  EXPECT_NE(r.status.message.find("self-intersects"), std::string::npos)
      << r.status.message;
  EXPECT_TRUE(r.triangles.empty());
}

TEST(AutoFallbackTest, IntersectionFreeOptimumIsAccepted) {
  Found f;
  ASSERT_TRUE(FindHexagon(false, &f));
  const Result r = Triangulate({f.polygon, {}, {}, {}, {}});
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_EQ(r.space_used, SpaceUsed::kAll);
  EXPECT_EQ(r.intersecting_pairs, 0);
  EXPECT_EQ(r.triangles, f.all.triangles);
  EXPECT_TRUE(ValidateMesh(r.vertices, r.polygon, r.triangles).valid());
}

}  // namespace
}  // namespace dot

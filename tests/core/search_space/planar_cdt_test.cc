// SPDX-License-Identifier: AGPL-3.0-or-later
// Planar and nearly planar polygons are triangulated over the 2D constrained
// Delaunay triangulation of their dominant plane; self-intersecting ones are
// rejected by name.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dot/dot.h"
#include "fixtures/checks.h"

namespace dot {
namespace {

using testing::ExpectValidDisk;

std::vector<Vec3> RegularPolygon(int n, double radius = 1) {
  std::vector<Vec3> v;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPi * i / n;
    v.push_back({radius * std::cos(t), radius * std::sin(t), 0});
  }
  return v;
}

// Rotates about an oblique axis: coordinates stop being exactly planar.
std::vector<Vec3> Tilt(std::vector<Vec3> v) {
  const double a = 0.7, b = 0.4;
  for (Vec3& p : v) {
    const Vec3 q{p.x, p.y * std::cos(a) - p.z * std::sin(a),
                 p.y * std::sin(a) + p.z * std::cos(a)};
    p = {q.x * std::cos(b) + q.z * std::sin(b), q.y,
         -q.x * std::sin(b) + q.z * std::cos(b)};
  }
  return v;
}

// A star: alternating outer and inner radii (non-convex).
std::vector<Vec3> Star(int spikes) {
  std::vector<Vec3> v;
  for (int i = 0; i < 2 * spikes; ++i) {
    const double t = kPi * i / spikes, r = i % 2 ? 0.35 : 1.0;
    v.push_back({r * std::cos(t), r * std::sin(t), 2.0});
  }
  return v;
}

// A comb: a non-convex, non-star-shaped planar polygon with many teeth.
std::vector<Vec3> Comb(int teeth) {
  std::vector<Vec3> v = {{0, 0, 0}};
  for (int i = 0; i < teeth; ++i) {
    v.push_back({2.0 * i + 1, 0, 0});
    v.push_back({2.0 * i + 1, 5, 0});
    v.push_back({2.0 * i + 2, 5, 0});
    v.push_back({2.0 * i + 2, 0.5, 0});
  }
  v.push_back({2.0 * teeth + 1, 0, 0});
  v.push_back({2.0 * teeth + 1, -1, 0});
  v.push_back({0, -1, 0});
  return v;
}

TEST(PlanarTest, ConvexCocircularPolygon) {
  for (int n : {3, 4, 5, 12, 100, 1000}) {
    const Result r = Triangulate({RegularPolygon(n), {}, {}, {}, {}});
    ExpectValidDisk(r);
    EXPECT_TRUE(r.planar);
    EXPECT_EQ(r.space_used, SpaceUsed::kPlanarDelaunay2d);
    EXPECT_EQ(r.triangles.size(), static_cast<size_t>(n - 2));
  }
}

TEST(PlanarTest, NonConvexPolygons) {
  for (const auto& v : {Star(7), Star(50), Comb(3), Comb(40)}) {
    for (bool bi : {false, true}) {
      Problem p{v, {}, {}, {}, {}};
      p.weights[bi ? Metric::kSquaredDihedral : Metric::kPerimeter] = 1;
      const Result r = Triangulate(p);
      ExpectValidDisk(r);
      EXPECT_TRUE(r.planar);
    }
  }
}

TEST(PlanarTest, TiltedAndNoisyPlanesStayPlanar) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> noise(-1e-9, 1e-9);
  for (auto v : {Tilt(Star(9)), Tilt(Comb(10)), Tilt(RegularPolygon(64))}) {
    for (Vec3& p : v) p.z += noise(rng);
    const Result r = Triangulate({v, {}, {}, {}, {}});
    ExpectValidDisk(r);
    EXPECT_TRUE(r.planar);
    EXPECT_EQ(r.space_used, SpaceUsed::kPlanarDelaunay2d);
  }
}

// Found by tests/fuzz/triangulate_fuzz: with planar_tolerance 0, the plane
// fit's rounding made this exactly planar quadrilateral non-planar, so it
// went to the 3D Delaunay step (CGAL refused it as coplanar, TetGen crashed
// the process). Exact predicates now decide exact planarity and
// collinearity, whatever the tolerance.
TEST(PlanarTest, ExactlyPlanarIsPlanarAtZeroTolerance) {
  const std::vector<Vec3> quad = {
      {-3, -2, 3}, {-1, -3, 3}, {-2, -3, 0}, {-3, -3, -3}};
  Options exact;
  exact.planar_tolerance = 0;
  for (DelaunayBackend b : {DelaunayBackend::kCgal, DelaunayBackend::kTetgen}) {
    if (b == DelaunayBackend::kTetgen && !TetgenAvailable()) continue;
    exact.delaunay = b;
    const Result r = Triangulate({quad, {}, {}, {}, {}}, exact);
    ExpectValidDisk(r);
    EXPECT_TRUE(r.planar);
    EXPECT_EQ(r.space_used, SpaceUsed::kPlanarDelaunay2d);
  }
  // Exactly collinear: refused as such (it was "coplanar", from CGAL).
  const std::vector<Vec3> line = {
      {1, 2, 3}, {4, 7, 10}, {7, 12, 17}, {10, 17, 24}};
  const Result r = Triangulate({line, {}, {}, {}, {}}, exact);
  EXPECT_EQ(r.status.code, StatusCode::kInvalidArgument);
  EXPECT_NE(r.status.message.find("collinear"), std::string::npos)
      << r.status.message;
}

TEST(PlanarTest, SelfIntersectingPlanarPolygonIsRejected) {
  // A bow tie: edges 1-2 and 3-0 cross.
  const std::vector<Vec3> bowtie = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  const Result r = Triangulate({bowtie, {}, {}, {}, {}});
  EXPECT_EQ(r.status.code, StatusCode::kInvalidArgument);
  EXPECT_NE(r.status.message.find("self-intersecting: edge 0-1 meets edge 2-3"),
            std::string::npos)
      << r.status.message;
  // A polygon touching itself at a vertex.
  const std::vector<Vec3> touching = {
      {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {1, 0, 0}, {0, 2, 0}};
  EXPECT_EQ(Triangulate({touching, {}, {}, {}, {}}).status.code,
            StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace dot

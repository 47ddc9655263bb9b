// SPDX-License-Identifier: AGPL-3.0-or-later
// Planar, nearly planar, cospherical and convex-hull polygons (paper, Lemma
// 4.4), and edge protection.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dot/dot.h"
#include "mesh/edge_index.h"

namespace dot {
namespace {

constexpr double kPi = 3.14159265358979323846;

void ExpectValidDisk(const Result& r) {
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  const MeshReport report = ValidateMesh(r.vertices, r.polygon, r.triangles);
  EXPECT_TRUE(report.valid()) << report.first_problem;
  EXPECT_EQ(report.intersecting_pairs, 0);
}

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
    const Result r = Triangulate({RegularPolygon(n), {}, {}});
    ExpectValidDisk(r);
    EXPECT_TRUE(r.planar);
    EXPECT_EQ(r.space_used, SpaceUsed::kPlanarDelaunay2d);
    EXPECT_EQ(r.triangles.size(), static_cast<size_t>(n - 2));
  }
}

TEST(PlanarTest, NonConvexPolygons) {
  for (const auto& v : {Star(7), Star(50), Comb(3), Comb(40)}) {
    for (bool bi : {false, true}) {
      Problem p{v, {}, {}};
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
    const Result r = Triangulate({v, {}, {}});
    ExpectValidDisk(r);
    EXPECT_TRUE(r.planar);
    EXPECT_EQ(r.space_used, SpaceUsed::kPlanarDelaunay2d);
  }
}

TEST(PlanarTest, SelfIntersectingPlanarPolygonIsRejected) {
  // A bow tie: edges 1-2 and 3-0 cross.
  const std::vector<Vec3> bowtie = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  const Result r = Triangulate({bowtie, {}, {}});
  EXPECT_EQ(r.status.code, StatusCode::kInvalidArgument);
  EXPECT_NE(r.status.message.find("self-intersecting: edge 0-1 meets edge 2-3"),
            std::string::npos)
      << r.status.message;
  // A polygon touching itself at a vertex.
  const std::vector<Vec3> touching = {
      {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {1, 0, 0}, {0, 2, 0}};
  EXPECT_EQ(Triangulate({touching, {}, {}}).status.code,
            StatusCode::kInvalidArgument);
}

TEST(DegenerateTest, CosphericalCubeVertices) {
  const std::vector<Vec3> cube = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                  {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, {0, 0, 1}};
  for (bool bi : {false, true}) {
    Problem p{cube, {}, {}};
    p.weights[bi ? Metric::kSquaredDihedral : Metric::kArea] = 1;
    Options o;
    o.space = SearchSpace::kDelaunay;
    ExpectValidDisk(Triangulate(p, o));
  }
}

TEST(DegenerateTest, CollinearRunsAndSquareWithMidpoints) {
  // A 3D polygon with three collinear consecutive vertices on each edge.
  const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 1},
                               {2, 2, 2}, {1, 2, 1}, {0, 2, 0}, {0, 1, 0.5}};
  ExpectValidDisk(Triangulate({v, {}, {}}));
  const std::vector<Vec3> square = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0},
                                    {2, 2, 0}, {1, 2, 0}, {0, 2, 0}, {0, 1, 0}};
  const Result r = Triangulate({square, {}, {}});
  ExpectValidDisk(r);
  EXPECT_TRUE(r.planar);
}

// Lemma 4.4: a polygon whose edges are Delaunay and on the convex hull is
// always Delaunay-triangulable. Polygons: perturbed zigzags between two
// circles of a cylinder (every vertex is extreme).
TEST(Lemma44Test, HullPolygonsWithDelaunayEdgesAlwaysSucceed) {
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<double> u(0, 1);
  int premise_held = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 2 * (3 + trial % 30);
    std::vector<Vec3> v;
    for (int i = 0; i < n; ++i) {
      const double t = 2 * kPi * (i + 0.4 * u(rng)) / n;
      const double z = i % 2 ? 0.7 + 0.3 * u(rng) : 0.3 * u(rng);
      v.push_back({std::cos(t), std::sin(t), z});
    }
    Tetrahedralization tets;
    ASSERT_TRUE(TetgenTetrahedralize(v, &tets).ok());
    std::vector<uint64_t> hull_edges, delaunay_edges;
    for (const auto& tet : tets.tets) {
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          delaunay_edges.push_back(UndirectedEdgeKey(tet[i], tet[j]));
    }
    // Hull faces: faces listed once among all tetrahedra.
    std::vector<Triangle> faces;
    for (const auto& tet : tets.tets) {
      for (int skip = 0; skip < 4; ++skip) {
        Triangle f;
        int k = 0;
        for (int c = 0; c < 4; ++c)
          if (c != skip) f[k++] = tet[c];
        std::sort(f.begin(), f.end());
        faces.push_back(f);
      }
    }
    std::sort(faces.begin(), faces.end());
    for (size_t i = 0; i < faces.size();) {
      size_t j = i;
      while (j < faces.size() && faces[j] == faces[i]) ++j;
      if (j - i == 1) {
        const Triangle& f = faces[i];
        hull_edges.push_back(UndirectedEdgeKey(f[0], f[1]));
        hull_edges.push_back(UndirectedEdgeKey(f[1], f[2]));
        hull_edges.push_back(UndirectedEdgeKey(f[0], f[2]));
      }
      i = j;
    }
    std::sort(hull_edges.begin(), hull_edges.end());
    std::sort(delaunay_edges.begin(), delaunay_edges.end());
    bool premise = true;
    for (int i = 0; i < n; ++i) {
      const uint64_t e = UndirectedEdgeKey(i, (i + 1) % n);
      premise &=
          std::binary_search(hull_edges.begin(), hull_edges.end(), e) &&
          std::binary_search(delaunay_edges.begin(), delaunay_edges.end(), e);
    }
    if (!premise) continue;
    ++premise_held;
    for (bool bi : {false, true}) {
      Problem p{v, {}, {}};
      p.weights[bi ? Metric::kSquaredDihedral : Metric::kArea] = 1;
      Options o;
      o.space = SearchSpace::kDelaunay;
      const Result r = Triangulate(p, o);
      ExpectValidDisk(r);
    }
  }
  EXPECT_GT(premise_held, 100);  // the lemma's premise must really be tested
}

TEST(EdgeProtectionTest, SplitsNonDelaunayEdgesUntilAllAreDelaunay) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int protected_cases = 0;
  for (int trial = 0; trial < 400 && protected_cases < 20; ++trial) {
    std::vector<Vec3> v;
    for (int i = 0; i < 9; ++i) v.push_back({u(rng), u(rng), u(rng)});
    Options plain;
    plain.space = SearchSpace::kDelaunay;
    const Result before = Triangulate({v, {}, {}}, plain);
    if (before.non_delaunay_edges.empty()) continue;
    ++protected_cases;
    EXPECT_EQ(before.status.code, StatusCode::kNoTriangulation);
    EXPECT_NE(before.status.message.find("not on any Delaunay triangle"),
              std::string::npos);
    Options o = plain;
    o.protect_edges = true;
    const Result after = Triangulate({v, {}, {}}, o);
    EXPECT_TRUE(after.non_delaunay_edges.empty()) << after.status.message;
    EXPECT_FALSE(after.inserted.empty());
    EXPECT_EQ(after.vertices.size(), v.size() + after.inserted.size());
    EXPECT_EQ(after.polygon.size(), after.vertices.size());
    // Input vertices keep their indices and coordinates.
    for (size_t i = 0; i < v.size(); ++i) EXPECT_EQ(after.vertices[i], v[i]);
    if (after.status.ok()) ExpectValidDisk(after);
  }
  EXPECT_EQ(protected_cases, 20);
}

}  // namespace
}  // namespace dot

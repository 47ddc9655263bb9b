// SPDX-License-Identifier: AGPL-3.0-or-later
// The 3D Delaunay search space: cospherical and collinear input, convex-hull
// polygons (paper, Lemma 4.4), and edge protection (Lemma 4.3).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "dot/dot.h"
#include "fixtures/checks.h"
#include "mesh/edge_index.h"

namespace dot {
namespace {

using testing::ExpectValidDisk;

TEST(DegenerateTest, CosphericalCubeVertices) {
  const std::vector<Vec3> cube = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                  {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, {0, 0, 1}};
  for (bool bi : {false, true}) {
    Problem p{cube, {}, {}, {}, {}};
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
  ExpectValidDisk(Triangulate({v, {}, {}, {}, {}}));
  const std::vector<Vec3> square = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0},
                                    {2, 2, 0}, {1, 2, 0}, {0, 2, 0}, {0, 1, 0}};
  const Result r = Triangulate({square, {}, {}, {}, {}});
  ExpectValidDisk(r);
  EXPECT_TRUE(r.planar);
}

// Lemma 4.4: a polygon whose edges are Delaunay and on the convex hull is
// always Delaunay-triangulable. Polygons: perturbed zigzags between two
// circles of a cylinder (every vertex is extreme).
TEST(Lemma44Test, HullPolygonsWithDelaunayEdgesAlwaysSucceed) {
  DOT_SKIP_WITHOUT_TETGEN();  // its tetrahedra tell the hull faces
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
    // Every face of every tetrahedron; hull faces are those listed once.
    std::vector<Triangle> faces, hull;
    for (const auto& tet : tets.tets) {
      for (int skip = 0; skip < 4; ++skip) {
        Triangle f;
        int k = 0;
        for (int c = 0; c < 4; ++c) {
          if (c != skip) f[k++] = tet[c];
        }
        std::sort(f.begin(), f.end());
        faces.push_back(f);
      }
    }
    std::sort(faces.begin(), faces.end());
    for (size_t i = 0; i < faces.size(); ++i) {
      const bool twice = (i > 0 && faces[i - 1] == faces[i]) ||
                         (i + 1 < faces.size() && faces[i + 1] == faces[i]);
      if (!twice) hull.push_back(faces[i]);
    }
    const EdgeIndex delaunay_edges = BuildEdgeIndex(faces);
    const EdgeIndex hull_edges = BuildEdgeIndex(hull);
    bool premise = true;
    for (int i = 0; i < n; ++i) {
      premise &= HasEdge(hull_edges, i, (i + 1) % n) &&
                 HasEdge(delaunay_edges, i, (i + 1) % n);
    }
    if (!premise) continue;
    ++premise_held;
    for (bool bi : {false, true}) {
      Problem p{v, {}, {}, {}, {}};
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
    const Result before = Triangulate({v, {}, {}, {}, {}}, plain);
    if (before.non_delaunay_edges.empty()) continue;
    ++protected_cases;
    EXPECT_EQ(before.status.code, StatusCode::kNoTriangulation);
    EXPECT_NE(before.status.message.find("not on any Delaunay triangle"),
              std::string::npos);
    Options o = plain;
    o.protect_edges = true;
    const Result after = Triangulate({v, {}, {}, {}, {}}, o);
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

// SPDX-License-Identifier: AGPL-3.0-or-later
// The two 3D Delaunay backends agree: identical faces (and so identical
// results) wherever no five vertices are cospherical, where the Delaunay
// tetrahedralization is unique. CGAL reports degenerate input by name; a
// build without TetGen refuses TetGen requests.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "dot/dot.h"
#include "fixtures/checks.h"
#include "fixtures/meshes.h"
#include "search_space/delaunay_cgal.h"
#include "search_space/faces_of_tetrahedra.h"

namespace dot {
namespace {

std::vector<Triangle> Sorted(std::vector<Triangle> faces) {
  std::sort(faces.begin(), faces.end());
  return faces;
}

void ExpectSameFaces(const std::vector<Vec3>& points) {
  std::vector<Triangle> cgal;
  int64_t cgal_tets = 0;
  ASSERT_TRUE(CgalDelaunayFaces(points, {}, &cgal, &cgal_tets).ok());
  Tetrahedralization tets;
  ASSERT_TRUE(TetgenTetrahedralize(points, &tets).ok());
  std::vector<Triangle> tetgen;
  ASSERT_TRUE(FacesOfTetrahedra(tets, &tetgen).ok());
  EXPECT_EQ(cgal_tets, static_cast<int64_t>(tets.tets.size()));
  ASSERT_EQ(cgal.size(), tetgen.size());
  EXPECT_TRUE(Sorted(cgal) == Sorted(tetgen));
}

// Uniform random points: in general position with probability one.
std::vector<Vec3> RandomPoints(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> p(n);
  for (Vec3& v : p) v = {u(rng), u(rng), u(rng)};
  return p;
}

TEST(DelaunayBackendsTest, SameFacesOnRandomPoints) {
  DOT_SKIP_WITHOUT_TETGEN();
  uint32_t seed = 7;
  for (int n : {5, 12, 100, 1000, 5000}) {
    SCOPED_TRACE(n);
    ExpectSameFaces(RandomPoints(n, seed++));
  }
}

TEST(DelaunayBackendsTest, SameFacesAndResultsOnScannedMeshHoles) {
  DOT_SKIP_WITHOUT_TETGEN();
  MeshData mesh;
  const std::string path = testing::MeshPath("elephant.off");
  ASSERT_TRUE(ReadMeshFile(path, &mesh).ok()) << path;
  int compared = 0;
  for (int size : {50, 200, 800}) {
    for (uint64_t seed = 1; seed <= 3; ++seed) {
      Hole hole;
      if (!GrowHole(mesh, size, seed, &hole).ok()) continue;
      SCOPED_TRACE(::testing::Message() << size << " triangles, seed " << seed);
      ExpectSameFaces(hole.boundary.vertices);
      Problem p{hole.boundary.vertices, {}, {}, {}, {}};
      p.weights[Metric::kSquaredDihedral] = 1;
      p.weights[Metric::kArea] = 1;
      Options cgal, tetgen;
      tetgen.delaunay = DelaunayBackend::kTetgen;
      const Result a = Triangulate(p, cgal);
      const Result b = Triangulate(p, tetgen);
      EXPECT_EQ(a.status.code, b.status.code);
      EXPECT_EQ(a.triangles, b.triangles);
      EXPECT_EQ(a.total_cost, b.total_cost);
      ++compared;
    }
  }
  EXPECT_GE(compared, 6);
}

TEST(DelaunayBackendsTest, CgalReportsCoincidentAndCoplanarPoints) {
  std::vector<Triangle> faces;
  int64_t tets = 0;
  std::vector<Vec3> twice = RandomPoints(20, 3);
  twice.push_back(twice[4]);
  Status s = CgalDelaunayFaces(twice, {}, &faces, &tets);
  EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
  EXPECT_NE(s.message.find("coincide"), std::string::npos) << s.message;

  std::vector<Vec3> flat = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  s = CgalDelaunayFaces(flat, {}, &faces, &tets);
  EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
  EXPECT_NE(s.message.find("coplanar"), std::string::npos) << s.message;
}

TEST(DelaunayBackendsTest, ResultReportsTheBackendUsed) {
  DOT_SKIP_WITHOUT_TETGEN();
  Problem p{MakeCurve(Curve::kSpiral, 300), {}, {}, {}, {}};
  for (DelaunayBackend b : {DelaunayBackend::kCgal, DelaunayBackend::kTetgen}) {
    Options o;
    o.delaunay = b;
    const Result r = Triangulate(p, o);
    ASSERT_TRUE(r.status.ok()) << r.status.message;
    EXPECT_EQ(r.delaunay, b);
    EXPECT_EQ(r.space_used, SpaceUsed::kDelaunay3d);
    const MeshReport report = ValidateMesh(r.vertices, r.polygon, r.triangles);
    EXPECT_TRUE(report.valid())
        << DelaunayBackendName(b) << ": " << report.first_problem;
  }
  EXPECT_EQ(DelaunayBackendFromName("tetgen"), DelaunayBackend::kTetgen);
  EXPECT_EQ(DelaunayBackendFromName("cgal"), DelaunayBackend::kCgal);
  EXPECT_EQ(DelaunayBackendFromName("qhull"), std::nullopt);
}

// Found by tests/fuzz/request_fuzz: a coordinate at the bottom of the
// double range (2^-1022 next to 4) underflows TetGen's predicates, and with
// edge protection the "Delaunay" patch self-intersected, answered OK.
// TetGen now refuses what it cannot decide exactly; CGAL decides it.
TEST(DelaunayBackendsTest, TetgenRefusesCoordinatesItsPredicatesUnderflowOn) {
  DOT_SKIP_WITHOUT_TETGEN();
  const std::vector<Vec3> polygon = {{0, 0, 0},
                                     {4.00390625, 0, 0},
                                     {4, 6.103515625e-05, 1.0000000000000553},
                                     {0x1p-1022, 4, 0},
                                     {2, 2, 3.04541015625},
                                     {1, 3, -2},
                                     {3, 1.0000009536743162, 2}};
  Options o;
  o.space = SearchSpace::kDelaunay;
  o.protect_edges = true;
  o.delaunay = DelaunayBackend::kTetgen;
  const Result tetgen = Triangulate({polygon, {}, {}, {}, {}}, o);
  EXPECT_EQ(tetgen.status.code, StatusCode::kInvalidArgument);
  EXPECT_NE(tetgen.status.message.find("use the cgal backend"),
            std::string::npos)
      << tetgen.status.message;
  o.delaunay = DelaunayBackend::kCgal;
  testing::ExpectValidDisk(Triangulate({polygon, {}, {}, {}, {}}, o));
}

// Without TetGen (DOT_WITH_TETGEN=OFF) CGAL is the only backend: TetGen
// requests are refused with a message that says what to use instead.
TEST(DelaunayBackendsTest, BuildWithoutTetgenRefusesItClearly) {
  if (TetgenAvailable()) GTEST_SKIP() << "this build has TetGen";
  const std::string expected =
      "this build has no TetGen backend (built with DOT_WITH_TETGEN=OFF); use "
      "cgal";
  Options tetgen;
  tetgen.delaunay = DelaunayBackend::kTetgen;
  for (const auto& loop :
       {MakeCurve(Curve::kSpiral, 300),
        std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}) {
    const Result r = Triangulate({loop, {}, {}, {}, {}}, tetgen);
    EXPECT_EQ(r.status.code, StatusCode::kInvalidArgument);
    EXPECT_EQ(r.status.message, expected);
    EXPECT_TRUE(r.triangles.empty());
  }
  Tetrahedralization tets;
  const Status s = TetgenTetrahedralize(RandomPoints(10, 1), &tets);
  EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message, expected);
  // The default backend is unaffected.
  testing::ExpectValidDisk(
      Triangulate({MakeCurve(Curve::kSpiral, 300), {}, {}, {}, {}}));
}

}  // namespace
}  // namespace dot

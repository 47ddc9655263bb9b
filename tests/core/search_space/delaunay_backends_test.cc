// SPDX-License-Identifier: AGPL-3.0-or-later
// The two 3D Delaunay backends agree: identical faces (and so identical
// results) wherever no five vertices are cospherical, where the Delaunay
// tetrahedralization is unique.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "dot/dot.h"
#include "search_space/delaunay_cgal.h"
#include "search_space/faces_of_tetrahedra.h"
#include "solve/adjacency.h"
#include "solve/solvers.h"

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
  uint32_t seed = 7;
  for (int n : {5, 12, 100, 1000, 5000}) {
    SCOPED_TRACE(n);
    ExpectSameFaces(RandomPoints(n, seed++));
  }
}

TEST(DelaunayBackendsTest, SameFacesAndResultsOnScannedMeshHoles) {
  MeshData mesh;
  const std::string path = std::string(DOT_MESH_DIR) + "/elephant.off";
  ASSERT_TRUE(ReadMeshFile(path, &mesh).ok()) << path;
  int compared = 0;
  for (int size : {50, 200, 800}) {
    for (uint64_t seed = 1; seed <= 3; ++seed) {
      Hole hole;
      if (!GrowHole(mesh, size, seed, &hole).ok()) continue;
      SCOPED_TRACE(testing::Message() << size << " triangles, seed " << seed);
      ExpectSameFaces(hole.boundary.vertices);
      Problem p{hole.boundary.vertices, {}, {}};
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
                                  {0, 1}, {}, &sol)
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
  Problem p{MakeCurve(Curve::kSpiral, 300), {}, {}};
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
  DelaunayBackend parsed;
  EXPECT_TRUE(ParseDelaunayBackend("tetgen", &parsed));
  EXPECT_EQ(parsed, DelaunayBackend::kTetgen);
  EXPECT_FALSE(ParseDelaunayBackend("qhull", &parsed));
}

}  // namespace
}  // namespace dot

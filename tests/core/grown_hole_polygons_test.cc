// SPDX-License-Identifier: AGPL-3.0-or-later
// Holes grown on meshes (paper, section 5.1) are filled with valid,
// intersection-free triangulations that respect the boundary normals.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "dot/dot.h"
#include "fixtures/meshes.h"

namespace dot {
namespace {

using testing::BumpyTorus;
using testing::MeshPath;

void TriangulateGrownHoles(const MeshData& mesh, const std::vector<int>& sizes,
                           int* filled, int* attempted) {
  uint64_t seed = 1;
  for (int size : sizes) {
    Hole hole;
    const Status s = GrowHole(mesh, size, seed++, &hole);
    if (!s.ok()) continue;  // no room for this hole around the seed
    ++*attempted;
    EXPECT_EQ(hole.triangles, size);
    EXPECT_EQ(hole.boundary.normals.size(), hole.boundary.vertices.size());
    Problem p{hole.boundary.vertices, hole.boundary.normals, {}, {}, {}};
    p.weights[Metric::kArea] = 1;
    p.weights[Metric::kNormalDeviation] = 0.1;
    p.weights[Metric::kSquaredDihedral] = 0.5;
    Options o;
    o.protect_edges = true;
    o.space = SearchSpace::kDelaunay;
    const Result r = Triangulate(p, o);
    if (r.status.code == StatusCode::kNoTriangulation) continue;
    ASSERT_TRUE(r.status.ok()) << r.status.message;
    ++*filled;
    const MeshReport report = ValidateMesh(r.vertices, r.polygon, r.triangles);
    EXPECT_TRUE(report.valid())
        << "hole of " << size << ": " << report.first_problem;
    EXPECT_EQ(report.intersecting_pairs, 0);
  }
}

TEST(HolesTest, FillsHolesOnASyntheticTorus) {
  int filled = 0, attempted = 0;
  TriangulateGrownHoles(BumpyTorus(80, 40),
                        {10, 30, 60, 100, 200, 300, 500, 800, 1000, 1500},
                        &filled, &attempted);
  EXPECT_EQ(attempted, 10);
  EXPECT_GE(filled, 9);
}

// Real scanned meshes from Debian's libcgal-demo (extracted at build time).
TEST(HolesTest, FillsHolesOnRealMeshes) {
  int filled = 0, attempted = 0;
  for (const char* name : {"elephant.off", "armadillo.off"}) {
    const std::string path = MeshPath(name);
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " missing";
    MeshData mesh;
    ASSERT_TRUE(ReadMeshFile(path, &mesh).ok());
    TriangulateGrownHoles(mesh,
                          {20, 50, 100, 150, 200, 300, 400, 600, 800, 1000},
                          &filled, &attempted);
  }
  EXPECT_GE(attempted, 15);
  EXPECT_GE(filled, attempted * 8 / 10);
  std::printf("filled %d of %d holes\n", filled, attempted);
}

}  // namespace
}  // namespace dot

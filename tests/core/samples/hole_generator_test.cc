// SPDX-License-Identifier: AGPL-3.0-or-later
// The hole generator cuts disk-shaped holes with simple boundary loops, and
// refuses holes the mesh has no room for.
#include <gtest/gtest.h>

#include "dot/dot.h"
#include "fixtures/meshes.h"

namespace dot {
namespace {

using testing::BumpyTorus;

TEST(HoleGeneratorTest, GrowHoleKeepsASimpleBoundaryLoop) {
  const MeshData torus = BumpyTorus(60, 30);
  for (int size : {1, 2, 10, 100, 500}) {
    Hole hole;
    ASSERT_TRUE(GrowHole(torus, size, 42 + size, &hole).ok());
    EXPECT_EQ(hole.triangles, size);
    // A disk of t triangles whose vertices are all on the boundary has
    // t + 2 boundary vertices; interior vertices only shorten it.
    EXPECT_LE(hole.boundary.vertices.size(), static_cast<size_t>(size) + 2);
    EXPECT_GE(hole.boundary.vertices.size(), 3u);
  }
  Hole hole;
  EXPECT_FALSE(GrowHole(torus, 4 * 3600, 1, &hole).ok());
}

TEST(HoleGeneratorTest, BoundaryNormalsAreTheKeptSurfaceNormals) {
  // The torus is oriented outwards, so the normals of the triangles that
  // remain, and so each boundary normal, point away from the tube's core
  // circle (radius 2 in the plane z = 0).
  const MeshData torus = BumpyTorus(60, 30);
  Hole hole;
  ASSERT_TRUE(GrowHole(torus, 40, 7, &hole).ok());
  ASSERT_EQ(hole.boundary.normals.size(), hole.boundary.vertices.size());
  for (size_t i = 0; i < hole.boundary.vertices.size(); ++i) {
    const Vec3& p = hole.boundary.vertices[i];
    const Vec3 core = 2 * Normalized(Vec3{p.x, p.y, 0});
    EXPECT_NEAR(Norm(hole.boundary.normals[i]), 1, 1e-12);
    EXPECT_GT(Dot(hole.boundary.normals[i], p - core), 0) << i;
  }
}

TEST(HoleGeneratorTest, SameSeedSameHole) {
  const MeshData torus = BumpyTorus(40, 20);
  Hole a, b, c;
  ASSERT_TRUE(GrowHole(torus, 60, 3, &a).ok());
  ASSERT_TRUE(GrowHole(torus, 60, 3, &b).ok());
  ASSERT_TRUE(GrowHole(torus, 60, 4, &c).ok());
  EXPECT_EQ(a.boundary.vertices, b.boundary.vertices);
  EXPECT_NE(a.boundary.vertices, c.boundary.vertices);
}

TEST(HoleGeneratorTest, RejectsSizesOutsideTheMesh) {
  const MeshData torus = BumpyTorus(10, 6);
  Hole hole;
  EXPECT_EQ(GrowHole(torus, 0, 1, &hole).code, StatusCode::kInvalidArgument);
  const Status s = GrowHole(torus, 120, 1, &hole);
  EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
  EXPECT_NE(s.message.find("between 1 and the mesh's 120 triangles"),
            std::string::npos)
      << s.message;
}

}  // namespace
}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
// FaceTree against a scan of every face, on random boxes over a bumpy
// torus: nothing that can meet a box is missed (a face with a corner inside
// it), nothing whose own box misses it is given, and the ids come sorted.
#include "mesh/face_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "fixtures/meshes.h"

namespace dot {
namespace {

bool Inside(const Vec3& p, const Box3& b) {
  return b.lo.x <= p.x && p.x <= b.hi.x && b.lo.y <= p.y && p.y <= b.hi.y &&
         b.lo.z <= p.z && p.z <= b.hi.z;
}

TEST(FaceTreeTest, AgreesWithAScanOfEveryFace) {
  const MeshData mesh = testing::BumpyTorus(80, 40);
  const FaceTree tree(mesh);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> at(-2.6, 2.6), size(0.0, 0.5);
  int nonempty = 0;
  for (int q = 0; q < 300; ++q) {
    Box3 box;
    const Vec3 c{at(rng), at(rng), 0.2 * at(rng)};
    const Vec3 half{size(rng), size(rng), size(rng)};
    box.Add(c - half);
    box.Add(c + half);
    std::vector<int32_t> found{-1};  // appended to, not replaced
    tree.FacesMeeting(box, &found);
    ASSERT_EQ(found[0], -1);
    found.erase(found.begin());
    ASSERT_TRUE(std::is_sorted(found.begin(), found.end()));
    std::vector<bool> given(mesh.triangles.size(), false);
    for (int32_t f : found) given[f] = true;
    for (size_t f = 0; f < mesh.triangles.size(); ++f) {
      Box3 own;
      bool corner_inside = false;
      for (int32_t v : mesh.triangles[f]) {
        own.Add(mesh.vertices[v]);
        corner_inside = corner_inside || Inside(mesh.vertices[v], box);
      }
      if (corner_inside) {
        EXPECT_TRUE(given[f]) << "missed face " << f;
      }
      if (!own.Meets(box)) {
        EXPECT_FALSE(given[f]) << "far face " << f;
      }
    }
    nonempty += !found.empty();
  }
  EXPECT_GT(nonempty, 100);  // the boxes did reach the surface
}

TEST(FaceTreeTest, AnEmptyBoxOrMeshFindsNothing) {
  const MeshData mesh = testing::BumpyTorus(8, 4);
  std::vector<int32_t> found;
  FaceTree(mesh).FacesMeeting(Box3{}, &found);
  EXPECT_TRUE(found.empty());
  Box3 all;
  all.Add({-9, -9, -9});
  all.Add({9, 9, 9});
  FaceTree(MeshData{}).FacesMeeting(all, &found);
  EXPECT_TRUE(found.empty());
}

}  // namespace
}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
// FaceTree against a scan of every face, on random boxes over a bumpy
// torus: exactly the faces whose own box meets the query's are given, in
// increasing order; the tree's float boxes miss nothing at the edges of
// double precision or at coordinates beyond float's range.
#include "mesh/face_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
      EXPECT_EQ(given[f], own.Meets(box)) << "face " << f;
    }
    nonempty += !found.empty();
  }
  EXPECT_GT(nonempty, 100);  // the boxes did reach the surface
}

TEST(FaceTreeTest, BoxesThatTouchInOnePointAreFoundAtAnyScale) {
  // Coordinates a float cannot hold exactly (and some beyond its range):
  // a query that touches a face's box only at its corner still finds it.
  for (double scale : {1.0, 1e-30, 1e30, 1e300}) {
    // 0.7f < 0.7: a box rounded to nearest would miss the corner.
    const double a = 0.1 * scale, b = 0.7 * scale;
    MeshData mesh{{{a, a, a}, {b, a, a}, {a, b, b}, {-b, -b, -b}},
                  {{0, 1, 2}, {0, 2, 3}}};
    const FaceTree tree(mesh);
    Box3 corner;  // the single point (b, b, b): face 0's box's corner
    corner.Add({b, b, b});
    std::vector<int32_t> found;
    tree.FacesMeeting(corner, &found);
    EXPECT_EQ(found, std::vector<int32_t>{0}) << scale;
    Box3 beyond;  // just past it
    beyond.Add({std::nextafter(b, 2 * b), b, b});
    found.clear();
    tree.FacesMeeting(beyond, &found);
    EXPECT_TRUE(found.empty()) << scale;
  }
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

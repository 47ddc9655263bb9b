// SPDX-License-Identifier: AGPL-3.0-or-later
// The validator must catch each kind of defect it promises to catch.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>

#include "dot/dot.h"
#include "fixtures/meshes.h"

namespace dot {
namespace {

// A square pyramid's open side surface spanning the square 0-1-2-3.
const std::vector<Vec3> kSquare = {
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}};
const std::vector<int32_t> kLoop = {0, 1, 2, 3};

TEST(ValidateTest, AcceptsAValidDisk) {
  const MeshReport r = ValidateMesh(kSquare, kLoop, {{0, 1, 2}, {0, 2, 3}});
  EXPECT_TRUE(r.valid()) << r.first_problem;
  EXPECT_TRUE(r.disk);
  EXPECT_TRUE(r.boundary_is_polygon);
  EXPECT_EQ(r.intersecting_pairs, 0);
}

TEST(ValidateTest, DetectsMisorientation) {
  const MeshReport r = ValidateMesh(kSquare, kLoop, {{0, 1, 2}, {0, 3, 2}});
  EXPECT_EQ(r.misoriented_edges, 1);
  EXPECT_FALSE(r.valid());
}

TEST(ValidateTest, DetectsWrongBoundary) {
  const MeshReport r = ValidateMesh(kSquare, kLoop, {{0, 1, 2}});
  EXPECT_FALSE(r.boundary_is_polygon);
  EXPECT_FALSE(r.valid());
}

TEST(ValidateTest, DetectsNonManifoldEdgeAndDegenerateTriangle) {
  const MeshReport r =
      ValidateMesh(kSquare, kLoop, {{0, 1, 2}, {0, 2, 3}, {2, 0, 4}});
  EXPECT_EQ(r.non_manifold_edges, 1);
  const std::vector<Vec3> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  EXPECT_EQ(ValidateMesh(line, {0, 1, 2}, {{0, 1, 2}}).degenerate_triangles, 1);
}

TEST(ValidateTest, DetectsFoldedTrianglesSharingAnEdge) {
  // Both triangles on the same side of edge 0-2, in one plane.
  const std::vector<Vec3> v = {{0, 0, 0}, {2, 1, 0}, {2, 0, 0}, {1, 0.2, 0}};
  EXPECT_EQ(CountIntersectingPairs(v, {{0, 1, 2}, {0, 2, 3}}), 1);
  const std::vector<Vec3> unfolded = {
      {0, 0, 0}, {2, 1, 0}, {2, 0, 0}, {1, -1, 0}};
  EXPECT_EQ(CountIntersectingPairs(unfolded, {{0, 1, 2}, {0, 2, 3}}), 0);
}

TEST(ValidateTest, DetectsPiercingTriangles) {
  // Disjoint vertex sets; the second triangle pierces the first.
  const std::vector<Vec3> v = {{0, 0, 0},  {4, 0, 0}, {0, 4, 0},
                               {1, 1, -1}, {1, 1, 1}, {2, 2, 1}};
  EXPECT_EQ(CountIntersectingPairs(v, {{0, 1, 2}, {3, 4, 5}}), 1);
  // Sharing vertex 0, the second crosses the first's interior.
  const std::vector<Vec3> w = {
      {0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {2, 1, -1}, {1, 2, 1}};
  EXPECT_EQ(CountIntersectingPairs(w, {{0, 1, 2}, {0, 3, 4}}), 1);
  // Sharing vertex 0 only there: no intersection.
  const std::vector<Vec3> x = {
      {0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {-1, -1, 1}, {-1, -2, 1}};
  EXPECT_EQ(CountIntersectingPairs(x, {{0, 1, 2}, {0, 3, 4}}), 0);
}

TEST(ValidateTest, DetectsTwoDisksJoinedAtAVertex) {
  // Two triangles sharing only vertex 0: not a disk.
  const std::vector<Vec3> v = {
      {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  const MeshReport r =
      ValidateMesh(v, {0, 1, 2, 0, 3, 4}, {{0, 1, 2}, {0, 3, 4}});
  EXPECT_FALSE(r.disk);
}

// Before: a patch of 40,000 faces took about a second to check, with no
// way to stop; now the check polls its control.
TEST(ValidateTest, IntersectionCountStopsWhenAskedAndCountsOtherwise) {
  const MeshData torus = testing::BumpyTorus(200, 100);
  int64_t pairs = -1;
  Control expired;
  expired.deadline = std::chrono::steady_clock::now();
  const Status late = CountIntersectingPairs(torus.vertices, torus.triangles,
                                             SIZE_MAX, expired, &pairs);
  EXPECT_EQ(late.code, StatusCode::kDeadlineExceeded);
  EXPECT_NE(late.message.find("intersection check"), std::string::npos);
  EXPECT_EQ(pairs, -1);
  std::atomic<bool> cancel{true};
  Control cancelled;
  cancelled.cancel = &cancel;
  EXPECT_EQ(CountIntersectingPairs(torus.vertices, torus.triangles, SIZE_MAX,
                                   cancelled, &pairs)
                .code,
            StatusCode::kCancelled);
  ASSERT_TRUE(CountIntersectingPairs(torus.vertices, torus.triangles, SIZE_MAX,
                                     Control{}, &pairs)
                  .ok());
  EXPECT_EQ(pairs, 0);
  EXPECT_EQ(pairs, CountIntersectingPairs(torus.vertices, torus.triangles));
}

}  // namespace
}  // namespace dot

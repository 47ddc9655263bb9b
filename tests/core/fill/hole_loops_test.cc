// SPDX-License-Identifier: AGPL-3.0-or-later
// FindHoleLoops: every border cycle, simple, oriented against its faces.
#include <gtest/gtest.h>

#include "dot/dot.h"
#include "fixtures/filled_mesh.h"
#include "fixtures/meshes.h"

namespace dot {
namespace {

using testing::BumpyTorus;
using testing::Star;
using testing::WithoutFaces;

// Each loop edge (a, b) is a side b -> a of the face recorded across it.
void ExpectOrientedAgainstFaces(const MeshData& m, const HoleLoop& loop) {
  const size_t n = loop.vertices.size();
  ASSERT_EQ(loop.faces.size(), n);
  for (size_t i = 0; i < n; ++i) {
    const int32_t a = loop.vertices[i], b = loop.vertices[(i + 1) % n];
    const Triangle& t = m.triangles[loop.faces[i]];
    bool found = false;
    for (int s = 0; s < 3; ++s) found |= t[s] == b && t[(s + 1) % 3] == a;
    EXPECT_TRUE(found) << "loop edge " << a << "-" << b;
  }
}

TEST(HoleLoopsTest, ClosedMeshHasNone) {
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(BumpyTorus(20, 10), &loops).ok());
  EXPECT_TRUE(loops.empty());
}

TEST(HoleLoopsTest, TheStarOfAVertexLeavesItsLink) {
  const MeshData torus = BumpyTorus(20, 10);
  const MeshData m = WithoutFaces(torus, Star(torus, 55));
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(m, &loops).ok());
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].vertices.size(), 6u);
  EXPECT_FALSE(loops[0].pinched);
  ExpectOrientedAgainstFaces(m, loops[0]);
}

TEST(HoleLoopsTest, ABorderThroughAVertexTwiceIsSplitThere) {
  // The stars of (5, 5) and (7, 7) share only the vertex (6, 6).
  const MeshData torus = BumpyTorus(20, 10);
  auto id = [](int i, int j) { return i * 10 + j; };
  const MeshData m = WithoutFaces(torus, [&](int32_t f) {
    return Star(torus, id(5, 5))(f) || Star(torus, id(7, 7))(f);
  });
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(m, &loops).ok());
  ASSERT_EQ(loops.size(), 2u);
  for (const HoleLoop& l : loops) {
    EXPECT_TRUE(l.pinched);
    EXPECT_EQ(l.vertices.size(), 6u);
    ExpectOrientedAgainstFaces(m, l);
    std::vector<int32_t> sorted = l.vertices;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
  }
  // Both pieces filled: closed, edge-manifold.
  const FillResult r = FillHoles(m);
  testing::ExpectFilledMesh(m, r, /*closed=*/true, "pinched");
  EXPECT_EQ(r.report.filled, 2);
}

// Two gaps that share two vertices: a 2x2 island held by two corner cells
// that touch it at one vertex each. Each loop must follow its own gap (turn
// around the shared vertex through its own fan), never cross to the other.
TEST(HoleLoopsTest, TwoGapsThroughTheSameTwoVerticesStayApart) {
  const int n = 10;
  const MeshData grid = testing::FlatGrid(n);
  const MeshData m = WithoutFaces(grid, [&](int32_t f) {
    const int quad = f / 2, i = quad / n, j = quad % n;
    const bool ring = i >= 3 && i < 7 && j >= 3 && j < 7;
    const bool island = i >= 4 && i < 6 && j >= 4 && j < 6;
    const bool holder = (i == 3 && j == 3) || (i == 6 && j == 6);
    return ring && !island && !holder;
  });
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(m, &loops).ok());
  ASSERT_EQ(loops.size(), 3u);  // the rim and the two gaps
  FillOptions o;
  o.selection.skip_longest = true;
  const FillResult r = FillHoles(m, o);
  testing::ExpectFilledMesh(m, r, /*closed=*/false, "island");
  EXPECT_EQ(r.report.filled, 2);
  for (const HoleReport& h : r.report.holes) {
    if (h.status != HoleStatus::kSkipped) {
      EXPECT_TRUE(h.pinched);
      EXPECT_EQ(h.boundary_vertices, 12);
    }
  }
}

TEST(HoleLoopsTest, OpenTerrainHasItsRimAndItsHoles) {
  const MeshData grid = testing::FlatGrid(10);
  const MeshData m = WithoutFaces(grid, Star(grid, 5 * 11 + 5));
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(m, &loops).ok());
  ASSERT_EQ(loops.size(), 2u);
  std::vector<size_t> sizes{loops[0].vertices.size(), loops[1].vertices.size()};
  std::sort(sizes.begin(), sizes.end());
  EXPECT_EQ(sizes, (std::vector<size_t>{6, 40}));
  for (const HoleLoop& l : loops) ExpectOrientedAgainstFaces(m, l);

  FillOptions o;
  o.selection.skip_longest = true;
  const FillResult r = FillHoles(m, o);
  testing::ExpectFilledMesh(m, r, /*closed=*/false, "terrain");
  EXPECT_EQ(r.report.filled, 1);
  EXPECT_EQ(r.report.skipped, 1);
  for (const HoleReport& h : r.report.holes) {
    EXPECT_EQ(h.status == HoleStatus::kSkipped, h.boundary_vertices == 40);
    if (h.status == HoleStatus::kSkipped) {
      EXPECT_NE(h.reason.find("longest border"), std::string::npos);
    }
  }
  o.selection = {};
  o.selection.max_edges = 10;
  EXPECT_EQ(FillHoles(m, o).report.filled, 1);
  o.selection = {};
  o.selection.ids = {loops[0].vertices.size() == 6 ? 0 : 1};
  EXPECT_EQ(FillHoles(m, o).report.filled, 1);
}

TEST(HoleLoopsTest, NonManifoldEdgeIsNamed) {
  MeshData m{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}},
             {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}};
  std::vector<HoleLoop> loops;
  const Status s = FindHoleLoops(m, &loops);
  EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
  EXPECT_NE(s.message.find("edge 0-1 is shared by 3 faces"), std::string::npos)
      << s.message;
}

}  // namespace
}  // namespace dot

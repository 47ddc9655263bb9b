// SPDX-License-Identifier: AGPL-3.0-or-later
// Holes with islands: the grouping rule on flat grids whose answers are
// known, explicit groups and their refusals, and real meshes with ring
// holes cut around islands (CutIslandHoles) filled by one patch per hole,
// checked against the closed mesh they were cut from.
#include <gtest/gtest.h>

#include <map>
#include <numeric>

#include "dot/dot.h"
#include "fixtures/filled_mesh.h"
#include "fixtures/meshes.h"

namespace dot {
namespace {

bool In(int i, int j, int lo, int hi) {
  return i >= lo && i < hi && j >= lo && j < hi;
}

// FlatGrid(n) without the quads `drop` marks.
template <typename Drop>
MeshData GridWithout(int n, Drop drop) {
  return testing::WithoutFaces(testing::FlatGrid(n), [&](int32_t f) {
    const int quad = f / 2;
    return drop(quad / n, quad % n);
  });
}

// Loop ids by edge count (every loop of these grids has its own size).
std::map<size_t, int32_t> IdsBySize(const std::vector<HoleLoop>& loops) {
  std::map<size_t, int32_t> ids;
  for (const HoleLoop& l : loops) ids[l.vertices.size()] = l.id;
  EXPECT_EQ(ids.size(), loops.size());
  return ids;
}

TEST(GroupHoleLoopsTest, AnIslandJoinsTheNearestRimOfALargerPiece) {
  // A 20 x 20 grid; a square hole [3, 17) holding a ring-shaped island
  // [5, 15) minus [7, 13), which holds a small island [9, 11).
  const MeshData m = GridWithout(20, [](int i, int j) {
    const bool ring = In(i, j, 5, 15) && !In(i, j, 7, 13);
    return In(i, j, 3, 17) && !ring && !In(i, j, 9, 11);
  });
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(m, &loops).ok());
  ASSERT_EQ(loops.size(), 5u);
  auto id = IdsBySize(loops);
  const int32_t outer = id[80], rim = id[56], ring_out = id[40],
                ring_in = id[24], small = id[8];
  std::vector<int32_t> group;
  ASSERT_TRUE(GroupHoleLoops(m, loops, IslandMode::kAuto, {}, &group).ok());
  EXPECT_EQ(group[outer], outer);
  EXPECT_EQ(group[rim], rim);
  EXPECT_EQ(group[ring_out], rim);     // the ring floats in the hole
  EXPECT_EQ(group[ring_in], ring_in);  // a hole of the ring, not an island
  EXPECT_EQ(group[small], ring_in);    // floats in the ring's hole
  ASSERT_TRUE(GroupHoleLoops(m, loops, IslandMode::kOff, {}, &group).ok());
  for (size_t i = 0; i < loops.size(); ++i) EXPECT_EQ(group[i], int32_t(i));
  // An explicit group is kept as given and not regrouped.
  ASSERT_TRUE(
      GroupHoleLoops(m, loops, IslandMode::kAuto, {{small, rim}}, &group).ok());
  EXPECT_EQ(group[small], rim);
  // Its rim is taken: the nearest rim left around it is the grid's border.
  EXPECT_EQ(group[ring_out], outer);
  EXPECT_EQ(group[ring_in], ring_in);
}

TEST(GroupHoleLoopsTest, BadGroupsAreRefusedByName) {
  const MeshData m = GridWithout(
      12, [](int i, int j) { return In(i, j, 2, 10) && !In(i, j, 4, 8); });
  std::vector<HoleLoop> loops;
  ASSERT_TRUE(FindHoleLoops(m, &loops).ok());
  ASSERT_EQ(loops.size(), 3u);
  std::vector<int32_t> group;
  auto refusal = [&](std::vector<std::vector<int32_t>> join) {
    const Status s = GroupHoleLoops(m, loops, IslandMode::kAuto, join, &group);
    EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
    return s.message;
  };
  EXPECT_NE(refusal({{0, 7}}).find("there is no hole 7"), std::string::npos);
  EXPECT_NE(refusal({{0, 1}, {1, 2}}).find("hole 1 is named twice"),
            std::string::npos);
  EXPECT_NE(refusal({{2}}).find("fewer than 2 loops"), std::string::npos);
}

TEST(FillHolesIslandsTest, AFlatRingIsFilledByOnePatchJoiningBothLoops) {
  const MeshData m = GridWithout(
      16, [](int i, int j) { return In(i, j, 4, 12) && !In(i, j, 6, 10); });
  FillOptions o;
  o.selection.skip_longest = true;  // the grid's own border
  o.stage = FillStage::kTriangulate;
  const FillResult r = FillHoles(m, o);
  testing::ExpectFilledMesh(m, r, /*closed=*/false, "ring");
  ASSERT_EQ(r.report.loops, 3);
  EXPECT_EQ(r.report.filled, 2);
  int32_t rim = -1, island = -1;
  for (const HoleReport& h : r.report.holes) {
    if (h.boundary_vertices == 32) rim = h.id;
    if (h.boundary_vertices == 16) island = h.id;
  }
  ASSERT_GE(rim, 0);
  ASSERT_GE(island, 0);
  const HoleReport& hr = r.report.holes[rim];
  EXPECT_EQ(hr.joined, std::vector<int32_t>{island});
  EXPECT_EQ(hr.joined_to, -1);
  EXPECT_EQ(r.report.holes[island].joined_to, rim);
  EXPECT_EQ(r.report.holes[island].status, HoleStatus::kFilled);
  EXPECT_NE(r.report.holes[island].reason.find("island of hole"),
            std::string::npos);
  // One piece; a planar ring of 48 boundary vertices and no interior
  // vertex has exactly 48 triangles.
  EXPECT_EQ(ShapeOf(r.mesh).pieces, 1);
  EXPECT_EQ(hr.patch_triangles, 48);
  EXPECT_EQ(r.patches.size(), 1u);

  // Off: the island is capped alone; the rim's cap would cover it.
  o.islands = IslandMode::kOff;
  const FillResult alone = FillHoles(m, o);
  testing::ExpectFilledMesh(m, alone, /*closed=*/false, "ring, islands off");
  for (const HoleReport& h : alone.report.holes) {
    EXPECT_TRUE(h.joined.empty());
    EXPECT_EQ(h.joined_to, -1);
  }
  // Each cap lies on the grid's plane over faces of the mesh: none is kept.
  EXPECT_NE(alone.report.holes[rim].status, HoleStatus::kFilled);
  EXPECT_TRUE(alone.patches.empty());

  // The same ring joined explicitly with islands off.
  o.join = {{island, rim}};
  const FillResult joined = FillHoles(m, o);
  testing::ExpectFilledMesh(m, joined, /*closed=*/false, "ring, joined");
  EXPECT_EQ(joined.report.holes[rim].joined, std::vector<int32_t>{island});
  EXPECT_EQ(joined.mesh.triangles, r.mesh.triangles);
}

TEST(FillHolesIslandsTest, TwoIslandsInOneFlatHoleAreJoinedByOnePatch) {
  const MeshData m = GridWithout(16, [](int i, int j) {
    return In(i, j, 3, 13) && !In(i, j, 5, 7) && !In(i, j, 9, 11);
  });
  FillOptions o;
  o.selection.skip_longest = true;
  o.stage = FillStage::kTriangulate;
  const FillResult r = FillHoles(m, o);
  testing::ExpectFilledMesh(m, r, /*closed=*/false, "two islands");
  ASSERT_EQ(r.report.loops, 4);
  EXPECT_EQ(r.report.filled, 3);
  int32_t rim = -1;
  for (const HoleReport& h : r.report.holes) {
    if (h.boundary_vertices == 40) rim = h.id;
  }
  ASSERT_GE(rim, 0);
  EXPECT_EQ(r.report.holes[rim].joined.size(), 2u);
  // Three loops of 40 + 8 + 8 vertices, no inner vertex: n + 2 (k - 2)
  // triangles, joined into the grid as one piece.
  EXPECT_EQ(r.report.holes[rim].patch_triangles, 58);
  EXPECT_EQ(ShapeOf(r.mesh).pieces, 1);
}

TEST(FillHolesIslandsTest, RingHolesInClosedMeshesComeOutClosedInOnePiece) {
  for (const char* name : {"elephant.off", "armadillo.off"}) {
    PolygonSoup soup;
    MeshData closed;
    RepairReport repair;
    if (!ReadPolygonSoupFile(testing::MeshPath(name), &soup).ok() ||
        !RepairMesh(soup, &closed, &repair).ok()) {
      GTEST_SKIP() << name << " missing";
    }
    MeshData holey, removed;
    ASSERT_TRUE(CutIslandHoles(closed, 3, 150, 30, 11, &holey, &removed).ok());
    ASSERT_EQ(ShapeOf(holey).pieces, 4) << name;  // the body and 3 islands
    const FillResult r = FillHoles(holey);
    testing::ExpectFilledMesh(holey, r, /*closed=*/true, name);
    EXPECT_EQ(r.report.loops, 6) << name;
    EXPECT_EQ(r.report.filled, 6) << name;
    int rims = 0;
    for (const HoleReport& h : r.report.holes) {
      rims += h.joined.size() == 1;
      EXPECT_EQ(h.joined.size() == 1, h.joined_to < 0) << name << " " << h.id;
    }
    EXPECT_EQ(rims, 3) << name;
    EXPECT_EQ(r.patches.size(), 3u) << name;
    // The ground truth's topology: one piece, the closed mesh's genus.
    EXPECT_EQ(ShapeOf(r.mesh).pieces, 1) << name;
    EXPECT_EQ(ShapeOf(r.mesh).euler, ShapeOf(closed).euler) << name;
    std::printf(
        "%s: 3 ring holes of 120 triangles around islands of 30, "
        "each filled by one patch in %.1f ms\n",
        name, r.report.total_ms);
  }
}

}  // namespace
}  // namespace dot

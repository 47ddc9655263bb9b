// SPDX-License-Identifier: AGPL-3.0-or-later
// FillSoup, the use case behind the FillHoles RPC and dotctl: the repair
// and the fill it runs are exactly RepairMesh then FillHoles; options out
// of range are refused by the core, before any work, naming the field.
#include <gtest/gtest.h>

#include <cmath>

#include "dot/dot.h"
#include "fixtures/meshes.h"

namespace dot {
namespace {

// A grid with a square hole, every vertex sent twice (the second copy
// used by the odd faces): a soup that needs its repair.
PolygonSoup DuplicatedSoup() {
  const MeshData m = testing::GridWithSquareHole(8, 3, 5);
  PolygonSoup soup{m.vertices, {}};
  soup.vertices.insert(soup.vertices.end(), m.vertices.begin(),
                       m.vertices.end());
  const auto n = static_cast<int32_t>(m.vertices.size());
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    const int32_t shift = f % 2 ? n : 0;
    const Triangle& t = m.triangles[f];
    soup.faces.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
  }
  return soup;
}

TEST(FillSoupTest, RunsTheRepairThenFillHoles) {
  const PolygonSoup soup = DuplicatedSoup();
  MeshData repaired;
  RepairReport repair;
  ASSERT_TRUE(RepairMesh(soup, &repaired, &repair).ok());
  ASSERT_GT(repair.merged_vertices, 0);
  const FillResult direct = FillHoles(repaired);
  ASSERT_TRUE(direct.status.ok()) << direct.status.message;

  const SoupFillResult r = FillSoup(soup);
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  EXPECT_EQ(r.repair.merged_vertices, repair.merged_vertices);
  EXPECT_EQ(r.input_vertices, static_cast<int64_t>(repaired.vertices.size()));
  EXPECT_EQ(r.input_faces, static_cast<int64_t>(repaired.triangles.size()));
  EXPECT_EQ(r.fill.report.filled, 1);
  EXPECT_EQ(r.fill.mesh.triangles, direct.mesh.triangles);
  EXPECT_EQ(r.fill.mesh.vertices.size(), direct.mesh.vertices.size());
  EXPECT_TRUE(r.fill.report.closed == direct.report.closed);
}

TEST(FillSoupTest, WithoutRepairTheSoupIsFilledAsSent) {
  FillOptions options;
  options.repair = false;
  const SoupFillResult r = FillSoup(DuplicatedSoup(), options);
  ASSERT_TRUE(r.fill.status.ok()) << r.fill.status.message;
  EXPECT_EQ(r.repair.merged_vertices, 0);
  // Unmerged, the grid falls apart along every edge between an odd and an
  // even face: many more loops than the one hole.
  EXPECT_GT(r.fill.report.loops, 1);
  EXPECT_EQ(r.input_vertices,
            static_cast<int64_t>(DuplicatedSoup().vertices.size()));
}

TEST(FillSoupTest, OptionsOutOfRangeAreRefusedBeforeAnyWork) {
  struct Case {
    const char* words;
    void (*set)(FillOptions*);
  };
  const Case cases[] = {
      {"density must be between 0.1 and 100",
       [](FillOptions* o) { o->density = 0.01; }},
      {"density must be between 0.1 and 100",
       [](FillOptions* o) { o->density = std::nan(""); }},
      {"fairing_continuity must be 0, 1 or 2",
       [](FillOptions* o) { o->fairing_continuity = 3; }},
      {"max_hole_diameter must be a finite number >= 0",
       [](FillOptions* o) { o->selection.max_diameter = -1; }},
      {"max_hole_edges must be >= 0",
       [](FillOptions* o) { o->selection.max_edges = -1; }},
      {"threads must be >= 0", [](FillOptions* o) { o->threads = -2; }},
      {"every metric weight is zero",
       [](FillOptions* o) { o->weights = MetricWeights{}; }},
      {"is not finite",
       [](FillOptions* o) { o->weights[Metric::kArea] = HUGE_VAL; }},
  };
  // An empty soup: had the options passed, the repair would refuse it.
  const PolygonSoup empty;
  for (const Case& c : cases) {
    FillOptions o;
    c.set(&o);
    const Status check = CheckFillOptions(o);
    EXPECT_EQ(check.code, StatusCode::kInvalidArgument) << c.words;
    EXPECT_NE(check.message.find(c.words), std::string::npos) << check.message;
    const SoupFillResult r = FillSoup(empty, o);
    EXPECT_EQ(r.fill.status.message, check.message);
    const FillResult direct =
        FillHoles(testing::GridWithSquareHole(8, 3, 5), o);
    EXPECT_EQ(direct.status.message, check.message);
  }
  EXPECT_TRUE(CheckFillOptions(FillOptions{}).ok());
}

}  // namespace
}  // namespace dot

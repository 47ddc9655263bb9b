// SPDX-License-Identifier: AGPL-3.0-or-later
// What FillHoles promises whatever it is sent: it stops when asked in every
// stage, bounds its output, refuses what it cannot honour by name, and never
// answers OK with a non-finite vertex or an empty mesh.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>

#include "dot/dot.h"
#include "fixtures/filled_mesh.h"
#include "fixtures/meshes.h"

namespace dot {
namespace {

using testing::GridWithSquareHole;

MeshData HoleyTorus(int nu, int nv, int holes) {
  return testing::HoleyTorus(nu, nv, holes, 60);
}

TEST(FillLimitsTest, HighDensityStopsAtTheCapAndKeepsTheDotPatch) {
  // Before: density 100 turned a 16-edge hole into 96,516 faces.
  const MeshData m = GridWithSquareHole(12, 4, 8);
  FillOptions o;
  o.density = 100;
  o.selection.skip_longest = true;  // the grid's rim
  const FillResult r = FillHoles(m, o);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  testing::ExpectFilledMesh(m, r, /*closed=*/false, "density 100");
  ASSERT_EQ(r.report.filled, 1);
  const HoleReport* hole = nullptr;
  for (const HoleReport& h : r.report.holes) {
    if (h.status == HoleStatus::kFilled) hole = &h;
  }
  ASSERT_NE(hole, nullptr);
  EXPECT_EQ(hole->boundary_vertices, 16);
  EXPECT_NE(hole->reason.find("refinement stopped past"), std::string::npos)
      << hole->reason;
  EXPECT_LE(r.report.added_faces, 2 * (2 * 16 * 16 + 1000));
}

TEST(FillLimitsTest, AnyFiniteScaleIsFilledAndFairedWithoutNaN) {
  // Before: fairing at coordinates around 1e-150 made NaN vertices, and the
  // hole was reported filled; at 1e160 and beyond every hole failed on a
  // zero boundary normal, at 1e-160 on an infinite area weight.
  for (double scale :
       {1e-300, 1e-160, 1e-150, 1e-100, 1.0, 1e100, 1e150, 1e160, 1e300}) {
    MeshData m = HoleyTorus(40, 20, 2);
    for (Vec3& p : m.vertices) p = scale * p;
    const FillResult r = FillHoles(m);
    ASSERT_TRUE(r.status.ok()) << scale << ": " << r.status.message;
    for (const Vec3& p : r.mesh.vertices) {
      ASSERT_TRUE(IsFinite(p)) << "scale " << scale;
    }
    EXPECT_EQ(r.report.filled, 2) << scale << ": " << r.report.holes[0].reason;
    int faired = 0;
    for (const HoleReport& h : r.report.holes) faired += h.faired;
    EXPECT_GT(faired, 0) << "scale " << scale;
  }
}

TEST(FillLimitsTest, UnknownHoleIdsAreRefusedAndRepeatsAreCheap) {
  const MeshData m = HoleyTorus(40, 20, 3);
  FillOptions o;
  o.stage = FillStage::kTriangulate;
  for (int32_t bad : {3, 99, -1}) {
    o.selection.ids = {0, bad};
    const FillResult r = FillHoles(m, o);
    EXPECT_EQ(r.status.code, StatusCode::kInvalidArgument) << bad;
    EXPECT_NE(r.status.message.find("there is no hole " + std::to_string(bad)),
              std::string::npos)
        << r.status.message;
  }
  // Before: every loop searched the whole id list (15 M ids x 20 k loops).
  o.selection.ids.assign(2000000, 1);
  const FillResult r = FillHoles(m, o);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_EQ(r.report.filled, 1);
  EXPECT_EQ(r.report.skipped, 2);
}

TEST(FillLimitsTest, EmptyOrAllDegenerateMeshesAreRefused) {
  // Before: answered OK, loops=0, closed=true, with an empty mesh.
  const FillResult empty = FillHoles(MeshData{{{0, 0, 0}}, {}});
  EXPECT_EQ(empty.status.code, StatusCode::kInvalidArgument);
  EXPECT_NE(empty.status.message.find("no faces"), std::string::npos);
  PolygonSoup soup{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 0}},
                   {{0, 1, 2}, {0, 3, 1}, {1, 1, 2}},
                   {}};
  MeshData repaired;
  RepairReport report;
  const Status s = RepairMesh(soup, &repaired, &report);
  EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
  EXPECT_NE(s.message.find("nothing is left of the mesh after repair"),
            std::string::npos)
      << s.message;
}

TEST(FillLimitsTest, AVertexOnThousandsOfBorderEdgesIsRefusedByName) {
  // Before: 60,000 triangles sharing one corner kept the border walk busy
  // for minutes (every arrival weighed every border edge of the hub).
  MeshData m;
  m.vertices.push_back({0, 0, 0});
  for (int i = 0; i < 1000; ++i) {
    const double a = 2 * M_PI * i / 1000;
    m.vertices.push_back({std::cos(a), std::sin(a), 0});
    m.vertices.push_back({std::cos(a), std::sin(a), 1});
    m.triangles.push_back({0, 2 * i + 1, 2 * i + 2});
  }
  std::vector<HoleLoop> loops;
  const Status s = FindHoleLoops(m, &loops);
  EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
  EXPECT_NE(s.message.find("vertex 0 starts 1000 border edges"),
            std::string::npos)
      << s.message;
}

TEST(FillLimitsTest, CancelAndDeadlineStopEveryStage) {
  const MeshData m = HoleyTorus(60, 30, 4);
  const PolygonSoup soup = ToSoup(m);
  for (FillStage stage :
       {FillStage::kTriangulate, FillStage::kRefine, FillStage::kFair}) {
    FillOptions o;
    o.stage = stage;
    std::atomic<bool> cancel{true};
    Control c;
    c.cancel = &cancel;
    FillResult r = FillHoles(m, o, c);
    EXPECT_EQ(r.status.code, StatusCode::kCancelled);
    EXPECT_FALSE(r.partial);  // stopped before the loops were found
    EXPECT_TRUE(r.mesh.vertices.empty());
    Control late;
    late.deadline = std::chrono::steady_clock::now();
    r = FillHoles(m, o, late);
    EXPECT_EQ(r.status.code, StatusCode::kDeadlineExceeded);
    EXPECT_NE(r.status.message.find("deadline exceeded during"),
              std::string::npos)
        << r.status.message;
  }
  std::atomic<bool> cancel{true};
  Control c;
  c.cancel = &cancel;
  MeshData repaired;
  RepairReport report;
  EXPECT_EQ(RepairMesh(soup, c, &repaired, &report).code,
            StatusCode::kCancelled);
  std::vector<HoleLoop> loops;
  EXPECT_EQ(FindHoleLoops(m, &loops, c).code, StatusCode::kCancelled);
  // A polygon face is triangulated by DOT, which stops too.
  PolygonSoup polygon;
  for (int i = 0; i < 400; ++i) {
    const double a = 2 * M_PI * i / 400;
    polygon.vertices.push_back(
        {std::cos(a), std::sin(a), 0.2 * std::sin(5 * a)});
  }
  std::vector<int32_t> all(400);
  for (int i = 0; i < 400; ++i) all[i] = i;
  polygon.faces.push_back(all);
  MeshData triangulated;
  EXPECT_EQ(TriangulateSoup(polygon, c, &triangulated).code,
            StatusCode::kCancelled);
}

TEST(FillLimitsTest, AStopKeepsEveryHoleFinishedBeforeIt) {
  const MeshData m = HoleyTorus(60, 30, 5);
  FillOptions o;
  o.threads = 1;  // holes one at a time: the stop falls between two
  const FillResult full = FillHoles(m, o);
  ASSERT_TRUE(full.status.ok()) << full.status.message;
  ASSERT_EQ(full.report.filled, 5);
  std::atomic<bool> cancel{false};
  Control c;
  c.cancel = &cancel;
  std::vector<FillPhase> phases;
  const FillResult r =
      FillHoles(m, o, c, [&](FillPhase phase, int done, int total) {
        if (phases.empty() || phases.back() != phase) phases.push_back(phase);
        EXPECT_EQ(total, phase == FillPhase::kLoops ? 0 : 5);
        if (phase == FillPhase::kHoles && done == 2) cancel = true;
      });
  EXPECT_EQ(phases,
            (std::vector<FillPhase>{FillPhase::kLoops, FillPhase::kHoles,
                                    FillPhase::kMerge}));
  EXPECT_EQ(r.status.code, StatusCode::kCancelled) << r.status.message;
  ASSERT_TRUE(r.partial);
  EXPECT_EQ(r.report.filled, 2);
  EXPECT_EQ(r.report.stopped, 3);
  EXPECT_FALSE(r.report.closed);
  testing::ExpectFilledMesh(m, r, /*closed=*/false, "stopped after 2 holes");
  // The two kept are the patches a full fill makes for those holes.
  ASSERT_EQ(r.patches.size(), 2u);
  for (const FilledHole& kept : r.patches) {
    const HoleReport& h = r.report.holes[kept.hole];
    EXPECT_EQ(h.status, HoleStatus::kFilled);
    for (const FilledHole& f : full.patches) {
      if (f.hole != kept.hole) continue;
      EXPECT_EQ(kept.patch.new_vertices, f.patch.new_vertices);
    }
  }
  for (const HoleReport& h : r.report.holes) {
    if (h.status == HoleStatus::kStopped) {
      EXPECT_EQ(h.reason, "not started: the fill was cancelled");
    }
  }
  // Nobody to keep them for (a server whose client left): status only.
  c.keep_partial = [] { return false; };
  cancel = false;
  const FillResult unwanted =
      FillHoles(m, o, c, [&](FillPhase phase, int done, int) {
        if (phase == FillPhase::kHoles && done == 2) cancel = true;
      });
  EXPECT_EQ(unwanted.status.code, StatusCode::kCancelled);
  EXPECT_FALSE(unwanted.partial);
  EXPECT_TRUE(unwanted.mesh.triangles.empty());
}

TEST(FillLimitsTest, ADeadlineAtAnyPointLeavesAValidMeshOrNone) {
  const MeshData m = testing::HoleyTorus(80, 40, 5, 300);
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(FillHoles(m).status.ok());
  const auto full = std::chrono::steady_clock::now() - t0;
  // Deadlines through the whole fill: in the loops, the holes, the merge.
  for (int percent : {2, 20, 40, 60, 80, 95}) {
    Control c;
    c.deadline = std::chrono::steady_clock::now() + full * percent / 100;
    const std::string what = std::to_string(percent) + "% of the time";
    const FillResult r = FillHoles(m, FillOptions{}, c);
    if (r.status.ok() || r.partial) {
      testing::ExpectFilledMesh(m, r, /*closed=*/r.status.ok(), what);
      EXPECT_EQ(r.report.filled + r.report.stopped, 5) << what;
      EXPECT_GT(r.report.filled, 0) << what;
    } else {
      EXPECT_EQ(r.status.code, StatusCode::kDeadlineExceeded) << what;
      EXPECT_TRUE(r.mesh.triangles.empty()) << what;
    }
  }
}

}  // namespace
}  // namespace dot

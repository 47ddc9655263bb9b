// SPDX-License-Identifier: AGPL-3.0-or-later
// The CGAL backend's parallel insertion gives exactly what sequential
// insertion gives (CGAL's Delaunay is unique under symbolic perturbation,
// whatever the insertion order), and still honours cancel and deadline.
// Sizes stay small by lowering the threshold.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <random>

#include "dot/dot.h"
#include "search_space/delaunay_cgal.h"

namespace dot {
namespace {

Options WithThreads(int threads) {
  Options o;
  o.parallel_delaunay_min_points = 1000;
  o.delaunay_threads = threads;
  return o;
}

std::vector<Triangle> SortedFaces(const std::vector<Vec3>& points,
                                  const Options& options, int64_t* tetrahedra) {
  std::vector<Triangle> faces;
  const Status s = CgalDelaunayFaces(points, options, {}, &faces, tetrahedra);
  EXPECT_TRUE(s.ok()) << s.message;
  std::sort(faces.begin(), faces.end());
  return faces;
}

void ExpectSameFaces(const std::vector<Vec3>& points) {
  int64_t tets1 = 0, tets2 = 0;
  const std::vector<Triangle> one = SortedFaces(points, WithThreads(1), &tets1);
  const std::vector<Triangle> two = SortedFaces(points, WithThreads(2), &tets2);
  EXPECT_GT(one.size(), points.size());
  EXPECT_EQ(tets1, tets2);
  EXPECT_TRUE(one == two) << one.size() << " against " << two.size()
                          << " faces";
}

TEST(ParallelDelaunayTest, SameFacesAndTrianglesWithOneAndTwoThreads) {
  for (Curve curve : {Curve::kMonkey, Curve::kSpiral}) {
    SCOPED_TRACE(CurveName(curve));
    const std::vector<Vec3> points = MakeCurve(curve, 3000);
    ExpectSameFaces(points);
    for (bool bi : {false, true}) {
      Problem p{points, {}, {}, {}, {}};
      p.weights[bi ? Metric::kSquaredDihedral : Metric::kArea] = 1;
      const Result one = Triangulate(p, WithThreads(1));
      const Result two = Triangulate(p, WithThreads(2));
      ASSERT_TRUE(one.status.ok()) << one.status.message;
      ASSERT_TRUE(two.status.ok()) << two.status.message;
      EXPECT_EQ(one.triangles, two.triangles) << (bi ? "DOT2" : "DOT1");
      EXPECT_EQ(one.total_cost, two.total_cost);
      EXPECT_EQ(one.stats.delaunay_triangles, two.stats.delaunay_triangles);
      EXPECT_EQ(one.stats.tetrahedra, two.stats.tetrahedra);
    }
  }
}

// A grid is as cospherical as input gets: every unit cube's eight corners
// lie on one sphere, so only the symbolic perturbation decides the faces.
TEST(ParallelDelaunayTest, SameFacesOnCosphericalGridAndRandomPoints) {
  std::vector<Vec3> grid;
  for (int i = 0; i < 14; ++i) {
    for (int j = 0; j < 14; ++j) {
      for (int k = 0; k < 14; ++k) grid.push_back({1.0 * i, 1.0 * j, 1.0 * k});
    }
  }
  std::shuffle(grid.begin(), grid.end(), std::mt19937(3));
  ExpectSameFaces(grid);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> random(5000);
  for (Vec3& v : random) v = {u(rng), u(rng), u(rng)};
  ExpectSameFaces(random);
}

TEST(ParallelDelaunayTest, ReportsCoincidentPoints) {
  std::vector<Vec3> points = MakeCurve(Curve::kMonkey, 3000);
  points.push_back(points[2500]);
  std::vector<Triangle> faces;
  int64_t tets = 0;
  const Status s = CgalDelaunayFaces(points, WithThreads(2), {}, &faces, &tets);
  EXPECT_EQ(s.code, StatusCode::kInvalidArgument);
  EXPECT_NE(s.message.find("1 vertices coincide"), std::string::npos)
      << s.message;
}

TEST(ParallelDelaunayTest, CancelAndDeadlineStopTheParallelInsertion) {
  using Clock = std::chrono::steady_clock;
  const std::vector<Vec3> points = MakeCurve(Curve::kSpiral, 60000);
  std::atomic<bool> cancel{false};
  Clock::time_point cancelled_at;
  Control control;
  control.cancel = &cancel;
  control.progress = [&](Stage stage, double fraction) {
    if (stage == Stage::kDelaunay && fraction > 0.3 && !cancel) {
      cancelled_at = Clock::now();
      cancel = true;
    }
  };
  std::vector<Triangle> faces;
  int64_t tets = 0;
  Status s = CgalDelaunayFaces(points, WithThreads(2), control, &faces, &tets);
  const double ms = MsSince(cancelled_at);
  EXPECT_EQ(s.code, StatusCode::kCancelled) << s.message;
  std::printf("parallel Delaunay step stopped %.1f ms after the cancel\n",
              ms);  // a figure, not a bound: see scripts/stop_latency.sh

  Control deadline;
  deadline.deadline = Clock::now() + std::chrono::milliseconds(20);
  s = CgalDelaunayFaces(points, WithThreads(2), deadline, &faces, &tets);
  EXPECT_EQ(s.code, StatusCode::kDeadlineExceeded) << s.message;
}

}  // namespace
}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
#include "network/face_cost.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace dot {
namespace {

// A square of four curves, each a side with its midpoint; corners 1 and 3
// lifted by `lift` (a saddle unless 0).
NetworkGraph Square(double lift) {
  NetworkGraph g;
  const Vec3 corners[4] = {{0, 0, 0}, {1, 0, lift}, {1, 1, 0}, {0, 1, lift}};
  for (const Vec3& c : corners) g.vertices.push_back(c);
  for (int32_t k = 0; k < 4; ++k) {
    const Vec3 mid = 0.5 * (corners[k] + corners[(k + 1) % 4]);
    g.vertices.push_back(mid);
    g.curves.push_back({{k, 4 + k, (k + 1) % 4}});
  }
  return g;
}

std::vector<CurveUse> Forward() {
  return {{0, false}, {1, false}, {2, false}, {3, false}};
}

TEST(FaceCostsTest, FlatFaceCostsNothingAndASaddleCostsItsBending) {
  const NetworkGraph flat = Square(0), saddle = Square(0.5);
  FaceCosts flat_costs(flat, {}), saddle_costs(saddle, {});
  EXPECT_NEAR(flat_costs.Cost(Forward()), 0, 1e-12);
  EXPECT_GT(saddle_costs.Cost(Forward()), 0.1);
}

TEST(FaceCostsTest, AFaceIsPricedOnceFromAnyStartEitherWay) {
  const NetworkGraph g = Square(0.5);
  FaceCosts costs(g, {});
  const double first = costs.Cost(Forward());
  EXPECT_EQ(costs.Cost({{2, false}, {3, false}, {0, false}, {1, false}}),
            first);
  EXPECT_EQ(costs.Cost({{3, true}, {2, true}, {1, true}, {0, true}}), first);
  EXPECT_EQ(costs.priced(), 1u);
}

// A face that runs a curve there and back is no patch: it costs the most a
// point can.
TEST(FaceCostsTest, AFaceRunningACurveTwiceIsUnsurfaceable) {
  const NetworkGraph g = Square(0);
  FaceCosts costs(g, {});
  EXPECT_EQ(costs.Cost({{0, false}, {0, true}}), 4 * FaceCosts::kUnsurfaceable);
}

// A long loop is priced by at most kMaxPoints of its points, every
// junction among them.
TEST(FaceCostsTest, LongLoopsArePricedBySomeOfTheirPoints) {
  NetworkGraph g;
  const int n = 5000;
  for (int32_t k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    g.vertices.push_back({std::cos(a), std::sin(a), 0.1 * std::sin(3 * a)});
  }
  // Two curves: 0 -> 1000 and 1000 -> 0 round the rest.
  NetworkCurve a, b;
  for (int32_t k = 0; k <= 1000; ++k) a.vertices.push_back(k);
  for (int32_t k = 1000; k <= n; ++k) b.vertices.push_back(k % n);
  g.curves = {a, b};
  const std::vector<CurveUse> face = {{0, false}, {1, false}};
  const std::vector<Vec3> points = PricedPoints(g, face);
  EXPECT_LE(points.size(), static_cast<size_t>(FaceCosts::kMaxPoints));
  EXPECT_GE(points.size(), static_cast<size_t>(FaceCosts::kMaxPoints) - 2);
  EXPECT_EQ(points[0], g.vertices[0]);
  EXPECT_EQ(std::count(points.begin(), points.end(), g.vertices[1000]), 1);
  FaceCosts costs(g, {});
  const double cost = costs.Cost(face);
  EXPECT_GT(cost, 0);
  EXPECT_LT(cost, FaceCosts::kUnsurfaceable);  // DOT triangulated it
}

}  // namespace
}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
#include "network/face_cost.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace dot {
namespace {

constexpr int64_t kPlenty = 1 << 20;  // points to price

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
std::vector<CurveUse> Backward() {
  return {{3, true}, {2, true}, {1, true}, {0, true}};
}

// A wavy ring of `n` points cut into curves at every `step`-th point.
NetworkGraph Ring(int n, int step) {
  NetworkGraph g;
  const double pi = std::acos(-1.0);
  for (int32_t k = 0; k < n; ++k) {
    const double a = 2 * pi * k / n;
    g.vertices.push_back({std::cos(a), std::sin(a), 0.1 * std::sin(3 * a)});
  }
  for (int32_t k = 0; k < n; k += step) {
    NetworkCurve c;
    for (int32_t j = k; j <= std::min(k + step, n); ++j) {
      c.vertices.push_back(j % n);
    }
    g.curves.push_back(c);
  }
  return g;
}

std::vector<CurveUse> AllForward(const NetworkGraph& g) {
  std::vector<CurveUse> face;
  for (size_t c = 0; c < g.curves.size(); ++c) {
    face.push_back({static_cast<int32_t>(c), false});
  }
  return face;
}

TEST(FaceCostsTest, FlatFaceCostsNothingAndASaddleCostsItsBending) {
  const NetworkGraph flat = Square(0), saddle = Square(0.5);
  FaceCosts flat_costs(flat, {}, kPlenty), saddle_costs(saddle, {}, kPlenty);
  EXPECT_NEAR(flat_costs.Cost(Forward()).value(), 0, 1e-12);
  EXPECT_GT(saddle_costs.Cost(Forward()).value(), 0.1);
}

TEST(FaceCostsTest, AFaceIsPricedOnceFromAnyStartEitherWay) {
  const NetworkGraph g = Square(0.5);
  FaceCosts costs(g, {}, kPlenty);
  const double first = costs.Cost(Forward()).value();
  EXPECT_EQ(costs.Cost({{2, false}, {3, false}, {0, false}, {1, false}}),
            first);
  EXPECT_EQ(costs.Cost(Backward()), first);
  EXPECT_EQ(costs.priced(), 1u);
}

// Thinned to kMaxPoints, a face keeps the same points whichever way it is
// run and whichever curve it starts from: the price does not depend on how
// a trace found it first (junctions kept: 30 curves; evenly spaced: 300).
TEST(FaceCostsTest, ALongFaceCostsTheSameFromAnyStartEitherWay) {
  for (int step : {100, 10}) {
    SCOPED_TRACE(step);
    const NetworkGraph g = Ring(3000, step);
    std::vector<CurveUse> forward = AllForward(g), backward;
    for (auto it = forward.rbegin(); it != forward.rend(); ++it) {
      backward.push_back({it->curve, !it->reversed});
    }
    std::vector<CurveUse> later = forward;
    std::rotate(later.begin(), later.begin() + 7, later.end());
    FaceCosts one(g, {}, kPlenty), other(g, {}, kPlenty), third(g, {}, kPlenty);
    const double cost = one.Cost(forward).value();
    EXPECT_EQ(other.Cost(backward), cost);
    EXPECT_EQ(third.Cost(later), cost);
  }
}

// A face that runs a curve there and back is no patch: it costs the most a
// point can.
TEST(FaceCostsTest, AFaceRunningACurveTwiceIsUnsurfaceable) {
  const NetworkGraph g = Square(0);
  FaceCosts costs(g, {}, kPlenty);
  EXPECT_EQ(costs.Cost({{0, false}, {0, true}}), 4 * FaceCosts::kUnsurfaceable);
}

// A figure eight through one junction twice is pinched: no rim.
TEST(FaceCostsTest, AFacePassingAJunctionTwiceIsUnsurfaceable) {
  NetworkGraph g;
  g.vertices = {{0, 0, 0}, {1, 1, 0}, {1, -1, 0}, {-1, 1, 0}, {-1, -1, 0}};
  g.curves = {{{0, 1, 2, 0}}, {{0, 3, 4, 0}}};  // two loops from vertex 0
  FaceCosts costs(g, {}, kPlenty);
  EXPECT_EQ(costs.Cost({{0, false}, {1, false}}),
            6 * FaceCosts::kUnsurfaceable);
  EXPECT_NEAR(costs.Cost({{0, false}}).value(), 0, 1e-12);  // one lobe
}

// A long loop is priced by at most kMaxPoints of its points: every
// junction among them when its curves are few, evenly spaced along it when
// they are many.
TEST(FaceCostsTest, LongLoopsArePricedBySomeOfTheirPoints) {
  const NetworkGraph few = Ring(5000, 1000);
  const std::vector<Vec3> points = PricedPoints(few, AllForward(few));
  EXPECT_LE(points.size(), static_cast<size_t>(FaceCosts::kMaxPoints));
  EXPECT_GE(points.size(), static_cast<size_t>(FaceCosts::kMaxPoints) - 5);
  for (int32_t junction = 0; junction < 5000; junction += 1000) {
    EXPECT_EQ(std::count(points.begin(), points.end(), few.vertices[junction]),
              1);
  }
  FaceCosts costs(few, {}, kPlenty);
  const double cost = costs.Cost(AllForward(few)).value();
  EXPECT_GT(cost, 0);
  EXPECT_LT(cost, FaceCosts::kUnsurfaceable);  // DOT triangulated it
  // 2,500 curves of two edges: still kMaxPoints.
  const NetworkGraph many = Ring(5000, 2);
  EXPECT_EQ(PricedPoints(many, AllForward(many)).size(),
            static_cast<size_t>(FaceCosts::kMaxPoints));
}

// No price once the points to price are spent, or the caller stopped the
// run; what was priced stays.
TEST(FaceCostsTest, NoPriceOnceSpentOrStopped) {
  const NetworkGraph g = Square(0.5);
  FaceCosts costs(g, {}, 10);
  ASSERT_TRUE(costs.Cost(Forward()).has_value());  // 8 points
  EXPECT_FALSE(costs.spent());
  EXPECT_FALSE(costs.Cost({{0, false}, {0, true}}).has_value() &&
               costs.Cost({{1, false}, {1, true}}).has_value());
  EXPECT_TRUE(costs.spent());
  EXPECT_TRUE(costs.Cost(Backward()).has_value());  // priced before
  std::atomic<bool> cancel{true};
  Control stop;
  stop.cancel = &cancel;
  FaceCosts cancelled(g, stop, kPlenty);
  EXPECT_FALSE(cancelled.Cost(Forward()).has_value());
  EXPECT_EQ(cancelled.priced(), 0u);
}

}  // namespace
}  // namespace dot

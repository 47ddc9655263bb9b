// SPDX-License-Identifier: AGPL-3.0-or-later
// Every finite scale behaves like unit scale: the same triangles for the
// same polygon scaled by 1e-300 .. 1e300, costs in the caller's units, and
// weights whose weighted sums overflow refused by name.
#include "polygon/unit_scale.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dot/dot.h"

namespace dot {
namespace {

constexpr double kScales[] = {1e-300, 1e-200, 1e-100, 1e-10, 1,    1e10,
                              1e78,   1e100,  1e154,  1e200, 1e300};

std::vector<Vec3> Scaled(const std::vector<Vec3>& p, double s) {
  std::vector<Vec3> out;
  for (const Vec3& v : p) out.push_back(s * v);
  return out;
}

MetricWeights Only(Metric m) {
  MetricWeights w;
  w[m] = 1;
  return w;
}

TEST(UnitScaleTest, ScaleIsAnExactPowerOfTwo) {
  const UnitScale s = ChooseUnitScale({{3e-200, 0, 0}, {0, -1e-199, 0}});
  const Vec3 w = s.ToWork({0, -1e-199, 0});
  EXPECT_GE(std::abs(w.y), 0.5);
  EXPECT_LT(std::abs(w.y), 1.0);
  EXPECT_EQ(s.ToCaller(w).y, -1e-199);  // exact round trip
}

TEST(UnitScaleTest, WorkWeightsKeepTheRatiosOfTheObjective) {
  MetricWeights w;
  w[Metric::kArea] = 1;
  w[Metric::kPerimeter] = 1;
  w[Metric::kSquaredDihedral] = 1;
  const UnitScale s{10};  // work = caller * 1024
  const MetricWeights ww = WorkWeights(w, s);
  // area_caller = area_work / 2^20, perimeter_caller = perimeter_work / 2^10
  EXPECT_DOUBLE_EQ(ww[Metric::kPerimeter] / ww[Metric::kArea], 1024.0);
  EXPECT_DOUBLE_EQ(ww[Metric::kSquaredDihedral] / ww[Metric::kArea],
                   1024.0 * 1024.0);
  MetricWeights huge;
  huge[Metric::kArea] = 1e308;
  EXPECT_LE(std::abs(WorkWeights(huge, UnitScale{}).v[0]), 1.0);
}

const std::vector<std::vector<Vec3>>& Polygons() {
  static const auto* polygons = new std::vector<std::vector<Vec3>>{
      MakeCurve(Curve::kSpiral, 40), MakeCurve(Curve::kMonkey, 30),
      MakeCurve(Curve::kMobius, 24), MakeCurve(Curve::kMoment, 12)};
  return *polygons;
}

// Scaling by 2^j is exact: every outcome, ties included, must be the unit
// one, and the costs exactly rescaled (where representable).
TEST(UnitScaleTest, PowerOfTwoScalesGiveIdenticalResults) {
  for (const auto& polygon : Polygons()) {
    for (Metric m : {Metric::kArea, Metric::kPerimeter, Metric::kShape,
                     Metric::kSquaredDihedral}) {
      const Result unit = Triangulate({polygon, {}, Only(m), {}, {}});
      ASSERT_TRUE(unit.status.ok()) << unit.status.message;
      for (int j = -1000; j <= 1000; j += 125) {
        SCOPED_TRACE(std::string(MetricName(m)) + " at 2^" + std::to_string(j));
        const Result r = Triangulate(
            {Scaled(polygon, std::ldexp(1.0, j)), {}, Only(m), {}, {}});
        ASSERT_TRUE(r.status.ok()) << r.status.message;
        EXPECT_EQ(r.triangles, unit.triangles);
        const double area = std::ldexp(unit.metric_costs[Metric::kArea], 2 * j);
        if (std::isnormal(area)) {
          EXPECT_EQ(r.metric_costs[Metric::kArea], area);
        }
        EXPECT_EQ(r.metric_costs[Metric::kShape],
                  unit.metric_costs[Metric::kShape]);
      }
    }
  }
}

// Scaling by 10^j rounds every coordinate: the same optimum (the same
// triangles where the objective has no near-ties, as the angle-based
// metrics here; the same optimal cost for area and perimeter, whose
// planar parts tie), costs in the caller's units.
TEST(UnitScaleTest, DecimalScalesFrom1e300To1e300GiveTheSameOptimum) {
  for (const auto& polygon : Polygons()) {
    for (Metric m : {Metric::kArea, Metric::kPerimeter, Metric::kShape,
                     Metric::kSquaredDihedral}) {
      const Result unit = Triangulate({polygon, {}, Only(m), {}, {}});
      ASSERT_TRUE(unit.status.ok()) << unit.status.message;
      for (double s : kScales) {
        SCOPED_TRACE(std::string(MetricName(m)) + " at scale " +
                     std::to_string(std::log10(s)));
        const Result r = Triangulate({Scaled(polygon, s), {}, Only(m), {}, {}});
        ASSERT_TRUE(r.status.ok()) << r.status.message;
        EXPECT_EQ(r.vertices, Scaled(polygon, s));  // the caller's, exactly
        const int degree = m == Metric::kArea        ? 2
                           : m == Metric::kPerimeter ? 1
                                                     : 0;
        if (degree == 0) {
          EXPECT_EQ(r.triangles, unit.triangles);
          EXPECT_NEAR(r.total_cost, unit.total_cost, 1e-9);
        } else {
          const double expected = unit.total_cost * std::pow(s, degree);
          if (std::isnormal(expected)) {
            EXPECT_NEAR(r.total_cost / expected, 1.0, 1e-9);
          }
        }
      }
    }
  }
}

TEST(UnitScaleTest, OverflowingWeightedSumsAreRefused) {
  const auto polygon = Scaled(MakeCurve(Curve::kMonkey, 30), 10);
  for (double w : {1e308, -1e308}) {
    MetricWeights weights;
    weights[Metric::kArea] = w;
    const Result r = Triangulate({polygon, {}, weights, {}, {}});
    EXPECT_EQ(r.status.code, StatusCode::kInvalidArgument) << w;
    EXPECT_NE(r.status.message.find("overflows"), std::string::npos);
  }
  MetricWeights fine;
  fine[Metric::kArea] = 1e300;
  const Result r = Triangulate({polygon, {}, fine, {}, {}});
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_TRUE(std::isfinite(r.total_cost));
  // The same optimum as weight 1 (by cost: this polygon has equal-area
  // triangulations, and rounding may pick another of them).
  EXPECT_NEAR(
      r.total_cost / 1e300,
      Triangulate({polygon, {}, Only(Metric::kArea), {}, {}}).total_cost, 1e-9);
}

// Found by tests/fuzz/triangulate_fuzz: at 1e200 the (unweighted) area
// overflows in the caller's units, which hid the overflow of the weighted
// perimeter: OK with an infinite total cost.
TEST(UnitScaleTest, OverflowIsRefusedWhenAnUnweightedMetricOverflows) {
  const auto polygon = Scaled(MakeCurve(Curve::kMonkey, 30), 1e200);
  MetricWeights weights;
  weights[Metric::kPerimeter] = 1e200;
  const Result r = Triangulate({polygon, {}, weights, {}, {}});
  EXPECT_EQ(r.status.code, StatusCode::kInvalidArgument);
  EXPECT_NE(r.status.message.find("overflows"), std::string::npos);
  // With a weight that fits, the answer stands: the area is just too large
  // for a double.
  const Result fine =
      Triangulate({polygon, {}, Only(Metric::kPerimeter), {}, {}});
  ASSERT_TRUE(fine.status.ok()) << fine.status.message;
  EXPECT_TRUE(std::isfinite(fine.total_cost));
  EXPECT_TRUE(std::isinf(fine.metric_costs[Metric::kArea]));
  // Two weighted metrics overflowing with opposite signs: no total at all
  // (it was OK with a NaN cost).
  MetricWeights opposite;
  opposite[Metric::kArea] = 1;
  opposite[Metric::kPerimeter] = -1e200;
  const Result nan = Triangulate({polygon, {}, opposite, {}, {}});
  EXPECT_EQ(nan.status.code, StatusCode::kInvalidArgument);
  EXPECT_NE(nan.status.message.find("overflows"), std::string::npos);
}

// Found by tests/fuzz/triangulate_fuzz: scaling into the unit range pushed
// tiny coordinates below the normal range, so the solver decided another
// polygon than the caller's (its count of intersecting pairs, 4, was not
// the caller's polygon's, 2). Such polygons are refused by vertex.
TEST(UnitScaleTest, CoordinatesThatWouldLosePrecisionAreRefused) {
  const std::vector<Vec3> wide = {
      {-3.5976964249515829e-47, 1.5764348338827278e-312,
       2.9230032746618058e+48},
      {0, 5.3049894774131808e-315, 0},
      {0, 0, 2},
      {0, 0, 0},
      {3.4090529563046012e-322, 4.2510976414123851e+228,
       3.6028862992780596e+252},
      {9.267953447431126e+199, 4.3967344908398287e+199,
       1.4944621914822201e-76}};
  Options all;
  all.space = SearchSpace::kAll;
  all.planar_tolerance = 0;  // at 1e-6 it is collinear by tolerance
  const Result r = Triangulate({wide, {}, {}, {}, {}}, all);
  EXPECT_EQ(r.status.code, StatusCode::kInvalidArgument);
  EXPECT_EQ(r.status.message.rfind("vertex 0 ", 0), 0u) << r.status.message;
  // A subnormal coordinate next to ordinary ones, scaled down by 2^-3: its
  // low bits would be lost (and are not when they are zero).
  const double subnormal = std::ldexp(7.0, -1074);
  const Result sub = Triangulate(
      {{{0, 0, 0}, {4, 0, 0}, {4, 4, 1}, {subnormal, 4, 0}}, {}, {}, {}, {}});
  EXPECT_EQ(sub.status.code, StatusCode::kInvalidArgument);
  EXPECT_EQ(sub.status.message.rfind("vertex 3 ", 0), 0u) << sub.status.message;
  const Result kept =
      Triangulate({{{0, 0, 0}, {4, 0, 0}, {4, 4, 1}, {8 * subnormal, 4, 0}},
                   {},
                   {},
                   {},
                   {}});
  EXPECT_TRUE(kept.status.ok()) << kept.status.message;
  // Scaling up is always exact: subnormal polygons are fine.
  const Result tiny = Triangulate(
      {{{0, 0, 0}, {4e-320, 0, 0}, {4e-320, 4e-320, 1e-320}, {0, 4e-320, 0}},
       {},
       {},
       {},
       {}});
  EXPECT_TRUE(tiny.status.ok()) << tiny.status.message;
}

// Found by tests/fuzz/triangulate_fuzz: at the bottom of the subnormal
// range, a vertex inserted by edge protection (a midpoint) rounded on its
// way back to the caller's coordinates, and the mesh returned OK
// self-intersected there. Such a result is refused; two bits higher it is
// exact and valid.
TEST(UnitScaleTest, InsertedVerticesTheCallerCannotHoldAreRefused) {
  const int units[8][3] = {{-3, 0, -3}, {-2, 3, 0}, {-1, -2, 3}, {-3, 2, 0},
                           {1, 3, 2},   {1, 0, 2},  {1, 0, 0},   {1, 1, -2}};
  Options protect;
  protect.protect_edges = true;
  for (int exponent : {-1074, -1072}) {
    std::vector<Vec3> polygon;
    for (const auto& u : units) {
      polygon.push_back({std::ldexp(u[0], exponent), std::ldexp(u[1], exponent),
                         std::ldexp(u[2], exponent)});
    }
    const Result r = Triangulate({polygon, {}, {}, {}, {}}, protect);
    if (exponent == -1074) {
      EXPECT_EQ(r.status.code, StatusCode::kInvalidArgument);
      EXPECT_EQ(r.status.message.rfind("edge protection inserted vertex", 0),
                0u)
          << r.status.message;
      EXPECT_TRUE(r.triangles.empty());
    } else {
      ASSERT_TRUE(r.status.ok()) << r.status.message;
      EXPECT_FALSE(r.inserted.empty());
      const MeshReport report =
          ValidateMesh(r.vertices, r.polygon, r.triangles);
      EXPECT_TRUE(report.valid()) << report.first_problem;
    }
  }
}

}  // namespace
}  // namespace dot

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
      const Result unit = Triangulate({polygon, {}, Only(m)});
      ASSERT_TRUE(unit.status.ok()) << unit.status.message;
      for (int j = -1000; j <= 1000; j += 125) {
        SCOPED_TRACE(std::string(MetricName(m)) + " at 2^" + std::to_string(j));
        const Result r =
            Triangulate({Scaled(polygon, std::ldexp(1.0, j)), {}, Only(m)});
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
      const Result unit = Triangulate({polygon, {}, Only(m)});
      ASSERT_TRUE(unit.status.ok()) << unit.status.message;
      for (double s : kScales) {
        SCOPED_TRACE(std::string(MetricName(m)) + " at scale " +
                     std::to_string(std::log10(s)));
        const Result r = Triangulate({Scaled(polygon, s), {}, Only(m)});
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
    const Result r = Triangulate({polygon, {}, weights});
    EXPECT_EQ(r.status.code, StatusCode::kInvalidArgument) << w;
    EXPECT_NE(r.status.message.find("overflows"), std::string::npos);
  }
  MetricWeights fine;
  fine[Metric::kArea] = 1e300;
  const Result r = Triangulate({polygon, {}, fine});
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_TRUE(std::isfinite(r.total_cost));
  // The same optimum as weight 1 (by cost: this polygon has equal-area
  // triangulations, and rounding may pick another of them).
  EXPECT_NEAR(r.total_cost / 1e300,
              Triangulate({polygon, {}, Only(Metric::kArea)}).total_cost, 1e-9);
}

}  // namespace
}  // namespace dot

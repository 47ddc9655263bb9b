// SPDX-License-Identifier: AGPL-3.0-or-later
// The solvers' per-candidate cost evaluates only the weighted metrics, and
// equals the weighted sum of all of them bit for bit.
#include "dot/metrics.h"

#include <gtest/gtest.h>

#include <random>

namespace dot {
namespace {

TEST(WeightedTriangleCostTest, EqualsTheWeightedSumOfEveryMetricBitForBit) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(-2, 2);
  std::vector<Vec3> points, normals;
  for (int i = 0; i < 40; ++i) {
    points.push_back({coord(rng), coord(rng), coord(rng)});
    normals.push_back({coord(rng), coord(rng), coord(rng)});
  }
  points.push_back(points[0]);  // a degenerate triangle: zero area and shape
  MetricWeights one_each[kMetricCount];
  for (int m = 0; m < kMetricCount; ++m) one_each[m][kAllMetrics[m]] = 1.5;
  MetricWeights mixed;
  mixed[Metric::kArea] = 1;
  mixed[Metric::kShape] = 0.25;
  mixed[Metric::kNormalDeviation] = 0.5;
  std::vector<MetricWeights> weights(std::begin(one_each), std::end(one_each));
  weights.push_back(mixed);
  for (const MetricWeights& w : weights) {
    for (int i = 0; i + 2 < 41; ++i) {
      const Triangle t = {i, (i + 7) % 41, 40};
      EXPECT_EQ(WeightedTriangleCost(w, points, normals, t),
                WeightedTotal(w, PerTriangleMetrics(points, normals, t)));
    }
  }
}

}  // namespace
}  // namespace dot

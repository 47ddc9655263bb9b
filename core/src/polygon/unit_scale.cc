// SPDX-License-Identifier: AGPL-3.0-or-later
#include "polygon/unit_scale.h"

#include <algorithm>
#include <climits>

namespace dot {

int LengthDegree(Metric m) {
  switch (m) {
    case Metric::kArea:
      return 2;
    case Metric::kPerimeter:
      return 1;
    default:
      return 0;
  }
}

UnitScale ChooseUnitScale(const std::vector<Vec3>& vertices) {
  double largest = 0;
  for (const Vec3& v : vertices) {
    largest = std::max({largest, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  }
  UnitScale s;
  if (largest > 0) {
    int e = 0;
    std::frexp(largest, &e);  // largest = f * 2^e, f in [0.5, 1)
    s.exponent = -e;
  }
  return s;
}

MetricWeights WorkWeights(const MetricWeights& weights,
                          const UnitScale& scale) {
  // w_m * cost_caller = w_m * 2^(-d_m k) * cost_work: exponents kept apart
  // from mantissas so nothing overflows before the normalization.
  MetricWeights out;
  int top = INT_MIN;
  std::array<int, kMetricCount> exponent{};
  std::array<double, kMetricCount> mantissa{};
  for (Metric m : kAllMetrics) {
    const int i = static_cast<int>(m);
    if (weights[m] == 0) continue;
    mantissa[i] = std::frexp(weights[m], &exponent[i]);
    exponent[i] -= LengthDegree(m) * scale.exponent;
    top = std::max(top, exponent[i]);
  }
  for (Metric m : kAllMetrics) {
    const int i = static_cast<int>(m);
    if (weights[m] == 0) continue;
    out[m] = std::ldexp(mantissa[i], exponent[i] - top);
  }
  return out;
}

MetricValues ToCallerUnits(const MetricValues& work, const UnitScale& scale) {
  MetricValues out;
  for (Metric m : kAllMetrics) {
    out[m] = std::ldexp(work[m], -LengthDegree(m) * scale.exponent);
  }
  return out;
}

}  // namespace dot

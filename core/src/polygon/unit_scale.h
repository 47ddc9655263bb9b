// SPDX-License-Identifier: AGPL-3.0-or-later
// The solver works on the polygon scaled by a power of two so that its
// largest coordinate is in [0.5, 1). Scaling by 2^k is exact in floating
// point (barring subnormals), so every exact predicate decides as it would
// on the caller's coordinates, while fits, metrics and squared lengths stay
// far from overflow and underflow at any finite scale (1e-300 .. 1e300).
// The metric weights are rescaled to the same objective up to a positive
// factor, so the optimum is the caller's.
#ifndef DOT_CORE_POLYGON_UNIT_SCALE_H_
#define DOT_CORE_POLYGON_UNIT_SCALE_H_

#include <cmath>
#include <vector>

#include "dot/geometry.h"
#include "dot/metrics.h"

namespace dot {

struct UnitScale {
  int exponent = 0;  // work coordinates = caller's * 2^exponent

  Vec3 ToWork(const Vec3& v) const {
    return {std::ldexp(v.x, exponent), std::ldexp(v.y, exponent),
            std::ldexp(v.z, exponent)};
  }
  Vec3 ToCaller(const Vec3& v) const {
    return {std::ldexp(v.x, -exponent), std::ldexp(v.y, -exponent),
            std::ldexp(v.z, -exponent)};
  }
};

// Power of the length scale in metric m: area 2, perimeter 1, the angles
// and the shape measure 0.
int LengthDegree(Metric m);

// The scale of `vertices` (finite, not all zero).
UnitScale ChooseUnitScale(const std::vector<Vec3>& vertices);

// Weights giving, on work coordinates, the caller's objective times a
// positive factor (area scales by 4^k, perimeter by 2^k, the rest not at
// all), normalized so the largest magnitude is in [0.5, 1): a weight of
// 1e308 cannot overflow the sums. Weights that become negligible against
// the others (by more than a double's range) become 0.
MetricWeights WorkWeights(const MetricWeights& weights, const UnitScale& scale);

// Metric values measured on work coordinates, in the caller's units (an
// exact power-of-two rescaling: no intermediate overflow or underflow).
MetricValues ToCallerUnits(const MetricValues& work, const UnitScale& scale);

}  // namespace dot

#endif  // DOT_CORE_POLYGON_UNIT_SCALE_H_

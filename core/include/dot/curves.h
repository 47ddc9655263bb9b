// SPDX-License-Identifier: AGPL-3.0-or-later
// The paper's test curves (section 5.1), sampled with n vertices, and pairs
// of loops bounding one surface.
#ifndef DOT_CURVES_H_
#define DOT_CURVES_H_

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "dot/geometry.h"
#include "dot/mesh.h"

namespace dot {

enum class Curve { kMonkey, kMobius, kSpiral, kMoment, kTwist, kTrefoil };
inline constexpr Curve kPaperCurves[] = {Curve::kMonkey, Curve::kMobius,
                                         Curve::kSpiral, Curve::kMoment,
                                         Curve::kTwist};

std::string_view CurveName(Curve c);  // "monkey", "mobius", ...
std::optional<Curve> CurveFromName(std::string_view name);

// Monkey: boundary of a monkey saddle over the unit circle.
// Mobius: boundary of a Mobius strip (one loop around twice).
// Spiral: two stacked planar spirals joined at their ends (a spiral ribbon).
// Moment: p_i = (t_i, t_i^2, t_i^3) with t_i = i / n scaled to unit size.
// Twist: the Moment vertices in crisscross order p1, p(n-1), p3, ... (n odd;
//   an even n is rounded up).
// Trefoil: a trefoil knot, which has no triangulation at all.
// Monkey, Mobius, Spiral and Trefoil are sampled uniformly by arc length.
std::vector<Vec3> MakeCurve(Curve c, int n);

// Two loops of n vertices each (n >= 3) bounding one surface, to try
// several loops (Problem::loop_sizes): kTube, rims of radius 1 and 0.7 at
// heights 0 and 0.8 (a loft between two cross-sections); kIsland, a rim of
// radius 1 around an island rim of radius 0.35 just above its plane (a hole
// with an island). Loop 1 runs against loop 0, as the boundary of the
// surface between them does. Each vertex is moved, radially and in z, by up
// to a third of the point spacing (seeded): rims as a scan gives them.
enum class LoopPair { kTube, kIsland };
std::string_view LoopPairName(LoopPair p);  // "tube", "island"
std::optional<LoopPair> LoopPairFromName(std::string_view name);
PolygonData MakeLoopPair(LoopPair pair, int n, uint64_t seed = 1);

}  // namespace dot

#endif  // DOT_CURVES_H_

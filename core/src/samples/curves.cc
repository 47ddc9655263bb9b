// SPDX-License-Identifier: AGPL-3.0-or-later
#include "dot/curves.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

namespace dot {
namespace {

// n points uniformly spaced by arc length along the closed curve f(s),
// s in [0, 1), measured on a dense polyline.
std::vector<Vec3> SampleByArcLength(const std::function<Vec3(double)>& f,
                                    int n) {
  const int dense = std::max(20000, 40 * n);
  std::vector<Vec3> p(dense + 1);
  std::vector<double> len(dense + 1, 0);
  for (int i = 0; i <= dense; ++i) {
    p[i] = f(double(i) / dense);
    if (i > 0) len[i] = len[i - 1] + Distance(p[i - 1], p[i]);
  }
  std::vector<Vec3> out;
  out.reserve(n);
  int j = 0;
  for (int k = 0; k < n; ++k) {
    const double target = len[dense] * k / n;
    while (j + 1 < dense && len[j + 1] < target) ++j;
    const double seg = len[j + 1] - len[j];
    const double a = seg > 0 ? (target - len[j]) / seg : 0;
    out.push_back(p[j] + a * (p[j + 1] - p[j]));
  }
  return out;
}

// A point of the spiral ribbon: inner-to-outer spiral at z = 0, a vertical
// segment, the spiral back at z = h, and a segment down. Each of the four
// pieces gets a quarter of the parameter range.
Vec3 SpiralRibbon(double s) {
  constexpr double kTurns = 2, kH = 0.5;
  auto arm = [](double u, double z) {
    const double theta = 2 * kPi * kTurns * u;
    const double r = 0.3 + 0.7 * u;
    return Vec3{r * std::cos(theta), r * std::sin(theta), z};
  };
  const double u = 4 * s;
  if (u < 1) return arm(u, 0);
  if (u < 2) return Vec3{arm(1, 0).x, arm(1, 0).y, kH * (u - 1)};
  if (u < 3) return arm(3 - u, kH);
  return Vec3{arm(0, 0).x, arm(0, 0).y, kH * (4 - u)};
}

Vec3 MomentPoint(int i, int n) {
  const double t = double(i) / n;
  return {t, t * t, t * t * t};
}

}  // namespace

std::vector<Vec3> MakeCurve(Curve c, int n) {
  n = std::max(n, 3);
  switch (c) {
    case Curve::kMonkey:
      return SampleByArcLength(
          [](double s) {
            const double t = 2 * kPi * s;
            return Vec3{std::cos(t), std::sin(t), std::cos(3 * t)};
          },
          n);
    case Curve::kMobius:
      return SampleByArcLength(
          [](double s) {
            const double t = 4 * kPi * s, w = 0.4;
            const double r = 1 + w * std::cos(t / 2);
            return Vec3{r * std::cos(t), r * std::sin(t), w * std::sin(t / 2)};
          },
          n);
    case Curve::kSpiral:
      return SampleByArcLength(SpiralRibbon, n);
    case Curve::kTrefoil:
      return SampleByArcLength(
          [](double s) {
            const double t = 2 * kPi * s;
            return Vec3{std::sin(t) + 2 * std::sin(2 * t),
                        std::cos(t) - 2 * std::cos(2 * t), -std::sin(3 * t)};
          },
          n);
    case Curve::kMoment: {
      std::vector<Vec3> p;
      for (int i = 1; i <= n; ++i) p.push_back(MomentPoint(i, n));
      return p;
    }
    case Curve::kTwist: {
      if (n % 2 == 0) ++n;
      // Odd indices ascending interleaved with even ones descending:
      // p1, p(n-1), p3, p(n-3), ..., p(n-2), p2, pn.
      std::vector<Vec3> p;
      for (int k = 0; 2 * k + 1 <= n; ++k) {
        p.push_back(MomentPoint(2 * k + 1, n));
        if (n - 1 - 2 * k >= 2) p.push_back(MomentPoint(n - 1 - 2 * k, n));
      }
      return p;
    }
  }
  return {};
}

std::string_view CurveName(Curve c) {
  switch (c) {
    case Curve::kMonkey:
      return "monkey";
    case Curve::kMobius:
      return "mobius";
    case Curve::kSpiral:
      return "spiral";
    case Curve::kMoment:
      return "moment";
    case Curve::kTwist:
      return "twist";
    case Curve::kTrefoil:
      return "trefoil";
  }
  return "?";
}

std::string_view LoopPairName(LoopPair p) {
  return p == LoopPair::kTube ? "tube" : "island";
}

std::optional<LoopPair> LoopPairFromName(std::string_view name) {
  for (LoopPair p : {LoopPair::kTube, LoopPair::kIsland}) {
    if (LoopPairName(p) == name) return p;
  }
  return std::nullopt;
}

PolygonData MakeLoopPair(LoopPair pair, int n, uint64_t seed) {
  const bool tube = pair == LoopPair::kTube;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  PolygonData p;
  for (int l = 0; l < 2; ++l) {
    const double radius = l == 0 ? 1.0 : tube ? 0.7 : 0.35;
    const double height = l == 0 ? 0.0 : tube ? 0.8 : 0.05;
    const double noise = 2 * kPi * radius / n / 3;
    for (int i = 0; i < n; ++i) {
      const double a = (l == 0 ? 1 : -1) * 2 * kPi * i / n;
      const double r = radius + noise * u(rng);
      p.vertices.push_back(
          {r * std::cos(a), r * std::sin(a), height + noise * u(rng)});
    }
    p.loop_sizes.push_back(n);
  }
  return p;
}

std::optional<Curve> CurveFromName(std::string_view name) {
  for (Curve c : {Curve::kMonkey, Curve::kMobius, Curve::kSpiral,
                  Curve::kMoment, Curve::kTwist, Curve::kTrefoil}) {
    if (CurveName(c) == name) return c;
  }
  return std::nullopt;
}

}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
// The paper's test curves are sampled as specified.
#include <gtest/gtest.h>

#include "dot/dot.h"

namespace dot {
namespace {

TEST(CurveTest, TwistIsCrisscrossOrderOfMoment) {
  const auto moment = MakeCurve(Curve::kMoment, 7);
  const auto twist = MakeCurve(Curve::kTwist, 7);
  ASSERT_EQ(twist.size(), 7u);
  // p1, p6, p3, p4, p5, p2, p7 (1-based, as in the paper).
  const int order[] = {1, 6, 3, 4, 5, 2, 7};
  for (int i = 0; i < 7; ++i) EXPECT_EQ(twist[i], moment[order[i] - 1]);
}

TEST(CurveTest, SamplesAreDistinctAndSized) {
  for (Curve c : kPaperCurves) {
    const auto v = MakeCurve(c, 101);
    EXPECT_EQ(v.size(), 101u) << CurveName(c);
    for (size_t i = 0; i < v.size(); ++i) {
      EXPECT_GT(Distance(v[i], v[(i + 1) % v.size()]), 0) << CurveName(c);
    }
  }
}

TEST(CurveTest, NamesRoundTrip) {
  for (Curve c : {Curve::kMonkey, Curve::kMobius, Curve::kSpiral,
                  Curve::kMoment, Curve::kTwist, Curve::kTrefoil}) {
    EXPECT_EQ(CurveFromName(CurveName(c)), c);
  }
  EXPECT_FALSE(CurveFromName("lissajous").has_value());
}

}  // namespace
}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
// The cubic "Delaunay first" program against brute force: every
// triangulation of small random polygons enumerated, preferred triangles
// counted, costs evaluated directly.
#include "solve/interval_dp.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <random>
#include <set>

#include "dot/dot.h"
#include "fixtures/brute_force.h"

namespace dot {
namespace {

struct Case {
  IntervalDpInput in;
  std::set<Triangle> allowed;  // non-degenerate, no forbidden chord
  std::set<Triangle> preferred;
};

Case RandomCase(std::mt19937_64& rng, int n, const MetricWeights& w) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::bernoulli_distribution coin(0.5), rare(0.1);
  Case c;
  for (int i = 0; i < n; ++i) {
    c.in.points.push_back({u(rng), u(rng), u(rng)});
    c.in.normals.push_back(Normalized(Vec3{u(rng), u(rng), 1.5}));
    c.in.edge_normals.push_back(coin(rng) ? Normalized(Vec3{u(rng), u(rng), 1})
                                          : Vec3{});
  }
  c.in.weights = w;
  std::set<std::pair<int, int>> forbidden;
  for (int i = 0; i < n; ++i) {
    for (int k = i + 2; k < n; ++k) {
      if ((i == 0 && k == n - 1) || !rare(rng)) continue;
      forbidden.insert({i, k});
      c.in.forbidden.emplace_back(k, i);  // either order is taken
    }
  }
  auto chord_ok = [&](int a, int b) { return !forbidden.count({a, b}); };
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      for (int d = b + 1; d < n; ++d) {
        if (!chord_ok(a, b) || !chord_ok(b, d) || !chord_ok(a, d)) continue;
        c.allowed.insert({a, b, d});
        if (coin(rng)) {
          c.preferred.insert({a, b, d});
          c.in.preferred.push_back({d, a, b});  // any vertex order
        }
      }
    }
  }
  return c;
}

struct Best {
  int count = 1 << 30;
  double cost = std::numeric_limits<double>::infinity();
};

// The lexicographic minimum (triangles outside `preferred`, then cost)
// over every triangulation.
Best BruteForce(const Case& c) {
  std::vector<std::vector<Triangle>> all;
  testing::EnumerateChain(0, static_cast<int>(c.in.points.size()) - 1,
                          c.allowed, &all);
  Best best;
  for (const auto& t : all) {
    int count = 0;
    for (const Triangle& x : t) count += c.preferred.count(x) ? 0 : 1;
    const double cost = WeightedTotal(
        c.in.weights,
        EvaluateMetrics(c.in.points, c.in.normals, t, c.in.edge_normals));
    if (count < best.count || (count == best.count && cost < best.cost)) {
      best = {count, cost};
    }
  }
  return best;
}

double Evaluate(const Case& c, const std::vector<Triangle>& t) {
  return WeightedTotal(c.in.weights, EvaluateMetrics(c.in.points, c.in.normals,
                                                     t, c.in.edge_normals));
}

MetricWeights Weights(std::initializer_list<std::pair<Metric, double>> ws) {
  MetricWeights w;
  for (auto [m, v] : ws) w[m] = v;
  return w;
}

void ExpectUsesAllowedTriangles(const Case& c,
                                const std::vector<Triangle>& triangles) {
  for (Triangle t : triangles) {
    // Oriented like the loop: ascending positions, or a rotation of them.
    EXPECT_TRUE(t[0] < t[1] ? (t[1] < t[2] || t[2] < t[0])
                            : (t[1] < t[2] && t[2] < t[0]));
    std::sort(t.begin(), t.end());
    EXPECT_TRUE(c.allowed.count(t)) << t[0] << " " << t[1] << " " << t[2];
  }
}

TEST(IntervalDpTest, PerTriangleWeightsGiveTheBruteForceOptimum) {
  std::mt19937_64 rng(11);
  const MetricWeights mixes[] = {
      Weights({{Metric::kArea, 1}}),
      Weights({{Metric::kPerimeter, 1}, {Metric::kShape, 0.5}}),
      Weights({{Metric::kNormalDeviation, 1}, {Metric::kArea, 0.2}}),
  };
  int solved = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const MetricWeights& w = mixes[trial % 3];
    const Case c = RandomCase(rng, 4 + trial % 6, w);
    const Best best = BruteForce(c);
    IntervalDpSolution sol;
    const Status s = SolveIntervalDp(c.in, {}, &sol);
    if (best.count == 1 << 30) {
      EXPECT_EQ(s.code, StatusCode::kNoTriangulation) << "trial " << trial;
      continue;
    }
    ASSERT_TRUE(s.ok()) << "trial " << trial << ": " << s.message;
    ++solved;
    EXPECT_EQ(sol.not_preferred, best.count) << "trial " << trial;
    EXPECT_NEAR(sol.cost, best.cost, 1e-9 * (1 + std::abs(best.cost)))
        << "trial " << trial;
    EXPECT_NEAR(Evaluate(c, sol.triangles), sol.cost,
                1e-9 * (1 + std::abs(sol.cost)));
    EXPECT_EQ(sol.triangles.size(), c.in.points.size() - 2);
    ExpectUsesAllowedTriangles(c, sol.triangles);
  }
  EXPECT_GT(solved, 90);  // the forbidden chords leave most solvable
}

TEST(IntervalDpTest, BendingIsPricedAtItsTrueCostAndNeverBeatsTheOptimum) {
  std::mt19937_64 rng(12);
  const MetricWeights w =
      Weights({{Metric::kSquaredDihedral, 1}, {Metric::kArea, 0.1}});
  int exact = 0, solved = 0;
  for (int trial = 0; trial < 80; ++trial) {
    const Case c = RandomCase(rng, 5 + trial % 5, w);
    const Best best = BruteForce(c);
    IntervalDpSolution sol;
    const Status s = SolveIntervalDp(c.in, {}, &sol);
    if (best.count == 1 << 30) continue;
    ASSERT_TRUE(s.ok()) << s.message;
    ++solved;
    // The count is exact whatever the weights (it is additive).
    EXPECT_EQ(sol.not_preferred, best.count) << "trial " << trial;
    // The reported cost is the answer's own, and no better than the best.
    EXPECT_NEAR(Evaluate(c, sol.triangles), sol.cost,
                1e-9 * (1 + std::abs(sol.cost)))
        << "trial " << trial;
    EXPECT_GE(sol.cost, best.cost - 1e-9 * (1 + std::abs(best.cost)));
    exact += sol.cost <= best.cost + 1e-9 * (1 + std::abs(best.cost));
    ExpectUsesAllowedTriangles(c, sol.triangles);
  }
  // An approximation, but not a poor one on small polygons.
  EXPECT_GT(exact, solved / 2) << exact << " of " << solved << " optimal";
}

TEST(IntervalDpTest, NoTriangulationWhenEveryOneNeedsAForbiddenChord) {
  IntervalDpInput in;
  in.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2}, {0, 1, 0}};
  in.weights[Metric::kArea] = 1;
  in.forbidden = {{0, 2}, {1, 3}};
  IntervalDpSolution sol;
  EXPECT_EQ(SolveIntervalDp(in, {}, &sol).code, StatusCode::kNoTriangulation);
  in.forbidden = {{0, 2}};
  ASSERT_TRUE(SolveIntervalDp(in, {}, &sol).ok());
  EXPECT_EQ(sol.triangles.size(), 2u);
  EXPECT_EQ(sol.not_preferred, 2);  // nothing was preferred
}

TEST(IntervalDpTest, StopsWhenCancelled) {
  IntervalDpInput in;
  for (int i = 0; i < 400; ++i) {
    const double a = 2 * M_PI * i / 400;
    in.points.push_back({std::cos(a), std::sin(a), 0.3 * std::sin(5 * a)});
  }
  in.weights[Metric::kArea] = 1;
  std::atomic<bool> cancel{true};
  Control control;
  control.cancel = &cancel;
  IntervalDpSolution sol;
  EXPECT_EQ(SolveIntervalDp(in, control, &sol).code, StatusCode::kCancelled);
}

// Through Triangulate: a polygon with no Delaunay triangulation (the
// paper's trefoil-like knot is too small; a twisted band of many turns
// is not) gets one that is checked and counted.
TEST(IntervalDpTest, TriangulateDelaunayFirstValidatesItsAnswer) {
  Problem p;
  const int n = 120;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    p.vertices.push_back({std::cos(3 * a) * (2 + std::cos(2 * a)),
                          std::sin(3 * a) * (2 + std::cos(2 * a)),
                          std::sin(2 * a)});
  }
  Options o;
  o.space = SearchSpace::kDelaunayFirst;
  const Result r = Triangulate(p, o);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_EQ(r.space_used, SpaceUsed::kAllDelaunayFirst);
  EXPECT_EQ(r.solver, Solver::kGk1);
  EXPECT_EQ(r.triangles.size(), static_cast<size_t>(n - 2));
  EXPECT_EQ(r.intersecting_pairs,
            CountIntersectingPairs(r.vertices, r.triangles));
  EXPECT_TRUE(ValidateMesh(r.vertices, r.polygon, r.triangles, false).valid());
  // The band has no triangulation over its Delaunay triangles alone.
  Options delaunay;
  delaunay.space = SearchSpace::kDelaunay;
  EXPECT_EQ(Triangulate(p, delaunay).status.code, StatusCode::kNoTriangulation);
  EXPECT_GT(r.stats.non_delaunay_triangles, 0);
  EXPECT_LT(r.stats.non_delaunay_triangles, n - 2);
  Options small = o;
  small.memory_budget_bytes = 1000;
  const Result refused_memory = Triangulate(p, small);
  EXPECT_EQ(refused_memory.status.code, StatusCode::kResourceExhausted);
  EXPECT_NE(refused_memory.status.message.find("exceeds the budget"),
            std::string::npos);

  // The Delaunay space, where it has an answer, is what it keeps.
  Problem ring;
  for (int i = 0; i < 40; ++i) {
    const double a = 2 * M_PI * i / 40;
    ring.vertices.push_back({std::cos(a), std::sin(a), 0.2 * std::cos(3 * a)});
  }
  const Result d = Triangulate(ring, o);
  ASSERT_TRUE(d.status.ok()) << d.status.message;
  EXPECT_EQ(d.stats.non_delaunay_triangles, 0);
  EXPECT_EQ(d.intersecting_pairs, 0);

  ring.weights[Metric::kSquaredDihedral] = 1;
  EXPECT_EQ(Triangulate(ring, o).solver, Solver::kGk2Greedy);

  Problem two = ring;
  two.loop_sizes = {20, 20};
  const Result refused = Triangulate(two, o);
  EXPECT_EQ(refused.status.code, StatusCode::kInvalidArgument);
  EXPECT_NE(refused.status.message.find("takes one loop"), std::string::npos);
  o.delaunay_first_max_vertices = 30;
  const Result big = Triangulate(ring, o);
  EXPECT_EQ(big.status.code, StatusCode::kResourceExhausted);
  EXPECT_NE(big.status.message.find("limited to 30"), std::string::npos);
}

}  // namespace
}  // namespace dot

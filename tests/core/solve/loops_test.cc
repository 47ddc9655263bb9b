// SPDX-License-Identifier: AGPL-3.0-or-later
// Two loops into one surface (Problem::loop_sizes): the solver's optimum
// against an exhaustive search over every genus-0 surface in the same
// candidate set, every result validated exactly, and the contract's edges:
// orientation, planar islands, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <set>

#include "dot/dot.h"
#include "fixtures/brute_force_surface.h"
#include "fixtures/search_spaces.h"

namespace dot {
namespace {

// A noisy circle of n points at height z, radius r, counter-clockwise seen
// from +z (clockwise when `reverse`).
void AddLoop(std::mt19937_64& rng, int n, double r, double z, double noise,
             bool reverse, Problem* p) {
  std::uniform_real_distribution<double> u(-noise, noise);
  const double phase = std::uniform_real_distribution<double>(0, 6.28)(rng);
  for (int i = 0; i < n; ++i) {
    const double a = phase + (reverse ? -1 : 1) * 2 * kPi * i / n;
    p->vertices.push_back(
        {r * std::cos(a) + u(rng), r * std::sin(a) + u(rng), z + u(rng)});
    p->normals.push_back(Normalized(Vec3{u(rng), u(rng), 1.0}));
  }
  p->loop_sizes.push_back(n);
}

std::vector<std::pair<const char*, MetricWeights>> Mixes() {
  auto mk = [](std::initializer_list<std::pair<Metric, double>> ws) {
    MetricWeights w;
    for (auto [m, x] : ws) w[m] = x;
    return w;
  };
  return {
      {"area", mk({{Metric::kArea, 1}})},
      {"perimeter+shape", mk({{Metric::kPerimeter, 1}, {Metric::kShape, 0.5}})},
      {"normal_deviation", mk({{Metric::kNormalDeviation, 1}})},
      {"squared_dihedral", mk({{Metric::kSquaredDihedral, 1}})},
      {"area+dihedral", mk({{Metric::kArea, 1}, {Metric::kDihedral, 0.4}})},
      {"max_twist", mk({{Metric::kSquaredDihedral, -1}})}};
}

// The reference over both directions of loop 1 when the solver may
// reverse it.
testing::SurfaceMinimum Reference(const Problem& p, const std::set<Triangle>& s,
                                  const MetricWeights& w, bool reorient,
                                  bool* reversed) {
  std::vector<int32_t> a, b;
  for (int32_t i = 0; i < p.loop_sizes[0]; ++i) a.push_back(i);
  for (int32_t i = 0; i < p.loop_sizes[1]; ++i)
    b.push_back(p.loop_sizes[0] + i);
  testing::SurfaceMinimum best =
      testing::BruteForceSurface(p.vertices, p.normals, {a, b}, s, w);
  *reversed = false;
  if (reorient) {
    std::reverse(b.begin(), b.end());
    testing::SurfaceMinimum flipped =
        testing::BruteForceSurface(p.vertices, p.normals, {a, b}, s, w);
    if (flipped.best < best.best) {
      *reversed = true;
      flipped.surfaces += best.surfaces;
      return flipped;
    }
    best.surfaces += flipped.surfaces;
  }
  return best;
}

void ExpectOptimal(const Problem& p, SearchSpace space, bool reorient,
                   const std::set<Triangle>& reference_space,
                   const std::string& what, int* solved, int* none) {
  for (const auto& [name, w] : Mixes()) {
    Problem q = p;
    q.weights = w;
    const std::string where = what + " " + name;
    bool ref_reversed = false;
    const testing::SurfaceMinimum ref =
        Reference(q, reference_space, w, reorient, &ref_reversed);
    Options o;
    o.space = space;
    o.reorient_loops = reorient;
    const Result r = Triangulate(q, o);
    if (ref.surfaces == 0) {
      EXPECT_EQ(r.status.code, StatusCode::kNoTriangulation)
          << where << ": " << r.status.message;
      ++*none;
      continue;
    }
    ASSERT_TRUE(r.status.ok()) << where << ": " << r.status.message;
    EXPECT_NEAR(ref.best, r.total_cost,
                1e-9 * std::max(1.0, std::fabs(ref.best)))
        << where << " (" << ref.surfaces << " surfaces)";
    ASSERT_EQ(r.loop_sizes.size(), 2u) << where;
    const MeshReport report = ValidateSurface(
        r.vertices, ResultLoops(r), r.triangles, space != SearchSpace::kAll);
    EXPECT_TRUE(report.valid()) << where << ": " << report.first_problem;
    // The boundary runs each loop's way (reversed ones reversed).
    EXPECT_TRUE(report.boundary_is_polygon) << where;
    if (std::fabs(ref.best - r.total_cost) > 1e-6) continue;
    ++*solved;
  }
}

TEST(LoopsOptimalityTest, TwoLoopsEqualExhaustiveSearchOverDelaunay) {
  std::mt19937_64 rng(20261127);
  int solved = 0, none = 0;
  for (int trial = 0; trial < 60; ++trial) {
    Problem p;
    const int n1 = 3 + trial % 3, n2 = 3 + (trial / 3) % 3;  // 3..5 each
    const bool island = trial % 2 == 0;
    // An island: a small loop inside a large one, near its plane; a tube:
    // two loops one above the other.
    AddLoop(rng, n1, 1.0, 0, 0.25, false, &p);
    AddLoop(rng, n2, island ? 0.35 : 0.8, island ? 0.1 : 0.9, 0.2,
            trial % 4 < 2, &p);
    ExpectOptimal(p, SearchSpace::kDelaunay, trial % 5 != 0,
                  testing::ReferenceDelaunaySpace(p.vertices),
                  "trial " + std::to_string(trial), &solved, &none);
  }
  std::printf("solved %d, no surface %d\n", solved, none);
  EXPECT_GT(solved, 100);
}

TEST(LoopsOptimalityTest, TwoLoopsEqualExhaustiveSearchOverAllTriangles) {
  std::mt19937_64 rng(20261128);
  int solved = 0, none = 0;
  for (int trial = 0; trial < 16; ++trial) {
    Problem p;
    const int n1 = 3 + trial % 2, n2 = 3 + (trial / 2) % 2;  // 3..4 each
    AddLoop(rng, n1, 1.0, 0, 0.3, false, &p);
    AddLoop(rng, n2, 0.6, 0.5, 0.3, trial % 3 == 0, &p);
    const int n = n1 + n2;
    ExpectOptimal(p, SearchSpace::kAll, trial % 2 == 0,
                  testing::AllTriangleSpace(n),
                  "all trial " + std::to_string(trial), &solved, &none);
  }
  std::printf("solved %d, no surface %d\n", solved, none);
  EXPECT_GT(solved, 80);
}

// Three loops: a pants (a wide rim below two small rims side by side) or a
// ring with two islands; small enough for the exhaustive reference.
Problem ThreeLoops(std::mt19937_64& rng, int trial) {
  Problem p;
  const int n0 = 3 + trial % 2, n1 = 3 + (trial / 2) % 2, n2 = 3;
  const bool pants = trial % 3 != 0;
  AddLoop(rng, n0, 1.0, 0, 0.15, false, &p);
  const size_t first = p.vertices.size();
  AddLoop(rng, n1, 0.3, pants ? 0.9 : 0.1, 0.1, pants, &p);
  for (size_t v = first; v < p.vertices.size(); ++v) p.vertices[v].x -= 0.45;
  const size_t second = p.vertices.size();
  AddLoop(rng, n2, 0.3, pants ? 0.9 : 0.1, 0.1, pants, &p);
  for (size_t v = second; v < p.vertices.size(); ++v) p.vertices[v].x += 0.45;
  return p;
}

TEST(LoopsApproximationTest, ThreeLoopsAreValidAndNeverBelowTheOptimum) {
  std::mt19937_64 rng(20261129);
  int cases = 0, found = 0, optimal = 0, exists = 0;
  double worst = 1;
  for (int trial = 0; trial < 24; ++trial) {
    const Problem base = ThreeLoops(rng, trial);
    const auto space = testing::ReferenceDelaunaySpace(base.vertices);
    std::vector<std::vector<int32_t>> loops(3);
    int32_t id = 0;
    for (int l = 0; l < 3; ++l) {
      for (int32_t i = 0; i < base.loop_sizes[l]; ++i) loops[l].push_back(id++);
    }
    for (Metric m : {Metric::kArea, Metric::kSquaredDihedral}) {
      Problem p = base;
      p.weights[m] = 1;
      const std::string where =
          "trial " + std::to_string(trial) + " " + std::string(MetricName(m));
      const testing::SurfaceMinimum ref = testing::BruteForceSurface(
          p.vertices, p.normals, loops, space, p.weights);
      Options o;
      o.space = SearchSpace::kDelaunay;
      const Result r = Triangulate(p, o);
      ++cases;
      if (ref.surfaces == 0) {
        EXPECT_EQ(r.status.code, StatusCode::kNoTriangulation) << where;
        continue;
      }
      ++exists;
      if (!r.status.ok()) {
        EXPECT_EQ(r.status.code, StatusCode::kNoTriangulation) << where;
        EXPECT_NE(r.status.message.find("approximate"), std::string::npos)
            << where << ": " << r.status.message;
        continue;
      }
      ++found;
      EXPECT_EQ(r.bridges.size(), 2u) << where;
      const MeshReport report =
          ValidateSurface(r.vertices, ResultLoops(r), r.triangles);
      EXPECT_TRUE(report.valid()) << where << ": " << report.first_problem;
      EXPECT_TRUE(report.boundary_is_polygon) << where;
      EXPECT_EQ(report.intersecting_pairs, 0) << where;
      // An approximation: never below the optimum, often at it.
      EXPECT_GE(r.total_cost, ref.best - 1e-9 * std::max(1.0, ref.best))
          << where;
      optimal += r.total_cost <= ref.best + 1e-9 * std::max(1.0, ref.best);
      worst = std::max(worst, r.total_cost / ref.best);
    }
  }
  std::printf(
      "3 loops: %d cases, a surface exists in %d, bridged found %d, "
      "optimal in %d, worst cost ratio %.3f\n",
      cases, exists, found, optimal, worst);
  EXPECT_GT(found, exists / 2);
}

TEST(LoopsApproximationTest, SphereWithCapsRemovedIsOneSurface) {
  // A unit sphere's six caps around the axes cut away: six loops of 12.
  Problem p;
  const Vec3 axes[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                        {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  for (const Vec3& d : axes) {
    const Vec3 helper = std::fabs(d.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
    const Vec3 u = Normalized(Cross(d, helper)), v = Cross(d, u);
    const double h = 0.85, radius = std::sqrt(1 - h * h);
    for (int i = 0; i < 12; ++i) {
      const double a = 2 * kPi * i / 12;
      p.vertices.push_back(h * d + radius * std::cos(a) * u +
                           radius * std::sin(a) * v);
    }
    p.loop_sizes.push_back(12);
  }
  for (Metric m : {Metric::kArea, Metric::kSquaredDihedral}) {
    p.weights = {};
    p.weights[m] = 1;
    const Result r = Triangulate(p);
    ASSERT_TRUE(r.status.ok()) << MetricName(m) << ": " << r.status.message;
    EXPECT_EQ(r.triangles.size(), 72u + 2 * 4);  // n + 2 (k - 2)
    EXPECT_EQ(r.bridges.size(), 5u);
    const MeshReport report =
        ValidateSurface(r.vertices, ResultLoops(r), r.triangles);
    EXPECT_TRUE(report.valid()) << report.first_problem;
  }
}

Problem Tube(int n, bool same_direction) {
  Problem p;
  for (int l = 0; l < 2; ++l) {
    for (int i = 0; i < n; ++i) {
      // Loop 1 runs against loop 0, as a tube's two rims do along it.
      const double a = 2 * kPi * i / n * (l == 1 && !same_direction ? -1 : 1);
      p.vertices.push_back({std::cos(a), std::sin(a), double(l)});
    }
    p.loop_sizes.push_back(n);
  }
  return p;
}

TEST(LoopsTest, TubeIsAnAnnulusCloseToTheCylinder) {
  const Result r = Triangulate(Tube(100, false));
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  const MeshReport report =
      ValidateSurface(r.vertices, ResultLoops(r), r.triangles);
  EXPECT_TRUE(report.valid()) << report.first_problem;
  EXPECT_EQ(report.intersecting_pairs, 0);
  EXPECT_EQ(r.triangles.size(), 200u);  // an annulus: as many as vertices
  EXPECT_TRUE(r.reversed_loops.empty());
  // The lateral area of the inscribed prism, 100 * |chord| * 1.
  const double lateral = 100 * 2 * std::sin(kPi / 100);
  EXPECT_NEAR(r.total_cost, lateral, 1e-6 * lateral);
  EXPECT_EQ(r.space_used, SpaceUsed::kDelaunay3d);
}

TEST(LoopsTest, LoopGivenTheOtherWayIsReversedOrRefused) {
  const Problem p = Tube(40, true);
  const Result r = Triangulate(p);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_EQ(r.reversed_loops, std::vector<int32_t>{1});
  EXPECT_TRUE(ValidateSurface(r.vertices, ResultLoops(r), r.triangles).valid());
  // The result's loop 1 is the input's, reversed.
  EXPECT_EQ(r.polygon[40], 40);
  EXPECT_EQ(r.polygon[41], 79);

  Options keep;
  keep.reorient_loops = false;
  const Result k = Triangulate(p, keep);
  // A tube whose rims run the same way has no oriented surface of
  // Delaunay triangles: it would have to twist.
  EXPECT_EQ(k.status.code, StatusCode::kNoTriangulation) << k.status.message;
  EXPECT_NE(k.status.message.find("one does with it reversed"),
            std::string::npos)
      << k.status.message;
  EXPECT_TRUE(k.reversed_loops.empty());
}

TEST(LoopsTest, PlanarIslandFillsTheRingExactly) {
  Problem p;
  // A 4 x 4 square (counter-clockwise) around a 1 x 1 island (clockwise).
  p.vertices = {{0, 0, 0},     {4, 0, 0},     {4, 4, 0},     {0, 4, 0},
                {1.5, 1.5, 0}, {1.5, 2.5, 0}, {2.5, 2.5, 0}, {2.5, 1.5, 0}};
  p.loop_sizes = {4, 4};
  Options o;
  o.reorient_loops = false;
  const Result r = Triangulate(p, o);
  ASSERT_TRUE(r.status.ok()) << r.status.message;
  EXPECT_EQ(r.space_used, SpaceUsed::kPlanarDelaunay2d);
  EXPECT_TRUE(r.planar);
  EXPECT_DOUBLE_EQ(r.total_cost, 16 - 1);
  EXPECT_EQ(r.triangles.size(), 8u);
  const MeshReport report =
      ValidateSurface(r.vertices, ResultLoops(r), r.triangles);
  EXPECT_TRUE(report.valid()) << report.first_problem;
}

TEST(LoopsTest, CoplanarLoopsSideBySideHaveNoSurface) {
  Problem p;
  p.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                {3, 0, 0}, {4, 0, 0}, {4, 1, 0}, {3, 1, 0}};
  p.loop_sizes = {4, 4};
  const Result r = Triangulate(p);
  EXPECT_EQ(r.status.code, StatusCode::kNoTriangulation);
  EXPECT_NE(r.status.message.find("one encloses the other"), std::string::npos)
      << r.status.message;
}

TEST(LoopsTest, BudgetRefusesBeforeListingAllTriangles) {
  Options all;
  all.space = SearchSpace::kAll;
  all.memory_budget_bytes = int64_t{64} << 20;
  const Result r = Triangulate(Tube(150, false), all);
  EXPECT_EQ(r.status.code, StatusCode::kResourceExhausted);
  EXPECT_NE(r.status.message.find("all triangles on 300 vertices"),
            std::string::npos)
      << r.status.message;
}

TEST(LoopsTest, MalformedLoopsAreRefusedByName) {
  Problem p = Tube(5, false);
  p.loop_sizes = {5, 4};
  EXPECT_NE(Triangulate(p).status.message.find("sum to 9"), std::string::npos);
  p.loop_sizes = {8, 2};
  EXPECT_NE(Triangulate(p).status.message.find("loop 1 has 2 vertices"),
            std::string::npos);
  p.loop_sizes = {3, 3, 1, 3};
  EXPECT_NE(Triangulate(p).status.message.find("loop 2 has 1 vertex"),
            std::string::npos)
      << Triangulate(p).status.message;
  // A forbidden edge that is an edge of loop 1 (its last to its first).
  p = Tube(5, false);
  p.forbidden_edges = {{9, 5}};
  EXPECT_NE(Triangulate(p).status.message.find("is a polygon edge"),
            std::string::npos);
}

}  // namespace
}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
// DOT1/DOT2 against brute-force enumeration inside the same search space,
// GK1/GK2 against the unrestricted brute force, on random small polygons.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <set>

#include "dot/dot.h"
#include "fixtures/brute_force.h"
#include "fixtures/search_spaces.h"
#include "mesh/edge_index.h"
#include "search_space/delaunay_cgal.h"
#include "search_space/faces_of_tetrahedra.h"

namespace dot {
namespace {

struct Mix {
  const char* name;
  MetricWeights w;
};

std::vector<Mix> MetricMixes() {
  auto mk = [](const char* name,
               std::initializer_list<std::pair<Metric, double>> ws) {
    Mix m{name, {}};
    for (auto [metric, weight] : ws) m.w[metric] = weight;
    return m;
  };
  return {
      mk("area", {{Metric::kArea, 1}}),
      mk("perimeter", {{Metric::kPerimeter, 1}}),
      mk("shape", {{Metric::kShape, 1}}),
      mk("normal_deviation", {{Metric::kNormalDeviation, 1}}),
      mk("squared_dihedral", {{Metric::kSquaredDihedral, 1}}),
      mk("dihedral", {{Metric::kDihedral, 1}}),
      mk("max_twist", {{Metric::kSquaredDihedral, -1}}),
      mk("area+sqdihedral",
         {{Metric::kArea, 1}, {Metric::kSquaredDihedral, 0.3}}),
      mk("everything", {{Metric::kArea, 0.7},
                        {Metric::kPerimeter, 0.2},
                        {Metric::kNormalDeviation, 0.5},
                        {Metric::kShape, 0.4},
                        {Metric::kDihedral, -0.3},
                        {Metric::kSquaredDihedral, 0.8}}),
  };
}

Problem RandomProblem(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(-1, 1);
  Problem p;
  for (int i = 0; i < n; ++i) {
    p.vertices.push_back({u(rng), u(rng), u(rng)});
    p.normals.push_back(Normalized(Vec3{u(rng), u(rng), 1.5}));
  }
  return p;
}

using testing::AllTriangleSpace;
using testing::ReferenceDelaunaySpace;

void ExpectNear(double expected, double actual, const std::string& what) {
  EXPECT_NEAR(expected, actual, 1e-9 * std::max(1.0, std::fabs(expected)))
      << what;
}

TEST(OptimalityTest, DotAndGkEqualBruteForceOnRandomPolygons) {
  std::mt19937_64 rng(20261122);
  int solved = 0, no_triangulation = 0;
  const auto mixes = MetricMixes();
  for (int trial = 0; trial < 240; ++trial) {
    const int n = 4 + trial % 6;  // 4..9
    Problem p = RandomProblem(rng, n);
    const std::set<Triangle> delaunay = ReferenceDelaunaySpace(p.vertices);
    const std::set<Triangle> all = AllTriangleSpace(n);
    for (const Mix& mix : mixes) {
      p.weights = mix.w;
      const std::string what = "trial " + std::to_string(trial) +
                               " n=" + std::to_string(n) + " metric " +
                               mix.name;
      const auto ref_dot =
          testing::BruteForceMinimum(p.vertices, p.normals, delaunay, mix.w);
      const auto ref_gk =
          testing::BruteForceMinimum(p.vertices, p.normals, all, mix.w);

      Options dot_options;
      dot_options.space = SearchSpace::kDelaunay;
      const Result dot = Triangulate(p, dot_options);
      if (ref_dot.triangulations == 0) {
        EXPECT_EQ(dot.status.code, StatusCode::kNoTriangulation) << what;
        ++no_triangulation;
      } else {
        ASSERT_TRUE(dot.status.ok()) << what << ": " << dot.status.message;
        ExpectNear(ref_dot.best, dot.total_cost, what + " (DOT)");
        EXPECT_EQ(dot.solver,
                  HasBiTriangleWeight(mix.w) ? Solver::kDot2 : Solver::kDot1);
        const MeshReport report =
            ValidateMesh(dot.vertices, dot.polygon, dot.triangles);
        EXPECT_TRUE(report.valid()) << what << ": " << report.first_problem;
        ++solved;
      }

      Options gk_options;
      gk_options.space = SearchSpace::kAll;
      const Result gk = Triangulate(p, gk_options);
      ASSERT_TRUE(gk.status.ok()) << what << ": " << gk.status.message;
      ExpectNear(ref_gk.best, gk.total_cost, what + " (GK)");
      EXPECT_GE(gk.intersecting_pairs, 0) << what;
      EXPECT_EQ(gk.solver,
                HasBiTriangleWeight(mix.w) ? Solver::kGk2 : Solver::kGk1);
      if (dot.status.ok()) {
        EXPECT_GE(dot.total_cost, gk.total_cost - 1e-9) << what;
      }
    }
  }
  // The sample must exercise both outcomes to mean anything.
  std::printf("solved %d, no triangulation %d\n", solved, no_triangulation);
  EXPECT_GT(solved, 1000);
  EXPECT_GT(no_triangulation, 10);
}

// Hole filling: bending against the faces across the polygon edges, and
// chords the surrounding mesh already has, against brute force over the
// same space minus those chords.
TEST(OptimalityTest, EdgeFaceNormalsAndForbiddenChordsEqualBruteForce) {
  std::mt19937_64 rng(20261124);
  std::uniform_real_distribution<double> u(-1, 1);
  int solved = 0, bent = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const int n = 5 + trial % 5;  // 5..9
    Problem p = RandomProblem(rng, n);
    for (int i = 0; i < n; ++i) {
      // Some edges have no face across them.
      p.edge_face_normals.push_back(
          i % 4 == 3 ? Vec3{} : Normalized(Vec3{u(rng), u(rng), 1.0}));
    }
    const int a = trial % n, b = (a + 2 + trial % (n - 3)) % n;
    p.forbidden_edges = {{a, b}};
    const uint64_t key = UndirectedEdgeKey(a, b);
    for (const auto& [space, reference] :
         {std::pair{SearchSpace::kDelaunay, ReferenceDelaunaySpace(p.vertices)},
          std::pair{SearchSpace::kAll, AllTriangleSpace(n)}}) {
      std::set<Triangle> allowed;
      for (const Triangle& t : reference) {
        if (UndirectedEdgeKey(t[0], t[1]) != key &&
            UndirectedEdgeKey(t[1], t[2]) != key &&
            UndirectedEdgeKey(t[0], t[2]) != key) {
          allowed.insert(t);
        }
      }
      for (const Mix& mix : MetricMixes()) {
        p.weights = mix.w;
        const std::string what = "trial " + std::to_string(trial) + " " +
                                 mix.name +
                                 (space == SearchSpace::kAll ? " all" : "");
        const auto ref = testing::BruteForceMinimum(
            p.vertices, p.normals, allowed, mix.w, p.edge_face_normals);
        Options o;
        o.space = space;
        const Result r = Triangulate(p, o);
        if (ref.triangulations == 0) {
          EXPECT_EQ(r.status.code, StatusCode::kNoTriangulation) << what;
          continue;
        }
        ASSERT_TRUE(r.status.ok()) << what << ": " << r.status.message;
        ExpectNear(ref.best, r.total_cost, what);
        for (const Triangle& t : r.triangles) {
          EXPECT_NE(UndirectedEdgeKey(t[0], t[1]), key) << what;
          EXPECT_NE(UndirectedEdgeKey(t[1], t[2]), key) << what;
          EXPECT_NE(UndirectedEdgeKey(t[0], t[2]), key) << what;
        }
        ++solved;
        if (HasBiTriangleWeight(mix.w)) {
          const MetricValues plain =
              EvaluateMetrics(r.vertices, p.normals, r.triangles);
          if (r.metric_costs[Metric::kDihedral] >
              plain[Metric::kDihedral] + 1e-9) {
            ++bent;
          }
        }
      }
    }
  }
  std::printf("solved %d, with boundary bending %d\n", solved, bent);
  EXPECT_GT(solved, 1000);
  EXPECT_GT(bent, 200);
}

TEST(OptimalityTest, AutoFallsBackToAllWhenNoDelaunayTriangulation) {
  std::mt19937_64 rng(7);
  int fallbacks = 0;
  for (int trial = 0; trial < 200 && fallbacks < 5; ++trial) {
    Problem p = RandomProblem(rng, 8);
    p.normals.clear();
    Options delaunay_only;
    delaunay_only.space = SearchSpace::kDelaunay;
    if (Triangulate(p, delaunay_only).status.code !=
        StatusCode::kNoTriangulation) {
      continue;
    }
    ++fallbacks;
    Options all;
    all.space = SearchSpace::kAll;
    const Result optimum = Triangulate(p, all);
    ASSERT_TRUE(optimum.status.ok()) << optimum.status.message;
    const Result r = Triangulate(p);  // kAuto
    // Accepted only when intersection-free.
    if (optimum.intersecting_pairs == 0) {
      ASSERT_TRUE(r.status.ok()) << r.status.message;
      EXPECT_EQ(r.space_used, SpaceUsed::kAll);
      EXPECT_EQ(r.triangles, optimum.triangles);
    } else {
      EXPECT_EQ(r.status.code, StatusCode::kNoTriangulation);
    }
    Options no_fallback;
    no_fallback.all_space_max_vertices = 7;
    EXPECT_EQ(Triangulate(p, no_fallback).status.code,
              StatusCode::kNoTriangulation);
  }
  EXPECT_EQ(fallbacks, 5);
}

TEST(OptimalityTest, SameInputSameTriangles) {
  const std::vector<Vec3> v = MakeCurve(Curve::kMonkey, 300);
  Problem p{v, {}, {}, {}, {}};
  p.weights[Metric::kSquaredDihedral] = 1;
  const Result a = Triangulate(p), b = Triangulate(p);
  ASSERT_TRUE(a.status.ok()) << a.status.message;
  EXPECT_EQ(a.triangles, b.triangles);
}

}  // namespace
}  // namespace dot

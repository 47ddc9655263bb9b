// SPDX-License-Identifier: AGPL-3.0-or-later
// Several loops into one surface (Problem::loop_sizes): time and peak heap
// of the annulus solver on tubes between two rims and on holes with an
// island, DOT1 (area) and DOT2 (squared dihedral), every output validated
// as a sphere with two holes (exact intersection test, outside the timing).
#include <cmath>
#include <fstream>
#include <iostream>
#include <random>

#include "measure.h"
#include "suite.h"

namespace dot::bench {
namespace {

Problem TwoRims(LoopPair pair, int n, uint64_t seed) {
  const PolygonData d = MakeLoopPair(pair, n, seed);
  Problem p;
  p.vertices = d.vertices;
  p.loop_sizes = d.loop_sizes;
  return p;
}

// Two exact circles (no noise), the tube's radii and heights: cocircular
// rims, whose Delaunay tetrahedralization has more faces.
Problem ExactTube(int n) {
  Problem p;
  for (int l = 0; l < 2; ++l) {
    const double r = l ? 0.7 : 1.0;
    for (int i = 0; i < n; ++i) {
      const double a = (l ? -1 : 1) * 2 * kPi * i / n;
      p.vertices.push_back({r * std::cos(a), r * std::sin(a), l ? 0.8 : 0});
    }
    p.loop_sizes.push_back(n);
  }
  return p;
}

// A unit sphere with `k` caps cut away around fixed directions (the axes,
// then two diagonals), each rim a circle of n points at height h along its
// direction, with seeded noise of a tenth of the point spacing. The rims
// run so that the sphere's remaining surface is on their left.
Problem SphereCaps(int k, int n, double h, uint64_t seed) {
  const double s = 1 / std::sqrt(3.0);
  const Vec3 dirs[8] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0},
                        {0, 0, 1}, {0, 0, -1}, {s, s, s}, {-s, -s, s}};
  std::mt19937_64 rng(seed);
  const double r = std::sqrt(1 - h * h);
  std::uniform_real_distribution<double> noise(-0.1, 0.1);
  Problem p;
  for (int l = 0; l < k; ++l) {
    const Vec3& d = dirs[l];
    const Vec3 helper = std::fabs(d.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
    const Vec3 u = Normalized(Cross(d, helper)), v = Cross(d, u);
    const double spacing = 2 * kPi * r / n;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * kPi * i / n;
      p.vertices.push_back(h * d + r * std::cos(a) * u + r * std::sin(a) * v +
                           spacing * Vec3{noise(rng), noise(rng), noise(rng)});
    }
    p.loop_sizes.push_back(n);
  }
  return p;
}

}  // namespace

int RunLoops(const Config& config, std::ostream& report) {
  struct Case {
    std::string name;
    Problem problem;
  };
  std::vector<Case> cases;
  const std::vector<int> sizes = config.quick
                                     ? std::vector<int>{50, 200}
                                     : std::vector<int>{50, 200, 500, 1000};
  for (int n : sizes) {
    cases.push_back({"tube 2 x " + std::to_string(n),
                     TwoRims(LoopPair::kTube, n, 1000 + n)});
  }
  for (int n : sizes) {
    cases.push_back({"island 2 x " + std::to_string(n),
                     TwoRims(LoopPair::kIsland, n, 2000 + n)});
  }
  cases.push_back({"cocircular tube 2 x 200", ExactTube(200)});
  // Three and more loops (bridges first: an approximation).
  cases.push_back({"sphere - 3 caps, 3 x 200", SphereCaps(3, 200, 0.85, 3)});
  cases.push_back({"sphere - 4 caps, 4 x 125", SphereCaps(4, 125, 0.85, 4)});
  cases.push_back({"sphere - 6 caps, 6 x 12", SphereCaps(6, 12, 0.85, 6)});
  if (!config.quick) {
    cases.push_back({"sphere - 8 caps, 8 x 50", SphereCaps(8, 50, 0.93, 8)});
    cases.push_back({"sphere - 6 caps, 6 x 200", SphereCaps(6, 200, 0.85, 60)});
  }
  struct Row {
    std::string name, solver;
    int n;
    Sample s;
    Result r;
  };
  std::vector<Row> rows;
  int invalid = 0;
  Options options;
  options.protect_edges = true;  // noisy rims have non-Delaunay edges
  for (const Case& c : cases) {
    for (const auto& [solver, metric] :
         {std::pair{"DOT1", Metric::kArea},
          std::pair{"DOT2", Metric::kSquaredDihedral}}) {
      std::cerr << "loops: " << c.name << " " << solver << "\n";
      Result r;
      const Sample s = Measure(
          config.reps, config.long_run_s, config.cap_s,
          [&] { r = SolveWith(c.problem, OneMetric(metric), options); });
      if (r.status.ok()) {
        const MeshReport m =
            ValidateSurface(r.vertices, ResultLoops(r), r.triangles);
        if (!m.valid()) {
          std::cerr << "loops: INVALID " << c.name << " " << solver << ": "
                    << m.first_problem << "\n";
          ++invalid;
        }
      } else {
        std::cerr << "loops: " << c.name << " " << solver << ": "
                  << r.status.message << "\n";
        ++invalid;
      }
      rows.push_back(
          {c.name, solver, static_cast<int>(c.problem.vertices.size()), s, r});
    }
  }
  std::ofstream csv(config.Path("loops.csv"));
  csv << "case,solver,vertices,ms,runs,heap_bytes,candidates,dp_states,"
         "triangles,ok\n";
  for (const Row& r : rows) {
    csv << r.name << "," << r.solver << "," << r.n << "," << r.s.ms << ","
        << r.s.runs << "," << r.s.heap << "," << r.r.stats.search_triangles
        << "," << r.r.stats.dp_states << "," << r.r.triangles.size() << ","
        << r.r.status.ok() << "\n";
  }
  report << "## Several loops: one surface joining the rims\n\n"
         << "Tubes (rims of radius 1 and 0.7, 0.8 apart) and holes with an "
            "island (radius 0.35, nearly coplanar), seeded noise, edge "
            "protection on; the cocircular tube has none (its Delaunay "
            "tetrahedralization has Θ(n²) faces). Spheres with k caps cut "
            "away: k rims (three or more loops: bridges first, then the "
            "optimum for them). Every output validated "
            "(genus 0, boundary = the loops, exact intersection test): "
         << invalid << " invalid. Data: `loops.csv`.\n\n"
         << "| case | solver | ms | peak heap | candidates | DP states | "
            "result |\n|---|---|---:|---:|---:|---:|---|\n";
  for (const Row& r : rows) {
    report << "| " << r.name << " | " << r.solver << " | "
           << (r.s.capped ? "> cap (" + Fixed(r.s.ms, 0) + ")" : Fixed(r.s.ms))
           << " | " << Mib(r.s.heap) << " | " << r.r.stats.search_triangles
           << " | " << r.r.stats.dp_states << " | "
           << (r.r.status.ok()
                   ? std::to_string(r.r.triangles.size()) + " triangles"
                   : std::string(StatusCodeName(r.r.status.code)))
           << " |\n";
  }
  report << "\n";
  return invalid;
}

}  // namespace dot::bench

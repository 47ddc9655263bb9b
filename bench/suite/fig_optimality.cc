// SPDX-License-Identifier: AGPL-3.0-or-later
// How much the Delaunay restriction costs: the optimum over all triangles
// (GK1/GK2) divided by the optimum over Delaunay triangles (DOT1/DOT2), per
// metric, on curves and hole boundaries of up to a few hundred vertices.
// 1 means the restriction lost nothing; GK may self-intersect, DOT never.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>

#include "measure.h"
#include "suite.h"

namespace dot::bench {

void RunOptimality(const Config& config, std::ostream& report) {
  struct Input {
    std::string name;
    std::vector<Vec3> loop;
  };
  std::vector<Input> inputs;
  const std::vector<int> sizes =
      config.quick ? std::vector<int>{20} : std::vector<int>{30, 60, 100};
  for (Curve c : kPaperCurves) {
    for (int n : sizes) {
      inputs.push_back({std::string(CurveName(c)) + "-" + std::to_string(n),
                        MakeCurve(c, n)});
    }
  }
  for (const HoleCase& h :
       MakeHoles(config, config.quick ? 3 : 20, 20, config.quick ? 60 : 150)) {
    inputs.push_back(
        {h.mesh + "-hole-" + std::to_string(h.triangles), h.boundary.vertices});
  }
  const std::vector<Metric> metrics = {Metric::kArea, Metric::kPerimeter,
                                       Metric::kDihedral,
                                       Metric::kSquaredDihedral};
  std::ofstream csv(config.Path("optimality.csv"));
  csv << "input,n,metric,dot_cost,gk_cost,ratio,gk_intersecting_pairs\n";
  report << "## Optimality: all triangles against Delaunay triangles\n\n"
         << "GK cost / DOT cost on " << inputs.size()
         << " inputs (5 curves at n = ";
  for (size_t i = 0; i < sizes.size(); ++i)
    report << (i ? ", " : "") << sizes[i];
  report << ", and hole boundaries); inputs DOT cannot triangulate are "
            "left out. Data: `optimality.csv`.\n\n"
         << "| metric | inputs | equal (ratio 1) | median ratio | min ratio "
            "| GK results self-intersecting |\n|---|---:|---:|---:|---:|---:|"
            "\n";
  Options dot_options, gk_options;
  dot_options.space = SearchSpace::kDelaunay;
  gk_options.space = SearchSpace::kAll;
  for (Metric m : metrics) {
    std::vector<double> ratios;
    int intersecting = 0;
    for (const Input& in : inputs) {
      const Problem p{in.loop, {}, OneMetric(m), {}, {}};
      const Result d = Triangulate(p, dot_options);
      if (!d.status.ok()) continue;
      const Result g = Triangulate(p, gk_options);
      if (!g.status.ok()) continue;
      const double ratio = d.total_cost > 0 ? g.total_cost / d.total_cost : 1;
      ratios.push_back(ratio);
      intersecting += g.intersecting_pairs > 0;
      csv << in.name << "," << in.loop.size() << "," << MetricName(m) << ","
          << d.total_cost << "," << g.total_cost << "," << ratio << ","
          << g.intersecting_pairs << "\n";
    }
    std::cerr << "optimality: " << MetricName(m) << " done\n";
    const auto equal =
        std::count_if(ratios.begin(), ratios.end(),
                      [](double r) { return std::abs(r - 1) <= 1e-9; });
    report << "| " << MetricName(m) << " | " << ratios.size() << " | " << equal
           << " | " << Fixed(Median(ratios), 4) << " | "
           << (ratios.empty()
                   ? "-"
                   : Fixed(*std::min_element(ratios.begin(), ratios.end()), 4))
           << " | " << intersecting << " |\n";
  }
  report << "\n";
}

}  // namespace dot::bench

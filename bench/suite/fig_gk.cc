// SPDX-License-Identifier: AGPL-3.0-or-later
// Figure 6 (paper): the full search over all triangles, GK1 (area) and GK2
// (squared dihedral), time and memory against n, each series ending at the
// first point over the time cap.
#include <fstream>
#include <iostream>

#include "measure.h"
#include "plot.h"
#include "suite.h"

namespace dot::bench {

void RunGk(const Config& config, std::ostream& report) {
  const std::vector<int> sizes =
      config.quick
          ? std::vector<int>{10, 20, 30}
          : std::vector<int>{10, 20, 40, 60, 80, 100, 150, 200, 250, 300, 400};
  struct Row {
    const char* solver;
    int n;
    Sample s;
    int64_t table_bytes;
  };
  std::vector<Row> rows;
  Options all;
  all.space = SearchSpace::kAll;
  all.memory_budget_bytes = int64_t{16} << 30;
  for (const auto& [name, metric] :
       {std::pair{"GK1", Metric::kArea},
        std::pair{"GK2", Metric::kSquaredDihedral}}) {
    for (int n : sizes) {
      std::cerr << "gk: " << name << " n=" << n << "\n";
      const Problem p{
          MakeCurve(Curve::kSpiral, n), {}, OneMetric(metric), {}, {}};
      Result r;
      const Sample s = Measure(config.reps, config.long_run_s, config.cap_s,
                               [&] { r = Triangulate(p, all); });
      rows.push_back({name, n, s, r.stats.table_bytes});
      if (s.capped || !r.status.ok()) break;
    }
  }
  std::ofstream csv(config.Path("fig6-gk.csv"));
  csv << "solver,n,ms,runs,heap_bytes,table_bytes,capped\n";
  for (const Row& r : rows) {
    csv << r.solver << "," << r.n << "," << r.s.ms << "," << r.s.runs << ","
        << r.s.heap << "," << r.table_bytes << "," << r.s.capped << "\n";
  }
  auto series = [&](const std::string& solver, bool memory) {
    Series s{solver, {}, {}};
    for (const Row& r : rows) {
      if (r.solver != solver) continue;
      s.x.push_back(r.n);
      s.y.push_back(memory ? r.s.heap : r.s.ms);
    }
    return s;
  };
  report << "## Figure 6: search over all triangles (GK1, GK2)\n\n"
         << "Spiral curve; each series stops at the first run over "
         << config.cap_s << " s. Data: `fig6-gk.csv`.\n\n";
  for (bool memory : {false, true}) {
    Plot plot{config.Path(memory ? "fig6-memory.png" : "fig6-time.png"),
              memory ? "GK1 / GK2 peak heap" : "GK1 / GK2 time",
              "n",
              memory ? "bytes" : "ms",
              false,
              true,
              {series("GK1", memory), series("GK2", memory)}};
    RenderPlot(plot);
    report << "![" << plot.title << "]("
           << (memory ? "fig6-memory.png" : "fig6-time.png") << ")\n";
  }
  report << "\n| solver | n | ms | peak heap |\n|---|---:|---:|---:|\n";
  for (const Row& r : rows) {
    report << "| " << r.solver << " | " << r.n << " | "
           << (r.s.capped ? "> cap (" + Fixed(r.s.ms, 0) + ")" : Fixed(r.s.ms))
           << " | " << Mib(r.s.heap) << " |\n";
  }
  report << "\n";
}

}  // namespace dot::bench

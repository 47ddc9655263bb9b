// SPDX-License-Identifier: AGPL-3.0-or-later
// dot-bench: the benchmark suite. Each figure is a free function that
// measures, writes its CSV and plots into the output directory and appends
// its section to the Markdown report.
#ifndef DOT_BENCH_SUITE_H_
#define DOT_BENCH_SUITE_H_

#include <ostream>
#include <string>
#include <vector>

#include "dot/dot.h"

namespace dot::bench {

struct Config {
  std::string out_dir = "bench-results";
  std::string mesh_dir;                  // libcgal-demo's data/meshes
  std::string server_path, dotctl_path;  // for the service figure
  std::string cgal_fill_path;            // CGAL's whole-process peer
  bool quick = false;                    // small sizes: a smoke run
  int reps = 5;                          // runs per point (medians)
  double long_run_s = 2;  // runs longer than this are repeated 3 times only
  double cap_s = 20;      // a run longer than this ends its series
  int holes = 200;        // hole boundaries for Figure 5

  std::string Path(const std::string& file) const {
    return out_dir + "/" + file;
  }
};

// Sizes are the paper's where the issue names them; each function documents
// what it measures.
// These two also validate every mesh they produce (ValidateMesh, exact
// intersection tests, outside the timings) and return how many were
// invalid.
int RunCurves(const Config& config, std::ostream& report);
int RunHoles(const Config& config, std::ostream& report);
void RunGk(const Config& config, std::ostream& report);
void RunOptimality(const Config& config, std::ostream& report);
void RunService(const Config& config, std::ostream& report);
// Whole processes on scan-size meshes; returns the runs that failed or
// left a hole open.
int RunScan(const Config& config, std::ostream& report);
// Several loops into one surface (fig_loops.cc); returns the outputs that
// failed or did not validate.
int RunLoops(const Config& config, std::ostream& report);
int RunIslands(const Config& config, std::ostream& report);
// Curve networks into surfaces (fig_network.cc); returns the outputs that
// failed or did not validate.
int RunNetwork(const Config& config, std::ostream& report);

// Formatting shared by the figures.
std::string Fixed(double v, int digits = 1);  // "-" for NaN
std::string Mib(double bytes);                // "12.3 MiB", "-" for NaN

// One solve with `options`; `weights` replaces the problem's.
Result SolveWith(const Problem& problem, const MetricWeights& weights,
                 const Options& options = {}, const Control& control = {});
MetricWeights OneMetric(Metric m);
// 1 when `r` succeeded with a mesh that fails ValidateMesh (reported on
// stderr), else 0.
int InvalidOutput(const Result& r, const std::string& what);

// Hole boundaries grown on the libcgal-demo meshes in config.mesh_dir:
// `count` of them, sizes log-uniform in [min_triangles, max_triangles],
// alternating between the meshes.
struct HoleCase {
  std::string mesh;
  int triangles = 0;
  PolygonData boundary;
};
std::vector<HoleCase> MakeHoles(const Config& config, int count,
                                int min_triangles, int max_triangles);

}  // namespace dot::bench

#endif  // DOT_BENCH_SUITE_H_

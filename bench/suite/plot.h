// SPDX-License-Identifier: AGPL-3.0-or-later
// Figures: each series goes to a .dat file, a gnuplot script draws them into
// a PNG (log-log, like the paper's), lines with the fitted log-log slope in
// the legend, or scatter points.
#ifndef DOT_BENCH_PLOT_H_
#define DOT_BENCH_PLOT_H_

#include <string>
#include <vector>

namespace dot::bench {

struct Series {
  std::string title;
  std::vector<double> x, y;
};

struct Plot {
  std::string path;  // PNG to write; .gp and .dat files go next to it
  std::string title, xlabel, ylabel;
  bool scatter = false;  // points only (no lines)
  bool fit = true;       // slope of log y against log x in each legend
  std::vector<Series> series;
};

// Writes the data and script and runs gnuplot; returns each series' slope
// (NaN when it has fewer than two points). A missing gnuplot leaves the
// script for later and is reported on stderr.
std::vector<double> RenderPlot(const Plot& plot);

}  // namespace dot::bench

#endif  // DOT_BENCH_PLOT_H_

// SPDX-License-Identifier: AGPL-3.0-or-later
#include "plot.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "measure.h"

namespace dot::bench {

std::vector<double> RenderPlot(const Plot& plot) {
  const std::string stem = plot.path.substr(0, plot.path.rfind('.'));
  std::vector<double> slopes;
  std::ofstream gp(stem + ".gp");
  gp << "set terminal pngcairo size 900,620 font ',11'\n"
     << "set output '" << plot.path << "'\n"
     << "set title '" << plot.title << "'\n"
     << "set xlabel '" << plot.xlabel << "'\nset ylabel '" << plot.ylabel
     << "'\nset logscale xy\nset grid\nset key left top\nset termoption "
        "noenhanced\n";
  std::string plots;
  for (size_t i = 0; i < plot.series.size(); ++i) {
    const Series& s = plot.series[i];
    const std::string dat = stem + "-" + std::to_string(i) + ".dat";
    std::ofstream d(dat);
    int points = 0;
    for (size_t k = 0; k < s.x.size(); ++k) {
      if (s.x[k] > 0 && s.y[k] > 0) {
        d << s.x[k] << " " << s.y[k] << "\n";
        ++points;
      }
    }
    const double slope = LogLogSlope(s.x, s.y);
    slopes.push_back(slope);
    if (points == 0) continue;
    std::string title = s.title;
    if (plot.fit && !std::isnan(slope)) {
      char buf[48];
      std::snprintf(buf, sizeof buf, " (slope %.2f)", slope);
      title += buf;
    }
    plots += (plots.empty() ? "plot " : ", ") + std::string("'") + dat +
             "' using 1:2 with " +
             (plot.scatter ? "points pt 7 ps 0.6" : "linespoints pt 7") +
             " title '" + title + "'";
  }
  gp << (plots.empty() ? "set label 'no data' at graph 0.5,0.5\nplot NaN"
                       : plots)
     << "\n";
  gp.close();
  const std::string cmd = "gnuplot '" + stem + ".gp' 2>/dev/null";
  if (std::system(cmd.c_str()) != 0) {
    std::cerr << "dot-bench: gnuplot failed on " << stem
              << ".gp (is gnuplot-nox installed?)\n";
  }
  return slopes;
}

}  // namespace dot::bench

// SPDX-License-Identifier: AGPL-3.0-or-later
// Figure 4 (paper): the five curves at growing n. For each point: Delaunay
// triangles, the Delaunay step with each backend, DOT1 (area) and DOT2
// (squared dihedral) end to end, a cached re-solve with new weights, table
// memory and peak heap; and the peer, CGAL's triangulate_hole_polyline, on
// the same polygon with our metrics evaluated on its output.
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>

#include "cgal_peer.h"
#include "measure.h"
#include "plot.h"
#include "suite.h"

namespace dot::bench {
namespace {

struct Point {
  std::string curve;
  int n = 0;
  std::string status, status2;  // DOT1's, DOT2's
  int64_t delaunay_triangles = 0, table_bytes_dot1 = 0, table_bytes_dot2 = 0;
  double delaunay_cgal_ms = NAN, delaunay_tetgen_ms = NAN;
  double after_delaunay_ms = NAN;  // DOT1 adjacency + DP + tiling
  Sample dot1, dot2, cached, peer;
  bool peer_ok = false;
  double our_area = NAN, peer_area = NAN, our_sqd = NAN, peer_sqd = NAN;
};

std::vector<int> Sizes(const Config& c) {
  if (c.quick) return {50, 100, 200};
  return {50, 100, 200, 500, 1000, 2000, 5000, 10000, 50000};
}

// Median time of the Delaunay step the core reports over `reps` solves.
double DelaunayMs(const Problem& p, const Options& o, int reps) {
  std::vector<double> ms;
  for (int r = 0; r < reps; ++r)
    ms.push_back(Triangulate(p, o).stats.delaunay_ms);
  return Median(ms);
}

}  // namespace

int RunCurves(const Config& config, std::ostream& report) {
  std::vector<Point> points;
  int invalid = 0, checked = 0;
  const MetricWeights area = OneMetric(Metric::kArea);
  const MetricWeights sqd = OneMetric(Metric::kSquaredDihedral);
  for (Curve curve : kPaperCurves) {
    std::map<std::string, bool> capped;                  // per method
    std::map<std::string, std::pair<int, double>> last;  // n, ms
    // Skips a method whose last time, grown quadratically, passes the cap
    // (the pathological curves have ~n^2 Delaunay triangles).
    auto skip = [&](const std::string& method, int n) {
      if (capped[method]) return true;
      const auto it = last.find(method);
      if (it == last.end()) return false;
      const double grow = static_cast<double>(n) / it->second.first;
      return it->second.second * grow * grow > 1000 * config.cap_s;
    };
    for (int n : Sizes(config)) {
      if (skip("dot1", n) && skip("dot2", n) && skip("peer", n)) break;
      Point pt;
      pt.curve = CurveName(curve);
      pt.n = n;
      const Problem p{MakeCurve(curve, n), {}, area, {}, {}};
      std::cerr << "curves: " << pt.curve << " n=" << n << "\n";
      Result r1, r2;
      if (!skip("dot1", n)) {
        std::vector<double> delaunay_ms, after_ms;  // per run, from the core
        pt.dot1 = Measure(config.reps, config.long_run_s, config.cap_s, [&] {
          r1 = SolveWith(p, area);
          delaunay_ms.push_back(r1.stats.delaunay_ms);
          after_ms.push_back(r1.stats.adjacency_ms + r1.stats.dp_ms +
                             r1.stats.tiling_ms);
        });
        capped["dot1"] =
            pt.dot1.capped || r1.status.code == StatusCode::kResourceExhausted;
        last["dot1"] = {n, pt.dot1.ms};
        pt.status = StatusCodeName(r1.status.code);
        invalid += InvalidOutput(r1, pt.curve + " DOT1");
        checked += r1.status.ok();
        pt.delaunay_triangles = r1.stats.delaunay_triangles;
        pt.table_bytes_dot1 = r1.stats.table_bytes;
        if (r1.status.ok()) pt.our_area = r1.metric_costs[Metric::kArea];
        if (r1.status.ok() && !pt.dot1.capped) {
          const int reps = pt.dot1.runs;
          pt.delaunay_cgal_ms = Median(delaunay_ms);
          pt.after_delaunay_ms = Median(after_ms);
          Options tetgen;
          tetgen.delaunay = DelaunayBackend::kTetgen;
          pt.delaunay_tetgen_ms = DelaunayMs(p, tetgen, reps);
          // A user dragging a weight slider: the same polygon, new weights.
          SpaceCache cache(int64_t{2} << 30);
          Control control;
          control.space_cache = &cache;
          SolveWith(p, area, {}, control);
          int k = 0;
          pt.cached = Measure(reps, config.long_run_s, config.cap_s, [&] {
            MetricWeights w = area;
            w[Metric::kPerimeter] = 0.1 * ++k;
            SolveWith(p, w, {}, control);
          });
        }
      }
      if (!skip("dot2", n)) {
        pt.dot2 = Measure(config.reps, config.long_run_s, config.cap_s,
                          [&] { r2 = SolveWith(p, sqd); });
        capped["dot2"] =
            pt.dot2.capped || r2.status.code == StatusCode::kResourceExhausted;
        last["dot2"] = {n, pt.dot2.ms};
        pt.table_bytes_dot2 = r2.stats.table_bytes;
        pt.status2 = StatusCodeName(r2.status.code);
        invalid += InvalidOutput(r2, pt.curve + " DOT2");
        checked += r2.status.ok();
        if (r2.status.ok()) {
          pt.our_sqd = r2.metric_costs[Metric::kSquaredDihedral];
        }
      }
      // The peer where the targets compare (and below), up to the cap.
      if (!skip("peer", n) && (config.quick || n <= 10000)) {
        std::vector<Triangle> patch;
        pt.peer = Measure(config.reps, config.long_run_s, config.cap_s,
                          [&] { patch = CgalFillHole(p.vertices); });
        capped["peer"] = pt.peer.capped;
        last["peer"] = {n, pt.peer.ms};
        pt.peer_ok = patch.size() + 2 == p.vertices.size();
        if (pt.peer_ok) {
          const MetricValues m = EvaluateMetrics(p.vertices, {}, patch);
          pt.peer_area = m[Metric::kArea];
          pt.peer_sqd = m[Metric::kSquaredDihedral];
        }
      }
      points.push_back(pt);
    }
  }

  std::ofstream csv(config.Path("fig4-curves.csv"));
  csv << "curve,n,status,delaunay_triangles,delaunay_cgal_ms,"
         "delaunay_tetgen_ms,dot1_ms,dot1_after_delaunay_ms,dot1_runs,"
         "dot1_heap_bytes,dot1_table_bytes,dot2_ms,dot2_runs,dot2_heap_bytes,"
         "dot2_table_bytes,cached_resolve_ms,cgal_ms,cgal_runs,cgal_heap_bytes,"
         "cgal_ok,dot1_area,cgal_area,dot2_sq_dihedral,cgal_sq_dihedral\n";
  for (const Point& p : points) {
    csv << p.curve << "," << p.n << "," << p.status << ","
        << p.delaunay_triangles << "," << p.delaunay_cgal_ms << ","
        << p.delaunay_tetgen_ms << "," << p.dot1.ms << ","
        << p.after_delaunay_ms << "," << p.dot1.runs << "," << p.dot1.heap
        << "," << p.table_bytes_dot1 << "," << p.dot2.ms << "," << p.dot2.runs
        << "," << p.dot2.heap << "," << p.table_bytes_dot2 << "," << p.cached.ms
        << "," << p.peer.ms << "," << p.peer.runs << "," << p.peer.heap << ","
        << p.peer_ok << "," << p.our_area << "," << p.peer_area << ","
        << p.our_sqd << "," << p.peer_sqd << "\n";
  }

  // One series per curve for each plotted quantity.
  auto per_curve = [&](auto value) {
    std::vector<Series> out;
    for (Curve c : kPaperCurves) {
      Series s{std::string(CurveName(c)), {}, {}};
      for (const Point& p : points) {
        if (p.curve != CurveName(c)) continue;
        s.x.push_back(p.n);
        s.y.push_back(value(p));
      }
      out.push_back(s);
    }
    return out;
  };
  auto ok = [](const Point& p, double v) { return p.status == "ok" ? v : NAN; };
  report << "## Figure 4: curves\n\nMedians of up to " << config.reps
         << " runs per point; log-log slopes in the legends. Data: "
            "`fig4-curves.csv`.\n\n";
  const std::vector<std::pair<std::string, Plot>> plots = {
      {"fig4-triangles.png",
       {"", "Delaunay triangles", "n", "triangles", false, true,
        per_curve([](const Point& p) {
          return static_cast<double>(p.delaunay_triangles);
        })}},
      {"fig4-delaunay-time.png",
       {"", "Delaunay step (CGAL backend)", "n", "ms", false, true,
        per_curve([&](const Point& p) { return ok(p, p.delaunay_cgal_ms); })}},
      {"fig4-dot1-time.png",
       {"", "DOT1 (area), end to end", "n", "ms", false, true,
        per_curve([&](const Point& p) { return ok(p, p.dot1.ms); })}},
      {"fig4-dot2-time.png",
       {"", "DOT2 (squared dihedral), end to end", "n", "ms", false, true,
        per_curve([&](const Point& p) { return ok(p, p.dot2.ms); })}},
      {"fig4-memory.png",
       {"", "Peak heap of DOT2", "n", "bytes", false, true,
        per_curve([&](const Point& p) { return ok(p, p.dot2.heap); })}},
  };
  for (auto [file, plot] : plots) {
    plot.path = config.Path(file);
    RenderPlot(plot);
    report << "![" << plot.title << "](" << file << ")\n";
  }

  report << "\n| curve | n | Delaunay triangles | Delaunay CGAL / TetGen ms "
            "| DOT1 ms | after Delaunay | DOT2 ms | cached re-solve ms | "
            "CGAL hole filling ms | DOT1 / CGAL | DOT2 / CGAL | cached / "
            "CGAL | heap DOT1 / CGAL | heap DOT2 / CGAL | sq. dihedral DOT2 / "
            "CGAL "
            "|\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
            "---:|---:|---:|\n";
  for (const Point& p : points) {
    auto ratio = [](double a, double b) {
      return std::isnan(a) || std::isnan(b) || b == 0 ? std::string("-")
                                                      : Fixed(a / b, 2);
    };
    const double after_share = p.after_delaunay_ms / p.delaunay_cgal_ms;
    report << "| " << p.curve << " | " << p.n << " | " << p.delaunay_triangles
           << " | " << Fixed(p.delaunay_cgal_ms) << " / "
           << Fixed(p.delaunay_tetgen_ms) << " | "
           << (p.status == "ok" ? Fixed(p.dot1.ms) : p.status) << " | "
           << (std::isnan(after_share) ? "-"
                                       : Fixed(100 * after_share, 0) + "%")
           << " | " << (p.status2 == "ok" ? Fixed(p.dot2.ms) : p.status2)
           << " | " << Fixed(p.cached.ms, 2) << " | "
           << (p.peer_ok ? Fixed(p.peer.ms) : "-") << " | "
           << ratio(ok(p, p.dot1.ms), p.peer_ok ? p.peer.ms : NAN) << " | "
           << ratio(ok(p, p.dot2.ms), p.peer_ok ? p.peer.ms : NAN) << " | "
           << ratio(ok(p, p.cached.ms), p.peer_ok ? p.peer.ms : NAN) << " | "
           << ratio(ok(p, p.dot1.heap), p.peer_ok ? p.peer.heap : NAN) << " | "
           << ratio(ok(p, p.dot2.heap), p.peer_ok ? p.peer.heap : NAN) << " | "
           << ratio(p.our_sqd, p.peer_sqd) << " |\n";
  }
  report << "\n\"after Delaunay\" is DOT1's adjacency + dynamic program + "
            "tiling as a share of its Delaunay step. A \"-\" for CGAL means "
            "it was not run at that size (over the time cap, or n > 10,000) "
            "or found no triangulation.\n\n";
  report << "Every DOT1 and DOT2 mesh above (" << checked
         << ") was validated (disk, boundary = polygon, no self-intersections "
            "by exact predicates): "
         << (invalid == 0 ? "all valid" : std::to_string(invalid) + " INVALID")
         << ".\n\n";
  return invalid;
}

}  // namespace dot::bench

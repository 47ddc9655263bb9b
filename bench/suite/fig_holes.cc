// SPDX-License-Identifier: AGPL-3.0-or-later
// Figure 5 (paper): hole boundaries grown on real meshes (libcgal-demo), 100
// to 10,000 triangles removed. Per hole: Delaunay triangles, times of the
// Delaunay step, DOT1 (area) and DOT2 (squared dihedral), peak heap, whether
// the boundary is Delaunay-triangulable (without and with edge protection),
// and the peer, CGAL's triangulate_hole_polyline, on the same boundary.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>

#include "cgal_peer.h"
#include "measure.h"
#include "plot.h"
#include "suite.h"

namespace dot::bench {
namespace {

struct HolePoint {
  std::string mesh;
  int removed = 0, n = 0;
  int64_t delaunay_triangles = 0;
  bool triangulable = false, protected_ok = false;
  int inserted = 0;  // by edge protection, when it was needed
  double delaunay_ms = NAN;
  Sample dot1, dot2, peer;
  bool peer_ok = false;
  double our_sqd = NAN, peer_sqd = NAN;
};

}  // namespace

int RunHoles(const Config& config, std::ostream& report) {
  int invalid = 0, checked = 0;
  const int count = config.quick ? 12 : config.holes;
  const std::vector<HoleCase> holes = MakeHoles(config, count, 100, 10000);
  const MetricWeights area = OneMetric(Metric::kArea);
  const MetricWeights sqd = OneMetric(Metric::kSquaredDihedral);
  std::vector<HolePoint> points;
  for (const HoleCase& h : holes) {
    HolePoint pt;
    pt.mesh = h.mesh;
    pt.removed = h.triangles;
    pt.n = static_cast<int>(h.boundary.vertices.size());
    if (points.size() % 20 == 0) {
      std::cerr << "holes: " << points.size() << "/" << holes.size() << "\n";
    }
    const Problem p{h.boundary.vertices, h.boundary.normals, area, {}, {}};
    Options plain;
    plain.space = SearchSpace::kDelaunay;
    Result r1, r2;
    pt.dot1 = Measure(config.reps, config.long_run_s, config.cap_s,
                      [&] { r1 = SolveWith(p, area, plain); });
    pt.delaunay_triangles = r1.stats.delaunay_triangles;
    pt.delaunay_ms = r1.stats.delaunay_ms;
    pt.triangulable = r1.status.ok();
    invalid += InvalidOutput(r1, h.mesh + " hole DOT1");
    checked += r1.status.ok();
    Options protect = plain;
    protect.protect_edges = true;
    if (pt.triangulable) {
      pt.protected_ok = true;
    } else {
      const Result rp = SolveWith(p, area, protect);
      pt.protected_ok = rp.status.ok();
      invalid += InvalidOutput(rp, h.mesh + " hole DOT1, edges protected");
      checked += rp.status.ok();
      pt.inserted = static_cast<int>(rp.inserted.size());
    }
    pt.dot2 = Measure(config.reps, config.long_run_s, config.cap_s,
                      [&] { r2 = SolveWith(p, sqd, plain); });
    invalid += InvalidOutput(r2, h.mesh + " hole DOT2");
    checked += r2.status.ok();
    if (r2.status.ok()) {
      pt.our_sqd = r2.metric_costs[Metric::kSquaredDihedral];
    }
    std::vector<Triangle> patch;
    pt.peer = Measure(config.reps, config.long_run_s, config.cap_s,
                      [&] { patch = CgalFillHole(p.vertices); });
    pt.peer_ok = patch.size() + 2 == p.vertices.size();
    if (pt.peer_ok) {
      pt.peer_sqd =
          EvaluateMetrics(p.vertices, {}, patch)[Metric::kSquaredDihedral];
    }
    points.push_back(pt);
  }

  std::ofstream csv(config.Path("fig5-holes.csv"));
  csv << "mesh,triangles_removed,n,delaunay_triangles,triangulable,"
         "triangulable_with_protection,inserted,delaunay_ms,dot1_ms,"
         "dot1_heap_bytes,dot2_ms,dot2_heap_bytes,cgal_ms,cgal_heap_bytes,"
         "cgal_ok,dot2_sq_dihedral,cgal_sq_dihedral\n";
  for (const HolePoint& p : points) {
    csv << p.mesh << "," << p.removed << "," << p.n << ","
        << p.delaunay_triangles << "," << p.triangulable << ","
        << p.protected_ok << "," << p.inserted << "," << p.delaunay_ms << ","
        << p.dot1.ms << "," << p.dot1.heap << "," << p.dot2.ms << ","
        << p.dot2.heap << "," << p.peer.ms << "," << p.peer.heap << ","
        << p.peer_ok << "," << p.our_sqd << "," << p.peer_sqd << "\n";
  }

  auto scatter = [&](const std::string& title, auto value) {
    Series s{title, {}, {}};
    for (const HolePoint& p : points) {
      s.x.push_back(p.n);
      s.y.push_back(value(p));
    }
    return s;
  };
  auto when_ok = [](bool ok, double v) { return ok ? v : NAN; };
  const std::vector<std::pair<std::string, Plot>> plots = {
      {"fig5-triangles.png",
       {"",
        "Delaunay triangles of hole boundaries",
        "boundary vertices n",
        "triangles",
        true,
        true,
        {scatter("Delaunay triangles",
                 [](const HolePoint& p) {
                   return static_cast<double>(p.delaunay_triangles);
                 })}}},
      {"fig5-time.png",
       {"",
        "Hole filling time",
        "boundary vertices n",
        "ms",
        true,
        true,
        {scatter("Delaunay step",
                 [](const HolePoint& p) { return p.delaunay_ms; }),
         scatter("DOT1 (area)",
                 [&](const HolePoint& p) {
                   return when_ok(p.triangulable, p.dot1.ms);
                 }),
         scatter("DOT2 (squared dihedral)",
                 [&](const HolePoint& p) {
                   return when_ok(p.triangulable, p.dot2.ms);
                 }),
         scatter("CGAL triangulate_hole_polyline",
                 [&](const HolePoint& p) {
                   return when_ok(p.peer_ok, p.peer.ms);
                 })}}},
      {"fig5-memory.png",
       {"",
        "Peak heap",
        "boundary vertices n",
        "bytes",
        true,
        true,
        {scatter("DOT2",
                 [&](const HolePoint& p) {
                   return when_ok(p.triangulable, p.dot2.heap);
                 }),
         scatter("CGAL",
                 [&](const HolePoint& p) {
                   return when_ok(p.peer_ok, p.peer.heap);
                 })}}},
  };
  report << "## Figure 5: holes in real meshes\n\n";
  for (auto [file, plot] : plots) {
    plot.path = config.Path(file);
    RenderPlot(plot);
    report << "![" << plot.title << "](" << file << ")\n";
  }
  int triangulable = 0, with_protection = 0, peer_ok = 0, both = 0,
      lower_sqd = 0, equal_sqd = 0;
  std::vector<double> ratio1, ratio2, ratio1_large, heap1, heap2, after;
  int lo_n = 1 << 30, hi_n = 0;
  for (const HolePoint& p : points) {
    lo_n = std::min(lo_n, p.n);
    hi_n = std::max(hi_n, p.n);
    triangulable += p.triangulable;
    with_protection += p.protected_ok;
    peer_ok += p.peer_ok;
    if (p.triangulable && p.peer_ok) {
      ++both;
      ratio1.push_back(p.dot1.ms / p.peer.ms);
      ratio2.push_back(p.dot2.ms / p.peer.ms);
      if (p.n >= 1000) ratio1_large.push_back(p.dot1.ms / p.peer.ms);
      heap1.push_back(p.dot1.heap / p.peer.heap);
      heap2.push_back(p.dot2.heap / p.peer.heap);
      after.push_back((p.dot1.ms - p.delaunay_ms) / p.delaunay_ms);
      const double rel = (p.our_sqd - p.peer_sqd) / std::max(p.peer_sqd, 1e-12);
      if (rel < -1e-9) ++lower_sqd;
      if (std::abs(rel) <= 1e-9) ++equal_sqd;
    }
  }
  report << "\n"
         << points.size() << " hole boundaries (n = " << lo_n << ".." << hi_n
         << " vertices) on ";
  std::vector<std::string> names;
  for (const HolePoint& p : points) {
    if (std::find(names.begin(), names.end(), p.mesh) == names.end()) {
      names.push_back(p.mesh);
    }
  }
  for (size_t i = 0; i < names.size(); ++i) {
    report << (i ? ", " : "") << "`" << names[i] << ".off`";
  }
  report << ". Data: `fig5-holes.csv`.\n\n"
         << "- Delaunay-triangulable as given: **" << triangulable << " of "
         << points.size() << "** (the paper: 1968 of 2000); with edge "
         << "protection: " << with_protection << " of " << points.size()
         << ".\n- CGAL found a triangulation for " << peer_ok << " of "
         << points.size() << ".\n- On the " << both
         << " boundaries both solved: median time ratio DOT1/CGAL "
         << Fixed(Median(ratio1), 2) << ", DOT2/CGAL "
         << Fixed(Median(ratio2), 2) << "; DOT2's sum of squared dihedral "
         << "angles is lower than CGAL's on " << lower_sqd << " and equal on "
         << equal_sqd << " ("
         << Fixed(100.0 * (lower_sqd + equal_sqd) / std::max(both, 1), 1)
         << "% not worse).\n- Boundaries with n >= 1000: median DOT1/CGAL "
         << Fixed(Median(ratio1_large), 2) << " over " << ratio1_large.size()
         << ".\n- Median peak heap DOT1/CGAL " << Fixed(Median(heap1), 2)
         << ", DOT2/CGAL " << Fixed(Median(heap2), 2)
         << ".\n- DOT1 after the Delaunay step (adjacency, weights, dynamic "
            "program, tiling, result) as a share of the Delaunay step: median "
         << Fixed(100 * Median(after), 0) << "%.\n\n";
  report << "Every DOT1 and DOT2 patch (" << checked << ") was validated: "
         << (invalid == 0 ? "all valid" : std::to_string(invalid) + " INVALID")
         << ".\n\n";
  return invalid;
}

}  // namespace dot::bench

// SPDX-License-Identifier: AGPL-3.0-or-later
// Our side of the comparison: FillSoup, the use case the server and
// dotctl run, timed and summarized per hole.
#include <utility>

#include "fill_bench/fill_bench.h"
#include "heap_meter.h"

namespace dot::bench::fill {
namespace {}  // namespace

Run RunOurs(const Config& config, const Case& c, const Holes& holes,
            FillStage stage, int threads, FillResult* last,
            bool allow_input_intersections) {
  Run run;
  FillOptions options;
  options.stage = stage;
  options.threads = threads;
  options.allow_input_intersections = allow_input_intersections;
  // The use case the server and dotctl run. The case's mesh was repaired
  // once when it was loaded, and CGAL gets it that way too, so the timed
  // run skips the repair (it only takes the triangles over).
  options.repair = false;
  const PolygonSoup soup = ToSoup(c.mesh);
  std::vector<std::vector<double>> hole_ms(holes.count);
  run.time = Repeat(config, [&](double* ms, double* heap) {
    *last = FillResult();
    PolygonSoup input = soup;  // FillSoup takes its own copy
    ResetHeapPeak();
    const auto t0 = Clock::now();
    FillResult r = FillSoup(std::move(input), options).fill;
    *ms = MsSince(t0);
    *heap = static_cast<double>(HeapPeakBytes());
    std::vector<double> per(holes.count, 0);
    for (const HoleReport& h : r.report.holes) {
      if (h.id >= 0 && h.id < static_cast<int>(holes.loop_hole.size())) {
        per[holes.loop_hole[h.id]] +=
            h.triangulate_ms + h.refine_ms + h.fair_ms + h.check_ms;
      }
    }
    for (int k = 0; k < holes.count; ++k) hole_ms[k].push_back(per[k]);
    *last = std::move(r);
    return true;
  });
  for (int k = 0; k < holes.count; ++k) {
    run.hole_ms.push_back(Median(hole_ms[k]));
  }
  if (!last->status.ok()) {
    run.status = "error: " + last->status.message;
    return run;
  }
  const FillReport& rep = last->report;
  run.loops = rep.loops;
  run.loops_filled = rep.filled;
  std::vector<int> open(holes.count, 0);
  for (const HoleReport& h : rep.holes) {
    if (h.status != HoleStatus::kFilled) {
      ++open[holes.loop_hole[h.id]];
      run.open_reasons.push_back("loop " + std::to_string(h.id) + " (" +
                                 std::to_string(h.boundary_vertices) +
                                 " vertices" + (h.pinched ? ", pinched" : "") +
                                 "): " + std::string(HoleStatusName(h.status)) +
                                 ": " + h.reason);
    }
    run.escalated += h.escalation == Escalation::kProtectedEdges ||
                     h.escalation == Escalation::kAllTriangles ||
                     h.escalation == Escalation::kDelaunayFirst;
    run.delaunay_first += h.status == HoleStatus::kFilled &&
                          h.escalation == Escalation::kDelaunayFirst;
    if (h.status == HoleStatus::kFilled && h.intersecting_pairs > 0) {
      ++run.crossing_holes;
      run.crossing_pairs += h.intersecting_pairs;
    }
    // Holes refinement left without new vertices have nothing to fair.
    run.fair_failed += h.status == HoleStatus::kFilled &&
                       (h.reason.find("fairing failed") != std::string::npos ||
                        h.reason.find("fairing undone") != std::string::npos);
    run.not_refined += h.status == HoleStatus::kFilled &&
                       h.reason.rfind("not refined", 0) == 0;
    run.reverted += h.reason.find("kept the unrefined") != std::string::npos;
  }
  for (int k = 0; k < holes.count; ++k) {
    run.hole_filled.push_back(open[k] == 0);
    run.holes_filled += open[k] == 0;
  }
  return run;
}

}  // namespace dot::bench::fill

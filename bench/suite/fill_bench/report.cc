// SPDX-License-Identifier: AGPL-3.0-or-later
// The figures: one CSV row per mesh and stage, and the report's tables
// and summaries.
#include <CGAL/version.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>

#include "fill_bench/fill_bench.h"

namespace dot::bench::fill {
namespace {

bool SelfIntersecting(const Run& r) {
  return r.judged && (r.verdict.pairs > 0 || r.verdict.degenerate > 0);
}

// Per-stage summary against the targets.
struct StageSummary {
  int meshes = 0, cgal_done = 0, cgal_timeout = 0, cgal_error = 0;
  int holes = 0, dot_filled = 0, cgal_filled = 0, cgal_only = 0, dot_only = 0;
  int holes_cgal_done = 0;
  int dot_si = 0, cgal_si = 0, dot_si_cut = 0, cgal_si_cut = 0, dot_si_open = 0,
      cgal_si_open = 0, dot_open_meshes = 0, cgal_pinched_si = 0,
      pinched_meshes = 0;
  int dot_nm = 0, cgal_nm = 0;  // outputs with non-manifold/misoriented edges
  std::vector<double> time_ratio, time_ratio_mt, time_ratio_build, heap_ratio,
      dot_hole_share;
  double dot_ms_sum = 0, cgal_ms_sum = 0;
  std::vector<double> d_dot, d_cgal, d_ratio;
  int dist_meshes = 0, dist_not_worse = 0;
  std::vector<double> cubic_speedup;  // where both filled
  int cubic_holes = 0, cubic_cgal_filled = 0, cubic_dot_open = 0;
  int delaunay_first = 0;  // holes dot filled by that step
  // allow_input_intersections where dot left holes open: holes it then
  // fills, those of them whose patch meets the mesh, their pairs, and the
  // outputs with non-manifold or misoriented edges (should be none).
  int dot_open = 0, dot_open_crossing_input = 0, allow_filled = 0,
      allow_crossing = 0, allow_nm = 0;
  int64_t allow_pairs = 0;
  std::vector<double> cubic_dot_ms, cubic_cgal_ms;  // holes both filled
};

StageSummary Summarize(const std::vector<Row>& rows, FillStage stage) {
  StageSummary s;
  for (const Row& row : rows) {
    if (row.stage != stage) continue;
    ++s.meshes;
    s.holes += row.holes;
    s.dot_filled += row.dot.holes_filled;
    s.delaunay_first += row.dot.delaunay_first;
    const int open_holes = row.holes - row.dot.holes_filled;
    s.dot_open += open_holes;
    if (row.truth_pairs > 0 || row.input_pairs > 0) {
      s.dot_open_crossing_input += open_holes;
    }
    if (row.dot_allow.status == "ok") {
      s.allow_filled += row.dot_allow.holes_filled - row.dot.holes_filled;
      s.allow_crossing += row.dot_allow.crossing_holes;
      s.allow_pairs += row.dot_allow.crossing_pairs;
      s.allow_nm +=
          row.dot_allow.judged && (row.dot_allow.verdict.non_manifold > 0 ||
                                   row.dot_allow.verdict.misoriented > 0);
    }
    const bool cgal_ok = row.cgal.status == "ok";
    s.cgal_done += cgal_ok;
    s.cgal_timeout += row.cgal.status.rfind("timeout", 0) == 0;
    s.cgal_error += row.cgal.status.rfind("error", 0) == 0;
    if (cgal_ok) {
      s.holes_cgal_done += row.holes;
      s.cgal_filled += row.cgal.holes_filled;
      for (int k = 0; k < row.holes; ++k) {
        const bool d = row.dot.hole_filled.size() > static_cast<size_t>(k) &&
                       row.dot.hole_filled[k];
        const bool g = row.cgal.hole_filled[k];
        s.cgal_only += g && !d;
        s.dot_only += d && !g;
      }
      s.time_ratio.push_back(row.dot.time.ms / row.cgal.time.ms);
      s.time_ratio_mt.push_back(row.dot_mt.time.ms / row.cgal.time.ms);
      s.time_ratio_build.push_back(row.dot.time.ms /
                                   (row.cgal.time.ms + row.cgal.build_ms));
      s.heap_ratio.push_back(row.dot.time.heap /
                             std::max(row.cgal.time.heap, 1.0));
      s.dot_ms_sum += row.dot.time.ms;
      s.dot_hole_share.push_back(
          std::accumulate(row.dot.hole_ms.begin(), row.dot.hole_ms.end(), 0.0) /
          row.dot.time.ms);
      s.cgal_ms_sum += row.cgal.time.ms;
    }
    const bool open = row.c->kind == "open";
    s.dot_open_meshes += open;
    s.pinched_meshes += row.pinched > 0;
    if (SelfIntersecting(row.dot)) {
      ++s.dot_si;
      (open ? s.dot_si_open : s.dot_si_cut)++;
    }
    auto non_manifold = [](const Run& r) {
      return r.judged &&
             (r.verdict.non_manifold > 0 || r.verdict.misoriented > 0);
    };
    s.dot_nm += non_manifold(row.dot);
    s.cgal_nm += non_manifold(row.cgal);
    if (SelfIntersecting(row.cgal)) {
      ++s.cgal_si;
      (open ? s.cgal_si_open : s.cgal_si_cut)++;
      s.cgal_pinched_si += row.pinched > 0;
    }
    const bool dot_all = row.dot.holes_filled == row.holes;
    if (!open && cgal_ok && dot_all && row.cgal.holes_filled == row.holes &&
        row.dot.judged && row.cgal.judged) {
      ++s.dist_meshes;
      s.d_dot.push_back(row.dot.verdict.d_mean);
      s.d_cgal.push_back(row.cgal.verdict.d_mean);
      s.d_ratio.push_back(row.dot.verdict.d_mean / row.cgal.verdict.d_mean);
      s.dist_not_worse +=
          row.dot.verdict.d_mean <= row.cgal.verdict.d_mean * (1 + 1e-9);
    }
    if (cgal_ok) {
      for (int k = 0; k < row.holes; ++k) {
        if (!row.cgal.hole_cubic[k]) continue;
        ++s.cubic_holes;
        if (!row.cgal.hole_filled[k]) continue;
        ++s.cubic_cgal_filled;
        if (!row.dot.hole_filled[k]) {
          ++s.cubic_dot_open;
          continue;
        }
        if (row.dot.hole_ms[k] > 0) {
          s.cubic_speedup.push_back(row.cgal.hole_ms[k] / row.dot.hole_ms[k]);
          s.cubic_dot_ms.push_back(row.dot.hole_ms[k]);
          s.cubic_cgal_ms.push_back(row.cgal.hole_ms[k]);
        }
      }
    }
  }
  return s;
}

double Max(const std::vector<double>& v) {
  return v.empty() ? NAN : *std::max_element(v.begin(), v.end());
}
double Min(const std::vector<double>& v) {
  return v.empty() ? NAN : *std::min_element(v.begin(), v.end());
}
int CountAtMost(const std::vector<double>& v, double limit) {
  return static_cast<int>(
      std::count_if(v.begin(), v.end(), [&](double x) { return x <= limit; }));
}

}  // namespace

std::string Yes(bool b) { return b ? "yes" : "no"; }

std::string Cell(const Run& r) {
  if (r.status != "ok") return r.status;
  std::ostringstream o;
  o << Fixed(r.time.ms, r.time.ms < 100 ? 1 : 0) << " ms, " << r.holes_filled;
  if (r.judged) {
    o << ", "
      << (SelfIntersecting(r) ? std::to_string(r.verdict.pairs) + " SI"
                              : "0 SI");
    if (!std::isnan(r.verdict.d_mean))
      o << ", d " << Fixed(r.verdict.d_mean, 3);
  }
  return o.str();
}

void WriteCsv(const Config& config, const std::vector<Row>& rows) {
  std::ofstream csv(config.Path("fill.csv"));
  csv << "mesh,kind,base,vertices,faces,loops,holes,pinched_loops,"
         "max_loop_vertices,stage,"
         "method,threads,status,runs,ms,heap_bytes,cycles_or_loops,"
         "cycles_or_loops_filled,holes_filled,new_faces,"
         "degenerate_new_faces,intersecting_pairs,closed,non_manifold_edges,"
         "misoriented_edges,dist_patch,dist_truth,dist_mean,dist_max,"
         "cubic_holes,ms_on_cubic_holes,escalated_holes,fair_failed,"
         "refine_reverted,not_refined,build_ms,input_intersecting_pairs,"
         "truth_intersecting_pairs,per_hole_ms_sum\n";
  for (const Row& row : rows) {
    const std::pair<const char*, const Run*> runs[] = {
        {"dot", &row.dot},
        {"dot_mt", &row.dot_mt},
        {"cgal", &row.cgal},
        {"dot_allow", &row.dot_allow}};
    for (const auto& [method, r] : runs) {
      if (r->status == "skipped") continue;
      const bool cgal = std::string(method) == "cgal";
      const Verdict& v = r->verdict;
      csv << row.c->name << "," << row.c->kind << "," << row.c->base << ","
          << row.vertices << "," << row.faces << "," << row.loops << ","
          << row.holes << "," << row.pinched << "," << row.max_loop << ","
          << FillStageName(row.stage) << "," << method << ","
          << (std::string(method) == "dot_mt" ? "0" : "1") << "," << r->status
          << "," << r->time.runs << "," << r->time.ms << "," << r->time.heap
          << "," << r->loops << "," << r->loops_filled << "," << r->holes_filled
          << ",";
      if (r->judged) {
        csv << v.new_faces << "," << v.degenerate << "," << v.pairs << ","
            << v.closed << "," << v.non_manifold << "," << v.misoriented << ","
            << v.d_patch << "," << v.d_truth << "," << v.d_mean << ","
            << v.d_max << ",";
      } else {
        csv << ",,,,,,,,,,";
      }
      csv << row.cubic_holes << ","
          << (cgal                           ? row.cgal_cubic_ms
              : std::string(method) == "dot" ? row.dot_cubic_ms
                                             : NAN)
          << "," << (cgal ? 0 : r->escalated) << "," << r->fair_failed << ","
          << r->reverted << "," << r->not_refined << "," << r->build_ms << ","
          << row.input_pairs << "," << row.truth_pairs << ","
          << std::accumulate(r->hole_ms.begin(), r->hole_ms.end(), 0.0) << "\n";
    }
  }
}

void WriteReport(const Config& config, const std::vector<Row>& rows,
                 std::ostream& report) {
  int cut = 0, open = 0, pinched = 0, dendritic = 0;
  for (const Row& row : rows) {
    if (row.stage != FillStage::kTriangulate) continue;
    (row.c->kind == "open" ? open : cut)++;
    pinched += row.c->kind == "pinched";
    dendritic += row.c->kind == "dendritic";
  }
  report << "## Hole filling against CGAL\n\n"
         << open << " real open meshes and " << cut
         << " meshes with holes cut into closed ones (" << pinched
         << " with pinched pairs of holes touching at a vertex, " << dendritic
         << " with one large dendritic hole). Per mesh and stage, in one "
            "run: dot's `FillHoles` (default options, threads = 1; "
            "threads = 0 in its own column) and CGAL "
         << CGAL_VERSION_STR
         << "'s `triangulate_hole` / `triangulate_and_refine_hole` / "
            "`triangulate_refine_and_fair_hole` on every border cycle of a "
            "`Surface_mesh` of the same repaired mesh, default parameters "
            "(CGAL 5.5 defaults to `use_delaunay_triangulation(true)` and "
            "falls back to its cubic search over all triangles when the 3D "
            "Delaunay space has no triangulation; density sqrt(2) and "
            "fairing continuity 1, like ours). CGAL runs in a child process "
            "stopped at "
         << Fixed(kCgalCapS, 0)
         << " s (\"timeout\"; a mesh that timed out is not run at later "
            "stages). Times are medians of up to "
         << config.reps
         << " runs of the whole mesh: dot's `FillHoles` call, and CGAL's "
            "filling of every border cycle of a ready `Surface_mesh` (the "
            "time to build that `Surface_mesh` from the indexed mesh is "
            "measured apart and shown in one column); peak heap by the "
            "suite's meter (CGAL's includes its `Surface_mesh`). Closed and "
            "edge-manifold are judged after mapping CGAL's duplicated "
            "vertices back, i.e. on the geometry. "
            "A hole is a border component: loops that share a vertex count "
            "as one (CGAL sees a pinched border as one cycle). Self-"
            "intersections: `dot::CountIntersectingPairs` (exact predicates) "
            "over the whole output with the new faces first, so pairs with "
            "at least one new face count (CGAL's duplicated pinch vertices "
            "are mapped back to the input vertex first); degenerate new "
            "faces count as self-intersecting. Distance (cut meshes): mean "
            "distance of area-weighted samples of the new faces to the "
            "closed mesh, and of the removed patches to the output, "
            "averaged, in mean edge lengths. Data: `fill.csv`.\n\n";
  report << "| stage | holes filled: dot / CGAL (of) | CGAL filled, dot not "
            "| self-intersecting outputs: dot / CGAL | distance, median: dot "
            "/ CGAL (dot not worse on) | time dot/CGAL per mesh: median "
            "(max) | sum of times dot/CGAL | CGAL incl. Surface_mesh build: "
            "median | threads=0: median | heap dot/CGAL median | "
            "cubic-fallback holes: speed-up median (min) "
            "|\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::vector<StageSummary> sums;
  for (FillStage stage : kStages) {
    const StageSummary s = Summarize(rows, stage);
    sums.push_back(s);
    report << "| " << FillStageName(stage) << " | " << s.dot_filled << " / "
           << s.cgal_filled << " (" << s.holes << "; CGAL ran on "
           << s.holes_cgal_done << ")"
           << " | " << s.cgal_only << " | " << s.dot_si << " / " << s.cgal_si
           << " of " << s.meshes << " | " << Fixed(Median(s.d_dot), 3) << " / "
           << Fixed(Median(s.d_cgal), 3) << " (" << s.dist_not_worse << " of "
           << s.dist_meshes << ") | " << Fixed(Median(s.time_ratio), 2) << " ("
           << Fixed(Max(s.time_ratio), 2) << ") | "
           << Fixed(s.dot_ms_sum / s.cgal_ms_sum, 3) << " | "
           << Fixed(Median(s.time_ratio_build), 2) << " | "
           << Fixed(Median(s.time_ratio_mt), 2) << " | "
           << Fixed(Median(s.heap_ratio), 2) << " | " << s.cubic_holes
           << " (CGAL filled " << s.cubic_cgal_filled << ", dot "
           << s.cubic_cgal_filled - s.cubic_dot_open
           << "): " << Fixed(Median(s.cubic_speedup), 0) << "x ("
           << Fixed(Min(s.cubic_speedup), 0) << "x) |\n";
  }
  report << "\nTargets (issue 11):\n\n";
  const double target[] = {0.5, 1.0, 1.0};
  for (size_t i = 0; i < sums.size(); ++i) {
    const StageSummary& s = sums[i];
    const std::string stage(FillStageName(kStages[i]));
    report << "- **" << stage << "**: holes: dot fills " << s.dot_filled
           << " of " << s.holes << ", CGAL " << s.cgal_filled << " of "
           << s.holes_cgal_done << " it ran on (" << s.cgal_timeout
           << " meshes timed out, " << s.cgal_error
           << " failed); every hole CGAL filled is filled by dot: "
           << (s.cgal_only == 0
                   ? "**met**"
                   : "**missed** on " + std::to_string(s.cgal_only) + " holes")
           << " (dot fills " << s.dot_only
           << " that CGAL does not). Self-intersecting outputs: dot "
           << s.dot_si << " (" << s.dot_si_cut << " cut, " << s.dot_si_open
           << " open), CGAL " << s.cgal_si << " (" << s.cgal_si_cut << " cut, "
           << s.cgal_si_open << " open; " << s.cgal_pinched_si << " of "
           << s.pinched_meshes << " with pinched loops): "
           << (s.dot_si == 0 ? "**met**" : "**missed**")
           << " (outputs with non-manifold or misoriented edges: dot "
           << s.dot_nm << ", CGAL " << s.cgal_nm
           << "). Distance not worse than CGAL's on " << s.dist_not_worse
           << " of " << s.dist_meshes
           << " cut meshes both filled completely (median ratio "
           << Fixed(Median(s.d_ratio), 3) << ", worst "
           << Fixed(Max(s.d_ratio), 3) << "): "
           << (s.dist_not_worse == s.dist_meshes ? "**met**" : "**missed**")
           << ". Time ratio <= " << Fixed(target[i], 1) << " on "
           << CountAtMost(s.time_ratio, target[i]) << " of "
           << s.time_ratio.size() << " meshes (median "
           << Fixed(Median(s.time_ratio), 2) << ", worst "
           << Fixed(Max(s.time_ratio), 2) << "): "
           << (CountAtMost(s.time_ratio, target[i]) ==
                       static_cast<int>(s.time_ratio.size())
                   ? "**met**"
                   : "**missed**")
           << " (against CGAL's time including building its Surface_mesh: "
           << CountAtMost(s.time_ratio_build, target[i]) << " of "
           << s.time_ratio_build.size() << "; the holes' own work is a median "
           << Fixed(100 * Median(s.dot_hole_share), 0)
           << "% of dot's time, the rest passes over the whole mesh)"
           << ". CGAL fell back to its cubic search on " << s.cubic_holes
           << " holes and filled " << s.cubic_cgal_filled << " of them; dot "
           << "left " << s.cubic_dot_open
           << " of those open; on the ones both filled, dot >= 10x faster on ";
    int fast = 0;
    for (double x : s.cubic_speedup) fast += x >= 10;
    report << fast << " of " << s.cubic_speedup.size() << " ("
           << (s.cubic_speedup.empty() ? "none measured"
               : fast == static_cast<int>(s.cubic_speedup.size())
                   ? "**met**"
                   : "**missed**")
           << "); dot slower than CGAL on "
           << CountAtMost(s.cubic_speedup, 1 - 1e-12)
           << " of them (issue 19: none), dot's time there median "
           << Fixed(Median(s.cubic_dot_ms), 0) << " ms, CGAL's "
           << Fixed(Median(s.cubic_cgal_ms), 0)
           << " ms. Holes filled by every triangle with the Delaunay ones "
              "first (the last step, for large holes with no Delaunay "
              "patch): "
           << s.delaunay_first << ". Holes dot left open: " << s.dot_open
           << ", " << s.dot_open_crossing_input
           << " of them in meshes whose input or removed surface crosses the "
              "mesh; with allow_input_intersections dot fills "
           << s.allow_filled << " more (" << s.allow_crossing
           << " of its holes report patches meeting the mesh, " << s.allow_pairs
           << " pairs in all; outputs with non-manifold or misoriented "
              "edges: "
           << s.allow_nm << ").\n";
  }
  report << "\nEscalations and fallbacks (holes, summed over meshes):\n\n";
  for (FillStage stage : kStages) {
    int escalated = 0, reverted = 0, not_refined = 0, dot_fair = 0,
        cgal_fair = 0;
    for (const Row& row : rows) {
      if (row.stage != stage) continue;
      escalated += row.dot.escalated;
      reverted += row.dot.reverted;
      not_refined += row.dot.not_refined;
      dot_fair += row.dot.fair_failed;
      cgal_fair += row.cgal.fair_failed;
    }
    report << "- " << FillStageName(stage) << ": dot patches from edge "
           << "protection, all triangles or Delaunay first " << escalated
           << "; refinement undone (it intersected) " << reverted
           << "; not refined (neighbourhood not manifold, e.g. pinched) "
           << not_refined << "; fairing failed or undone " << dot_fair
           << " (CGAL's `fair` failed: " << cgal_fair << ")\n";
  }
  report << "\nHoles dot left open (meshes in `fill-repro/`):\n\n";
  int listed = 0;
  std::map<std::pair<std::string, std::string>, std::string> open_at;
  std::vector<std::pair<std::string, std::string>> order;
  for (const Row& row : rows) {
    for (const std::string& why : row.dot.open_reasons) {
      auto key = std::make_pair(row.c->name, why);
      auto [it, added] = open_at.emplace(key, "");
      if (added) order.push_back(key);
      it->second += std::string(it->second.empty() ? "" : ", ") +
                    std::string(FillStageName(row.stage));
    }
  }
  for (const auto& key : order) {
    report << "- " << key.first << " (" << open_at[key] << "): " << key.second
           << "\n";
    ++listed;
  }
  for (const Row& row : rows) {
    if (!row.dot.note.empty()) {
      report << "- " << row.c->name << ", " << FillStageName(row.stage)
             << ": DEFECT: " << row.dot.note << "\n";
      ++listed;
    }
  }
  if (listed == 0) report << "- none\n";
  report
      << "\nPer mesh: time (ms), holes filled, self-intersecting pairs "
         "(SI), distance d (mean edge lengths).\n\n| mesh | holes | "
         "stage | dot | CGAL | CGAL cubic holes |\n|---|---|---|---|---|---|\n";
  for (const Row& row : rows) {
    report << "| " << row.c->name
           << (row.input_pairs > 0
                   ? " (input: " + std::to_string(row.input_pairs) +
                         " intersecting pairs)"
                   : "")
           << (row.truth_pairs > 0
                   ? " (ground truth: " + std::to_string(row.truth_pairs) +
                         " pairs with the mesh)"
                   : "")
           << " | " << row.holes << (row.pinched ? " (pinched)" : "") << " | "
           << FillStageName(row.stage) << " | " << Cell(row.dot) << " | "
           << Cell(row.cgal) << " | " << row.cubic_holes << " |\n";
  }
  report << "\n";
}

}  // namespace dot::bench::fill

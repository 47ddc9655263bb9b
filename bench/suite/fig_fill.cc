// SPDX-License-Identifier: AGPL-3.0-or-later
// Hole filling against CGAL 5.5 (issue 11's benchmark). Meshes: the real
// open meshes of libcgal-demo (ground truth unknown) and holes cut into
// closed ones (CutHoles; pinched pairs of holes that touch at one vertex;
// large dendritic holes whose boundaries are not Delaunay). For every mesh
// and stage (triangulate, refine, fair), in one process:
//  - dot: FillSoup (what the server and dotctl run; the mesh is repaired
//    once when loaded, so without its repair) with default options and the
//    stage, threads = 1 (and threads = 0, all cores, reported apart);
//  - CGAL: a Surface_mesh built from the same repaired mesh; every border
//    cycle (extract_boundary_cycles) filled with triangulate_hole,
//    triangulate_and_refine_hole or triangulate_refine_and_fair_hole,
//    default parameters (use_delaunay_triangulation(true), falling back to
//    the cubic search over all triangles; density sqrt(2), fairing
//    continuity 1, like ours). CGAL runs in a forked child so that a run
//    can be stopped at a time cap ("timeout"); the child times building
//    its Surface_mesh and filling it apart, and its peak heap covers both.
// Both outputs are then judged alike, outside the timings: holes filled,
// intersecting pairs among and against the new faces (exact predicates),
// closed and edge-manifold, and for cut meshes the distance to the
// ground#include <algorithm>
#include <filesystem>
#include <iostream>

#include "fill_bench/fill_bench.h"

namespace dot::bench {

using namespace fill;  // NOLINT: this file only strings fill/ together

int RunFill(const Config& config, std::ostream& report) {
  const std::vector<Case> cases = MakeCases(config);
  std::vector<Row> rows;
  int invalid = 0;
  const auto t_start = Clock::now();
  for (size_t ci = 0; ci < cases.size(); ++ci) {
    const Case& c = cases[ci];
    const Holes holes = FindHoles(c.mesh);
    const auto judge = MakeJudge(c);
    const bool soup = NeedsSoup(c.mesh);
    const bool have_sm = CgalCanBuild(c.mesh, soup);
    PointIds input_ids;
    for (size_t v = 0; v < c.mesh.vertices.size(); ++v) {
      input_ids.emplace(c.mesh.vertices[v], static_cast<int32_t>(v));
    }
    bool cgal_timed_out = false, repro_written = false;
    const int64_t input_pairs =
        CountIntersectingPairs(c.mesh.vertices, c.mesh.triangles);
    // Cut meshes: pairs the ground truth itself makes with the mesh (a
    // closed mesh that intersects itself where the hole was cut leaves no
    // intersection-free patch that follows it).
    int64_t truth_pairs = -1;
    if (!c.removed.triangles.empty()) {
      std::vector<Vec3> points = c.mesh.vertices;
      std::vector<int32_t> id(c.removed.vertices.size());
      for (size_t v = 0; v < id.size(); ++v) {
        auto it = input_ids.find(c.removed.vertices[v]);
        if (it != input_ids.end()) {
          id[v] = it->second;
        } else {
          id[v] = static_cast<int32_t>(points.size());
          points.push_back(c.removed.vertices[v]);
        }
      }
      std::vector<Triangle> faces;
      for (Triangle t : c.removed.triangles) {
        for (int32_t& v : t) v = id[v];
        faces.push_back(t);
      }
      const size_t checked = faces.size();
      faces.insert(faces.end(), c.mesh.triangles.begin(),
                   c.mesh.triangles.end());
      truth_pairs = CountIntersectingPairs(points, faces, checked);
    }
    for (FillStage stage : kStages) {
      Row row;
      row.c = &c;
      row.stage = stage;
      row.vertices = static_cast<int>(c.mesh.vertices.size());
      row.faces = static_cast<int>(c.mesh.triangles.size());
      row.loops = static_cast<int>(holes.loops.size());
      row.holes = holes.count;
      row.pinched = holes.pinched_loops;
      row.input_pairs = input_pairs;
      row.truth_pairs = truth_pairs;
      for (const HoleLoop& l : holes.loops) {
        row.max_loop =
            std::max(row.max_loop, static_cast<int>(l.vertices.size()));
      }
      FillResult ours, ours_mt;
      row.dot = RunOurs(config, c, holes, stage, 1, &ours);
      row.dot_mt = RunOurs(config, c, holes, stage, 0, &ours_mt);
      if (ours.status.ok()) {
        row.dot.verdict =
            Evaluate(*judge, ours.mesh.vertices, ours.mesh.triangles);
        row.dot.judged = true;
        // A defect: an output reported as filled that is not valid.
        const std::string defect = Defect(c, ours, row.dot.verdict);
        if (!defect.empty()) {
          ++invalid;
          std::cerr << "dot-bench fill: DEFECT " << c.name << " stage "
                    << FillStageName(stage) << ": " << defect << "\n";
          row.dot.note = defect;
        }
      }
      // The opt-in for inputs that cross themselves, where dot left holes
      // open: judged for its topology (its crossings are reported).
      if (!row.dot.open_reasons.empty()) {
        FillResult allowed;
        row.dot_allow = RunOurs(config, c, holes, stage, 1, &allowed, true);
        if (allowed.status.ok()) {
          row.dot_allow.verdict =
              Evaluate(*judge, allowed.mesh.vertices, allowed.mesh.triangles);
          row.dot_allow.judged = true;
        }
      } else {
        row.dot_allow.status = "skipped";
      }
      if (ours_mt.status.ok()) {
        if (ours_mt.mesh.vertices == ours.mesh.vertices &&
            ours_mt.mesh.triangles == ours.mesh.triangles) {
          row.dot_mt.verdict = row.dot.verdict;
        } else {
          row.dot_mt.verdict =
              Evaluate(*judge, ours_mt.mesh.vertices, ours_mt.mesh.triangles);
          row.dot_mt.note = "output differs from threads = 1";
        }
        row.dot_mt.judged = true;
      }
      if (!have_sm) {
        row.cgal.status = "error: no Surface_mesh";
      } else if (cgal_timed_out) {
        row.cgal.status = "timeout (earlier stage)";
      } else {
        MeshData cgal_mesh;
        row.cgal =
            RunCgal(config, c, holes, soup, input_ids, stage, &cgal_mesh);
        cgal_timed_out = row.cgal.status == "timeout";
        if (row.cgal.status == "ok") {
          row.cgal.verdict =
              Evaluate(*judge, cgal_mesh.vertices, cgal_mesh.triangles);
          row.cgal.judged = true;
          double dot_ms = 0, cgal_ms = 0;
          for (int k = 0; k < holes.count; ++k) {
            if (!row.cgal.hole_cubic[k]) continue;
            ++row.cubic_holes;
            dot_ms += row.dot.hole_ms[k];
            cgal_ms += row.cgal.hole_ms[k];
          }
          if (row.cubic_holes > 0) {
            row.dot_cubic_ms = dot_ms;
            row.cgal_cubic_ms = cgal_ms;
          }
        }
      }
      std::cerr << "fill: [" << ci + 1 << "/" << cases.size() << "] " << c.name
                << " " << FillStageName(stage) << ": dot " << Cell(row.dot)
                << " | mt " << Fixed(row.dot_mt.time.ms, 1) << " ms | CGAL "
                << Cell(row.cgal) << " cubic " << row.cubic_holes << " ("
                << Fixed(MsSince(t_start) / 1000, 0) << " s)\n";
      for (const std::string& why : row.dot.open_reasons) {
        std::cerr << "fill:   dot left open " << why << "\n";
      }
      // The mesh, for reproducing what dot left open or got wrong:
      // dotctl fill-holes --local fill-repro/<mesh>.ply --stage <stage>.
      if ((!row.dot.open_reasons.empty() || !row.dot.note.empty()) &&
          !repro_written) {
        std::string file = c.name;
        std::replace(file.begin(), file.end(), '/', '_');
        std::filesystem::create_directories(config.Path("fill-repro"));
        repro_written =
            WriteMeshFile(config.Path("fill-repro/" + file + ".ply"), c.mesh)
                .ok();
      }
      rows.push_back(std::move(row));
    }
  }
  WriteCsv(config, rows);
  WriteReport(config, rows, report);
  report << "Every dot output was judged (intersections, edge-manifold, "
            "orientation, closed as reported, input vertices kept): "
         << (invalid == 0 ? "all valid"
                          : std::to_string(invalid) + " DEFECTIVE (see stderr)")
         << ".\n\n";
  return invalid;
}

}  // namespace dot::bench

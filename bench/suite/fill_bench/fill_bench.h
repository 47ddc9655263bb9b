// SPDX-License-Identifier: AGPL-3.0-or-later
// Hole filling against CGAL 5.5, split by concern: the meshes (cases.cc),
// our runs (run_ours.cc), CGAL's in a child process (cgal_child.cc), the
// judge both outputs face alike (judge.cc) and the report (report.cc);
// ../fig_fill.cc runs them mesh by mesh and stage by stage.
#ifndef DOT_BENCH_SUITE_FILL_BENCH_FILL_BENCH_H_
#define DOT_BENCH_SUITE_FILL_BENCH_FILL_BENCH_H_

#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <unordered_map>
#include <vector>

#include "dot/dot.h"
#include "measure.h"
#include "suite.h"

namespace dot::bench::fill {

using Clock = std::chrono::steady_clock;

constexpr double kCgalCapS = 60;  // a CGAL run of one mesh stops here
constexpr char kTarball[] = "/usr/share/doc/libcgal-dev/data.tar.gz";
constexpr FillStage kStages[] = {FillStage::kTriangulate, FillStage::kRefine,
                                 FillStage::kFair};

// ---- cases.cc
// One benchmark mesh: repaired, with holes; for cut meshes the closed mesh
// they were cut from and the removed patches (the ground truth).
struct Case {
  std::string name, kind, base;  // kind: open, cut, pinched, dendritic
  MeshData mesh, original, removed;
};

std::vector<Case> MakeCases(const Config& config);
// A libcgal-demo mesh by name ("elephant"), repaired; false (said on
// stderr) when it cannot be read.
bool LoadMesh(const Config& config, const std::string& name, MeshData* out);

// ---- judge.cc
// Holes as the comparison counts them: loops that share a vertex (a
// pinched border) are one hole, since CGAL sees them as one border cycle.
struct Holes {
  std::vector<HoleLoop> loops;
  std::vector<int> loop_hole;               // loop -> hole
  std::unordered_map<int32_t, int> vertex;  // border vertex -> hole
  int count = 0, pinched_loops = 0;
};
Holes FindHoles(const MeshData& mesh);

// The judgement of one output mesh (input vertices first, same ids).
struct Verdict {
  int64_t new_faces = 0, degenerate = 0, pairs = -1;
  int64_t non_manifold = 0, misoriented = 0;
  bool closed = false;
  // Cut meshes, in mean edge lengths of the closed mesh: mean distance of
  // the new faces to the closed mesh, of the removed patches to the
  // output, their average, and the larger of the two maxima (Hausdorff).
  double d_patch = NAN, d_truth = NAN, d_mean = NAN, d_max = NAN;
};

// What every output is judged against, built once per mesh.
struct Judge;
std::shared_ptr<const Judge> MakeJudge(const Case& c);
Verdict Evaluate(const Judge& j, const std::vector<Vec3>& vertices,
                 const std::vector<Triangle>& faces);
// What is wrong with an output of ours reported as filled (empty: nothing).
std::string Defect(const Case& c, const FillResult& ours, const Verdict& v);

// ---- run_ours.cc, cgal_child.cc
// One method at one stage on one mesh.
struct Run {
  std::string status = "ok";  // ok, timeout, skipped, error: ...
  Sample time;
  int loops = 0, loops_filled = 0, holes_filled = 0;
  std::vector<bool> hole_filled;  // per hole (Holes)
  std::vector<double> hole_ms;    // per hole, median over runs
  std::vector<bool> hole_cubic;   // CGAL: the cubic search ran
  int escalated = 0, fair_failed = 0, reverted = 0;
  int delaunay_first = 0;  // dot: holes filled by the delaunay_first step
  // dot with allow_input_intersections: holes filled whose patch meets
  // the mesh, and the pairs they report (theirs with the mesh).
  int crossing_holes = 0;
  int64_t crossing_pairs = 0;
  int not_refined = 0;    // dot: neighbourhood not manifold (pinched)
  double build_ms = NAN;  // CGAL: building the Surface_mesh (median)
  std::vector<std::string> open_reasons;  // dot: holes left open, and why
  Verdict verdict;
  std::string note;
  bool judged = false;
};

// Repeats like Measure (fewer runs past long_run_s, one past cap_s);
// `once` returns the run's wall ms and peak heap.
template <typename Fn>
Sample Repeat(const Config& config, Fn once) {
  std::vector<double> ms, heap;
  Sample s;
  int reps = config.reps;
  for (int r = 0; r < reps; ++r) {
    double t = NAN, h = NAN;
    if (!once(&t, &h)) break;
    ms.push_back(t);
    heap.push_back(h);
    if (t > 1000 * config.cap_s) break;
    if (t > 1000 * config.long_run_s) reps = std::min(reps, 3);
  }
  s.ms = Median(ms);
  s.heap = Median(heap);
  s.runs = static_cast<int>(ms.size());
  return s;
}

Run RunOurs(const Config& config, const Case& c, const Holes& holes,
            FillStage stage, int threads, FillResult* last,
            bool allow_input_intersections = false);

// Vertex ids of a CGAL output in the input's numbering: copies of an input
// point (orient_polygon_soup's duplicates) are that input vertex; new
// points follow the input vertices.
struct ByPoint {
  size_t operator()(const Vec3& v) const {
    size_t h = std::hash<double>()(v.x);
    h = h * 1000003 ^ std::hash<double>()(v.y);
    return h * 1000003 ^ std::hash<double>()(v.z);
  }
};
using PointIds = std::unordered_map<Vec3, int32_t, ByPoint>;

// Whether CGAL gets the mesh as a polygon soup (non-manifold vertices).
bool NeedsSoup(const MeshData& mesh);
// Whether a Surface_mesh can be built from it at all.
bool CgalCanBuild(const MeshData& mesh, bool soup);
Run RunCgal(const Config& config, const Case& c, const Holes& holes, bool soup,
            const PointIds& input_ids, FillStage stage, MeshData* out);

// ---- report.cc
struct Row {
  const Case* c;
  int vertices = 0, faces = 0, loops = 0, holes = 0, pinched = 0;
  int max_loop = 0;          // vertices of the largest loop
  int64_t input_pairs = 0;   // intersecting pairs of the input itself
  int64_t truth_pairs = -1;  // of the ground truth with the input
  FillStage stage;
  Run dot, dot_mt, cgal;
  // dot with allow_input_intersections, run where dot left holes open.
  Run dot_allow;
  int cubic_holes = 0;
  double dot_cubic_ms = NAN, cgal_cubic_ms = NAN;
};

std::string Yes(bool b);
std::string Cell(const Run& r);
void WriteCsv(const Config& config, const std::vector<Row>& rows);
void WriteReport(const Config& config, const std::vector<Row>& rows,
                 std::ostream& report);

}  // namespace dot::bench::fill

#endif  // DOT_BENCH_SUITE_FILL_BENCH_FILL_BENCH_H_

// SPDX-License-Identifier: AGPL-3.0-or-later
// Hole filling against CGAL 5.5 (issue 11's benchmark). Meshes: the real
// open meshes of libcgal-demo (ground truth unknown) and holes cut into
// closed ones (CutHoles; pinched pairs of holes that touch at one vertex;
// large dendritic holes whose boundaries are not Delaunay). For every mesh
// and stage (triangulate, refine, fair), in one process:
//  - dot: FillHoles with default options and the stage, threads = 1 (and
//    threads = 0, all cores, reported apart);
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
// closed and edge-manifold, and for cut meshes the distance to the ground
// truth.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <numeric>
#include <random>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "heap_meter.h"
#include "measure.h"
#include "suite.h"
#include "util/union_find.h"

namespace dot::bench {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using Halfedge = SurfaceMesh::Halfedge_index;
namespace PMP = CGAL::Polygon_mesh_processing;
using Clock = std::chrono::steady_clock;

constexpr double kCgalCapS = 60;  // a CGAL run of one mesh stops here
constexpr char kTarball[] = "/usr/share/doc/libcgal-dev/data.tar.gz";
constexpr FillStage kStages[] = {FillStage::kTriangulate, FillStage::kRefine,
                                 FillStage::kFair};

// ---------------------------------------------------------------- meshes

// One benchmark mesh: repaired, with holes; for cut meshes the closed mesh
// they were cut from and the removed patches (the ground truth).
struct Case {
  std::string name, kind, base;  // kind: open, cut, pinched, dendritic
  MeshData mesh, original, removed;
};

// `name`.off in the mesh directory, extracted from libcgal-demo's tarball
// when missing. Empty when it cannot be had.
std::string MeshPath(const Config& config, const std::string& name) {
  const std::string path = config.mesh_dir + "/" + name + ".off";
  if (std::filesystem::exists(path)) return path;
  if (!std::filesystem::exists(kTarball)) return "";
  const std::string tmp = path + ".part";
  const std::string cmd = std::string("tar -xzOf ") + kTarball +
                          " data/meshes/" + name + ".off > '" + tmp +
                          "' 2>/dev/null";
  std::error_code ec;
  if (std::system(cmd.c_str()) != 0 ||
      std::filesystem::file_size(tmp, ec) == 0) {
    std::filesystem::remove(tmp, ec);
    return "";
  }
  std::filesystem::rename(tmp, path, ec);
  return ec ? "" : path;
}

PolygonSoup ToSoup(const MeshData& m) {
  PolygonSoup soup;
  soup.vertices = m.vertices;
  for (const Triangle& t : m.triangles)
    soup.faces.push_back({t[0], t[1], t[2]});
  return soup;
}

bool Repaired(const PolygonSoup& soup, const std::string& what, MeshData* out) {
  RepairReport rr;
  const Status s = RepairMesh(soup, out, &rr);
  if (!s.ok()) {
    std::cerr << "dot-bench fill: " << what << ": " << s.message << "\n";
  }
  return s.ok();
}

bool LoadMesh(const Config& config, const std::string& name, MeshData* out) {
  const std::string path = MeshPath(config, name);
  PolygonSoup soup;
  if (path.empty() || !ReadPolygonSoupFile(path, &soup).ok()) {
    std::cerr << "dot-bench fill: cannot read mesh " << name << "\n";
    return false;
  }
  return Repaired(soup, name, out);
}

uint64_t EdgeKey(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(a) << 32) | static_cast<uint32_t>(b);
}

// `pairs` pinched holes: a hole A grown with GrowHole (`ta` triangles) and a
// hole B of `tb` triangles grown from a face at one of A's boundary
// vertices v, never touching A elsewhere; so the border of A and B passes v
// twice (two fans of faces meet at v). Pairs share no vertex.
Status CutPinched(const MeshData& mesh, int pairs, int ta, int tb,
                  uint64_t seed, MeshData* holey, MeshData* removed) {
  const size_t nv = mesh.vertices.size(), nf = mesh.triangles.size();
  std::vector<std::vector<int32_t>> vertex_faces(nv);
  std::unordered_map<uint64_t, std::vector<int32_t>> edge_faces;
  for (size_t f = 0; f < nf; ++f) {
    const Triangle& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      vertex_faces[t[k]].push_back(static_cast<int32_t>(f));
      edge_faces[EdgeKey(t[k], t[(k + 1) % 3])].push_back(
          static_cast<int32_t>(f));
    }
  }
  std::vector<bool> in_hole(nf, false), near(nv, false);
  std::mt19937_64 rng(seed);
  int made = 0;
  for (uint64_t attempt = 0; made < pairs && attempt < 200u * pairs;
       ++attempt) {
    Hole a;
    if (!GrowHole(mesh, ta, seed * 7919 + attempt, &a).ok()) continue;
    std::vector<bool> in_a(nf, false), va(nv, false);
    bool apart = true;
    for (int32_t f : a.removed) {
      in_a[f] = true;
      for (int32_t v : mesh.triangles[f]) apart &= !near[v], va[v] = true;
    }
    if (!apart) continue;
    std::vector<int32_t> rim;  // A's boundary vertices
    for (size_t v = 0; v < nv; ++v) {
      if (!va[v]) continue;
      for (int32_t f : vertex_faces[v]) {
        if (!in_a[f]) {
          rim.push_back(static_cast<int32_t>(v));
          break;
        }
      }
    }
    std::shuffle(rim.begin(), rim.end(), rng);
    std::vector<int32_t> b;
    for (int32_t v : rim) {
      for (int32_t f0 : vertex_faces[v]) {
        const Triangle& t0 = mesh.triangles[f0];
        bool ok = !in_a[f0] && !in_hole[f0];
        for (int32_t u : t0) ok &= u == v || (!va[u] && !near[u]);
        if (!ok) continue;
        // Grow B: a face across one of B's edges whose third vertex is new
        // (so B stays a disk with a simple boundary) and away from A.
        b = {f0};
        std::unordered_set<int32_t> in_b = {f0};
        std::unordered_set<int32_t> vb(t0.begin(), t0.end());
        while (static_cast<int>(b.size()) < tb) {
          std::vector<int32_t> next;
          for (int32_t f : b) {
            const Triangle& t = mesh.triangles[f];
            for (int k = 0; k < 3; ++k) {
              for (int32_t g : edge_faces[EdgeKey(t[k], t[(k + 1) % 3])]) {
                if (in_b.count(g) || in_a[g] || in_hole[g]) continue;
                int32_t third = -1;
                for (int32_t u : mesh.triangles[g]) {
                  if (u != t[k] && u != t[(k + 1) % 3]) third = u;
                }
                if (third < 0 || vb.count(third) || va[third] || near[third]) {
                  continue;
                }
                next.push_back(g);
              }
            }
          }
          if (next.empty()) break;
          const int32_t g = next[rng() % next.size()];
          b.push_back(g);
          in_b.insert(g);
          for (int32_t u : mesh.triangles[g]) vb.insert(u);
        }
        if (static_cast<int>(b.size()) == tb) break;
        b.clear();
      }
      if (!b.empty()) break;
    }
    if (b.empty()) continue;
    for (int32_t f : a.removed) in_hole[f] = true;
    for (int32_t f : b) in_hole[f] = true;
    for (size_t f = 0; f < nf; ++f) {
      if (!in_hole[f]) continue;
      for (int32_t v : mesh.triangles[f]) near[v] = true;
    }
    ++made;
  }
  if (made < pairs) {
    return InvalidArgument("room for only " + std::to_string(made) +
                           " pinched pairs");
  }
  std::vector<bool> kept(nf);
  for (size_t f = 0; f < nf; ++f) kept[f] = !in_hole[f];
  *holey = SubMesh(mesh, kept);
  *removed = SubMesh(mesh, in_hole);
  return OkStatus();
}

// A cut: holes of `triangles` triangles (CutHoles), or pinched pairs.
struct CutSpec {
  std::string kind;
  int count = 0, triangles = 0, small = 0;  // small: B of a pinched pair
  uint64_t seed = 1;
};

std::vector<Case> MakeCases(const Config& config) {
  std::vector<Case> cases;
  const std::vector<std::string> open =
      config.quick
          ? std::vector<std::string>{"elephant-with-holes", "holes"}
          : std::vector<std::string>{"elephant-with-holes", "holes", "lion",
                                     "mech-holes-shark", "head"};
  for (const std::string& name : open) {
    Case c;
    c.name = name;
    c.kind = "open";
    c.base = name;
    if (LoadMesh(config, name, &c.mesh)) cases.push_back(std::move(c));
  }
  struct Base {
    std::string name;
    std::vector<CutSpec> cuts;
  };
  std::vector<Base> bases;
  if (config.quick) {
    bases = {{"elephant", {{"cut", 4, 30, 0, 1}, {"pinched", 1, 60, 20, 4}}},
             {"armadillo", {{"cut", 2, 300, 0, 2}}}};
  } else {
    const std::vector<CutSpec> common = {{"cut", 10, 30, 0, 1},
                                         {"cut", 4, 300, 0, 2},
                                         {"cut", 2, 1500, 0, 3},
                                         {"pinched", 2, 120, 40, 4}};
    for (const char* name :
         {"elephant", "armadillo", "bunny00", "refined_elephant", "cow",
          "homer", "camel", "man"}) {
      bases.push_back({name, common});
    }
    // Large dendritic holes (non-Delaunay boundaries, CGAL's cubic
    // fallback) where the mesh has room for them.
    // 2,500 triangles removed leave boundaries of 350-600 vertices; on
    // the smaller meshes (elephant, homer, camel) most of them send CGAL to
    // its cubic search.
    for (Base& b : bases) {
      const bool small =
          b.name == "elephant" || b.name == "homer" || b.name == "camel";
      for (uint64_t seed : {5, 6, 7, 8}) {
        if (seed <= 6 || small)
          b.cuts.push_back({"dendritic", 1, 2500, 0, seed});
      }
    }
  }
  for (const Base& base : bases) {
    MeshData closed;
    if (!LoadMesh(config, base.name, &closed)) continue;
    std::vector<HoleLoop> loops;
    if (!FindHoleLoops(closed, &loops).ok() || !loops.empty()) {
      std::cerr << "dot-bench fill: " << base.name
                << " is not closed; not used\n";
      continue;
    }
    for (const CutSpec& cut : base.cuts) {
      Case c;
      c.kind = cut.kind;
      c.base = base.name;
      MeshData holey;
      Status s;
      if (cut.kind == "pinched") {
        c.name = base.name + "/pinch" + std::to_string(cut.count) + "-t" +
                 std::to_string(cut.triangles) + "+" +
                 std::to_string(cut.small) + "-s" + std::to_string(cut.seed);
        s = CutPinched(closed, cut.count, cut.triangles, cut.small, cut.seed,
                       &holey, &c.removed);
      } else {
        // Fewer holes when the mesh has no room for them all.
        int count = cut.count;
        do {
          s = CutHoles(closed, count, cut.triangles, cut.seed, &holey,
                       &c.removed);
        } while (!s.ok() && --count > 0);
        c.name = base.name + "/k" + std::to_string(count) + "-t" +
                 std::to_string(cut.triangles) + "-s" +
                 std::to_string(cut.seed);
      }
      if (!s.ok() || !Repaired(ToSoup(holey), c.name, &c.mesh)) {
        std::cerr << "dot-bench fill: " << c.name << ": " << s.message << "\n";
        continue;
      }
      c.original = closed;
      cases.push_back(std::move(c));
    }
  }
  return cases;
}

// ------------------------------------------------------------- judging

// Holes as the comparison counts them: loops that share a vertex (a
// pinched border) are one hole, since CGAL sees them as one border cycle.
struct Holes {
  std::vector<HoleLoop> loops;
  std::vector<int> loop_hole;               // loop -> hole
  std::unordered_map<int32_t, int> vertex;  // border vertex -> hole
  int count = 0, pinched_loops = 0;
};

Holes FindHoles(const MeshData& mesh) {
  Holes h;
  if (!FindHoleLoops(mesh, &h.loops).ok()) return h;
  UnionFind holes(h.loops.size());  // loops that share a vertex: one hole
  std::unordered_map<int32_t, int> first;
  for (size_t i = 0; i < h.loops.size(); ++i) {
    h.pinched_loops += h.loops[i].pinched;
    for (int32_t v : h.loops[i].vertices) {
      auto [it, added] = first.emplace(v, static_cast<int>(i));
      if (!added) holes.Join(static_cast<int>(i), it->second);
    }
  }
  std::map<int, int> id;
  for (size_t i = 0; i < h.loops.size(); ++i) {
    auto [it, added] = id.emplace(holes.Find(static_cast<int>(i)),
                                  static_cast<int>(id.size()));
    h.loop_hole.push_back(it->second);
  }
  h.count = static_cast<int>(id.size());
  for (size_t i = 0; i < h.loops.size(); ++i) {
    for (int32_t v : h.loops[i].vertices) h.vertex[v] = h.loop_hole[i];
  }
  return h;
}

using Tri3 = K::Triangle_3;
using Primitive =
    CGAL::AABB_triangle_primitive<K, std::vector<Tri3>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

K::Point_3 P(const Vec3& v) { return {v.x, v.y, v.z}; }

std::vector<Tri3> Triangles3(const std::vector<Vec3>& v,
                             const std::vector<Triangle>& faces) {
  std::vector<Tri3> out;
  for (const Triangle& t : faces) {
    Tri3 tri(P(v[t[0]]), P(v[t[1]]), P(v[t[2]]));
    if (!tri.is_degenerate()) out.push_back(tri);
  }
  return out;
}

// Area-weighted sample points: centroids of an L x L subdivision of each
// triangle, L growing with its area over `cell` (about four points on a
// triangle of the mesh's mean edge length).
struct Samples {
  std::vector<K::Point_3> points;
  std::vector<double> weights;
};

Samples SamplePoints(const std::vector<Tri3>& tris, double cell) {
  Samples s;
  for (const Tri3& t : tris) {
    const double area = std::sqrt(CGAL::to_double(t.squared_area()));
    const int l =
        std::clamp(static_cast<int>(std::ceil(std::sqrt(area / cell))), 1, 32);
    const double w = area / (l * l);
    auto add = [&](double u, double v) {
      const double a = 1 - u - v;
      s.points.emplace_back(a * t[0].x() + u * t[1].x() + v * t[2].x(),
                            a * t[0].y() + u * t[1].y() + v * t[2].y(),
                            a * t[0].z() + u * t[1].z() + v * t[2].z());
      s.weights.push_back(w);
    };
    for (int i = 0; i < l; ++i) {
      for (int j = 0; i + j < l; ++j) {
        add((i + 1.0 / 3) / l, (j + 1.0 / 3) / l);
        if (i + j < l - 1) add((i + 2.0 / 3) / l, (j + 2.0 / 3) / l);
      }
    }
  }
  return s;
}

// Weighted mean and max distance of the samples to the tree's surface.
std::pair<double, double> Distances(const Samples& s, const Tree& tree) {
  double sum = 0, weight = 0, most = 0;
  for (size_t i = 0; i < s.points.size(); ++i) {
    const double d =
        std::sqrt(CGAL::to_double(tree.squared_distance(s.points[i])));
    sum += s.weights[i] * d;
    weight += s.weights[i];
    most = std::max(most, d);
  }
  return {weight > 0 ? sum / weight : NAN, weight > 0 ? most : NAN};
}

// What every output is judged against, built once per mesh.
struct Judge {
  std::unordered_set<uint64_t> input_faces;  // sorted corners, 21 bits each
  // Cut meshes: the closed mesh and samples of the removed patches.
  std::vector<Tri3> original_tris;
  std::unique_ptr<Tree> original;
  Samples truth;
  double edge = 0, cell = 0;  // mean edge length of the closed mesh
};

uint64_t FaceKey(Triangle t) {
  std::sort(t.begin(), t.end());
  return (static_cast<uint64_t>(t[0]) << 42) |
         (static_cast<uint64_t>(t[1]) << 21) | static_cast<uint64_t>(t[2]);
}

Judge MakeJudge(const Case& c) {
  Judge j;
  for (const Triangle& t : c.mesh.triangles) j.input_faces.insert(FaceKey(t));
  if (c.original.triangles.empty()) return j;
  double length = 0;
  for (const Triangle& t : c.original.triangles) {
    for (int k = 0; k < 3; ++k) {
      length += Distance(c.original.vertices[t[k]],
                         c.original.vertices[t[(k + 1) % 3]]);
    }
  }
  j.edge = length / (3.0 * c.original.triangles.size());
  j.cell = j.edge * j.edge * std::sqrt(3.0) / 16;
  j.original_tris = Triangles3(c.original.vertices, c.original.triangles);
  j.original =
      std::make_unique<Tree>(j.original_tris.begin(), j.original_tris.end());
  j.original->accelerate_distance_queries();
  j.truth =
      SamplePoints(Triangles3(c.removed.vertices, c.removed.triangles), j.cell);
  return j;
}

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

Verdict Evaluate(const Judge& j, const std::vector<Vec3>& vertices,
                 const std::vector<Triangle>& faces) {
  Verdict v;
  std::vector<Triangle> ordered, fresh;
  for (const Triangle& t : faces) {
    if (j.input_faces.count(FaceKey(t))) {
      ordered.push_back(t);
      continue;
    }
    ++v.new_faces;
    const bool degenerate =
        t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
        CGAL::collinear(P(vertices[t[0]]), P(vertices[t[1]]),
                        P(vertices[t[2]]));
    if (degenerate) {
      ++v.degenerate;
    } else {
      fresh.push_back(t);
    }
  }
  // New faces first: pairs with at least one new face are counted.
  const size_t checked = fresh.size();
  fresh.insert(fresh.end(), ordered.begin(), ordered.end());
  v.pairs = CountIntersectingPairs(vertices, fresh, checked);
  std::unordered_map<uint64_t, std::pair<int, int>> edges;  // uses, forward
  for (const Triangle& t : faces) {
    for (int k = 0; k < 3; ++k) {
      auto& e = edges[EdgeKey(t[k], t[(k + 1) % 3])];
      ++e.first;
      e.second += t[k] < t[(k + 1) % 3];
    }
  }
  v.closed = true;
  for (const auto& [key, e] : edges) {
    v.closed &= e.first == 2;
    v.non_manifold += e.first > 2;
    v.misoriented += e.first == 2 && e.second != 1;
  }
  if (j.original) {
    fresh.resize(checked);
    const Samples patch = SamplePoints(Triangles3(vertices, fresh), j.cell);
    const auto [patch_mean, patch_max] = Distances(patch, *j.original);
    const std::vector<Tri3> out_tris = Triangles3(vertices, faces);
    Tree out(out_tris.begin(), out_tris.end());
    out.accelerate_distance_queries();
    const auto [truth_mean, truth_max] = Distances(j.truth, out);
    v.d_patch = patch_mean / j.edge;
    v.d_truth = truth_mean / j.edge;
    v.d_mean = 0.5 * (v.d_patch + v.d_truth);
    v.d_max =
        std::max(std::isnan(patch_max) ? 0 : patch_max, truth_max) / j.edge;
  }
  return v;
}

// ------------------------------------------------------------- running

// One method at one stage on one mesh.
struct Run {
  std::string status = "ok";  // ok, timeout, skipped, error: ...
  Sample time;
  int loops = 0, loops_filled = 0, holes_filled = 0;
  std::vector<bool> hole_filled;  // per hole (Holes)
  std::vector<double> hole_ms;    // per hole, median over runs
  std::vector<bool> hole_cubic;   // CGAL: the cubic search ran
  int escalated = 0, fair_failed = 0, reverted = 0;
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
            FillStage stage, int threads, FillResult* last) {
  Run run;
  FillOptions options;
  options.stage = stage;
  options.threads = threads;
  std::vector<std::vector<double>> hole_ms(holes.count);
  run.time = Repeat(config, [&](double* ms, double* heap) {
    *last = FillResult();
    ResetHeapPeak();
    const auto t0 = Clock::now();
    FillResult r = FillHoles(c.mesh, options);
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
                     h.escalation == Escalation::kAllTriangles;
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

// --- CGAL, in a child process.

struct CgalVisitor : PMP::Hole_filling::Default_visitor {
  bool* cubic;
  explicit CgalVisitor(bool* c) : cubic(c) {}
  void start_cubic_phase(int) const { *cubic = true; }
};

// What the child sends back.
struct CgalCycle {
  int32_t first = 0;  // a vertex of the cycle (Surface_mesh index)
  int32_t filled = 0, cubic = 0, fair_ok = 1;
  double ms = 0;
};

struct CgalOnce {
  std::string status = "ok";
  double ms = NAN, build_ms = NAN, heap = NAN;
  std::vector<CgalCycle> cycles;
  std::vector<Vec3> vertices;  // Surface_mesh vertices, by index
  std::vector<Triangle> faces;
};

template <typename T>
void Put(std::string* out, const T& v) {
  out->append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <typename T>
bool Get(const std::string& in, size_t* at, T* v) {
  if (*at + sizeof *v > in.size()) return false;
  std::memcpy(v, in.data() + *at, sizeof *v);
  *at += sizeof *v;
  return true;
}

// The Surface_mesh CGAL fills, built from the repaired mesh: face by face
// (add_face), or, when the mesh has non-manifold vertices (pinched
// borders; `soup` is then true), as CGAL's readers do: orient_polygon_soup
// duplicates those vertices and polygon_soup_to_polygon_mesh builds it, so
// a pinched border is one cycle through two copies of a point.
bool BuildSurfaceMesh(const MeshData& m, bool soup, SurfaceMesh* sm) {
  if (!soup) {
    sm->reserve(m.vertices.size(), 3 * m.triangles.size() / 2,
                m.triangles.size());
    for (const Vec3& v : m.vertices) sm->add_vertex(P(v));
    for (const Triangle& t : m.triangles) {
      const auto f = sm->add_face(SurfaceMesh::Vertex_index(t[0]),
                                  SurfaceMesh::Vertex_index(t[1]),
                                  SurfaceMesh::Vertex_index(t[2]));
      if (f == SurfaceMesh::null_face()) return false;
    }
    return true;
  }
  std::vector<K::Point_3> points;
  for (const Vec3& v : m.vertices) points.push_back(P(v));
  std::vector<std::array<std::size_t, 3>> faces;
  for (const Triangle& t : m.triangles) {
    faces.push_back({static_cast<std::size_t>(t[0]),
                     static_cast<std::size_t>(t[1]),
                     static_cast<std::size_t>(t[2])});
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(faces)) {
    PMP::orient_polygon_soup(points, faces);
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(faces)) return false;
  PMP::polygon_soup_to_polygon_mesh(points, faces, *sm);
  return true;
}

// True when CGAL needs the soup route for `m` (non-manifold vertices).
bool NeedsSoup(const MeshData& m) {
  std::vector<std::array<std::size_t, 3>> faces;
  for (const Triangle& t : m.triangles) {
    faces.push_back({static_cast<std::size_t>(t[0]),
                     static_cast<std::size_t>(t[1]),
                     static_cast<std::size_t>(t[2])});
  }
  return !PMP::is_polygon_soup_a_polygon_mesh(faces);
}

// The child's work: build the Surface_mesh (timed apart), fill every
// border cycle (timed), send the result. Peak heap covers both.
std::string CgalChild(const MeshData& mesh, bool soup, FillStage stage) {
  ResetHeapPeak();
  const auto tb = Clock::now();
  SurfaceMesh sm;
  if (!BuildSurfaceMesh(mesh, soup, &sm)) _exit(5);
  const double build_ms = MsSince(tb);
  std::vector<CgalCycle> cycles;
  const auto t0 = Clock::now();
  std::vector<Halfedge> borders;
  PMP::extract_boundary_cycles(sm, std::back_inserter(borders));
  for (Halfedge h : borders) {
    CgalCycle cy;
    cy.first = static_cast<int32_t>(sm.target(h).idx());
    bool cubic = false;
    CgalVisitor visitor(&cubic);
    std::vector<SurfaceMesh::Face_index> faces;
    std::vector<SurfaceMesh::Vertex_index> vertices;
    const auto t = Clock::now();
    switch (stage) {
      case FillStage::kTriangulate:
        PMP::triangulate_hole(sm, h, std::back_inserter(faces),
                              CGAL::parameters::visitor(visitor));
        break;
      case FillStage::kRefine:
        PMP::triangulate_and_refine_hole(sm, h, std::back_inserter(faces),
                                         std::back_inserter(vertices),
                                         CGAL::parameters::visitor(visitor));
        break;
      case FillStage::kFair:
        cy.fair_ok = std::get<0>(PMP::triangulate_refine_and_fair_hole(
            sm, h, std::back_inserter(faces), std::back_inserter(vertices),
            CGAL::parameters::visitor(visitor)));
        break;
    }
    cy.ms = MsSince(t);
    cy.filled = !faces.empty();
    cy.cubic = cubic;
    cycles.push_back(cy);
  }
  const double ms = MsSince(t0);
  const auto heap = static_cast<double>(HeapPeakBytes());
  if (sm.has_garbage()) sm.collect_garbage();  // contiguous indices
  std::string out;
  Put(&out, ms);
  Put(&out, build_ms);
  Put(&out, heap);
  Put(&out, static_cast<int64_t>(cycles.size()));
  for (const CgalCycle& cy : cycles) Put(&out, cy);
  Put(&out, static_cast<int64_t>(sm.number_of_vertices()));
  for (auto v : sm.vertices()) {
    const K::Point_3& p = sm.point(v);
    Put(&out, Vec3{p.x(), p.y(), p.z()});
  }
  Put(&out, static_cast<int64_t>(sm.number_of_faces()));
  for (auto f : sm.faces()) {
    Triangle t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (k < 3) t[k] = static_cast<int32_t>(v.idx());
      ++k;
    }
    Put(&out, t);
  }
  return out;
}

CgalOnce RunCgalOnce(const MeshData& mesh, bool soup, FillStage stage,
                     double cap_s) {
  CgalOnce r;
  int fds[2];
  if (pipe(fds) != 0) {
    r.status = "error: pipe";
    return r;
  }
  std::cout.flush();
  std::cerr.flush();
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    r.status = "error: fork";
    return r;
  }
  if (pid == 0) {
    close(fds[0]);
    std::string out;
    int code = 0;
    try {
      out = CgalChild(mesh, soup, stage);
    } catch (const std::exception& e) {
      out.clear();
      code = 3;
    }
    size_t at = 0;
    while (at < out.size()) {
      const ssize_t w = write(fds[1], out.data() + at, out.size() - at);
      if (w <= 0) _exit(4);
      at += static_cast<size_t>(w);
    }
    close(fds[1]);
    _exit(code);
  }
  close(fds[1]);
  const auto deadline =
      Clock::now() + std::chrono::milliseconds(static_cast<int>(cap_s * 1000));
  std::string data;
  char buf[1 << 16];
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - Clock::now())
                          .count();
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = poll(&p, 1, static_cast<int>(left));
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) {
      timed_out = true;
      break;
    }
    const ssize_t n = read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    data.append(buf, static_cast<size_t>(n));
  }
  close(fds[0]);
  if (timed_out) kill(pid, SIGKILL);
  int wstatus = 0;
  waitpid(pid, &wstatus, 0);
  if (timed_out) {
    r.status = "timeout";
    return r;
  }
  if (!WIFEXITED(wstatus) || WEXITSTATUS(wstatus) != 0) {
    r.status = WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 5
                   ? "error: no Surface_mesh"
               : WIFSIGNALED(wstatus)
                   ? "error: crashed (signal " +
                         std::to_string(WTERMSIG(wstatus)) + ")"
                   : "error: exception (exit " +
                         std::to_string(WEXITSTATUS(wstatus)) + ")";
    return r;
  }
  size_t at = 0;
  int64_t n = 0;
  bool ok = Get(data, &at, &r.ms) && Get(data, &at, &r.build_ms) &&
            Get(data, &at, &r.heap) && Get(data, &at, &n);
  for (int64_t i = 0; ok && i < n; ++i) {
    CgalCycle cy;
    ok = Get(data, &at, &cy);
    r.cycles.push_back(cy);
  }
  ok = ok && Get(data, &at, &n);
  r.vertices.resize(ok ? n : 0);
  for (int64_t i = 0; ok && i < n; ++i) ok = Get(data, &at, &r.vertices[i]);
  ok = ok && Get(data, &at, &n);
  r.faces.resize(ok ? n : 0);
  for (int64_t i = 0; ok && i < n; ++i) ok = Get(data, &at, &r.faces[i]);
  if (!ok) r.status = "error: truncated answer";
  return r;
}

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

Run RunCgal(const Config& config, const Case& c, const Holes& holes, bool soup,
            const std::unordered_map<Vec3, int32_t, ByPoint>& input_ids,
            FillStage stage, MeshData* out) {
  Run run;
  CgalOnce last;
  // The hole of a cycle: its vertex's input id (copies of a point map to
  // the input vertex).
  auto hole_of = [&](const CgalOnce& once, const CgalCycle& cy) {
    if (cy.first < 0 ||
        cy.first >= static_cast<int32_t>(once.vertices.size())) {
      return -1;
    }
    auto v = input_ids.find(once.vertices[cy.first]);
    if (v == input_ids.end()) return -1;
    auto h = holes.vertex.find(v->second);
    return h == holes.vertex.end() ? -1 : h->second;
  };
  std::vector<std::vector<double>> hole_ms(holes.count);
  std::vector<double> build_ms;
  run.time = Repeat(config, [&](double* ms, double* heap) {
    CgalOnce once = RunCgalOnce(c.mesh, soup, stage, kCgalCapS);
    if (once.status != "ok") {
      if (last.status == "ok" && last.vertices.empty()) last = once;
      return false;
    }
    *ms = once.ms;
    *heap = once.heap;
    build_ms.push_back(once.build_ms);
    std::vector<double> per(holes.count, 0);
    for (const CgalCycle& cy : once.cycles) {
      const int h = hole_of(once, cy);
      if (h >= 0) per[h] += cy.ms;
    }
    for (int k = 0; k < holes.count; ++k) hole_ms[k].push_back(per[k]);
    last = std::move(once);
    return true;
  });
  if (run.time.runs == 0) {
    run.status = last.status;
    return run;
  }
  run.build_ms = Median(build_ms);
  std::vector<int32_t> id(last.vertices.size());
  out->vertices = c.mesh.vertices;
  for (size_t i = 0; i < last.vertices.size(); ++i) {
    auto it = input_ids.find(last.vertices[i]);
    if (it != input_ids.end()) {
      id[i] = it->second;
    } else {
      id[i] = static_cast<int32_t>(out->vertices.size());
      out->vertices.push_back(last.vertices[i]);
    }
  }
  out->triangles.clear();
  for (Triangle t : last.faces) {
    for (int32_t& v : t) v = id[v];
    out->triangles.push_back(t);
  }
  std::vector<int> open(holes.count, 0), cycles(holes.count, 0);
  run.hole_cubic.assign(holes.count, false);
  for (int k = 0; k < holes.count; ++k) {
    run.hole_ms.push_back(Median(hole_ms[k]));
  }
  run.loops = static_cast<int>(last.cycles.size());
  for (const CgalCycle& cy : last.cycles) {
    run.loops_filled += cy.filled;
    run.fair_failed += stage == FillStage::kFair && cy.filled && !cy.fair_ok;
    const int h = hole_of(last, cy);
    if (h < 0) {
      run.note = "a border cycle outside every hole";
      continue;
    }
    ++cycles[h];
    open[h] += !cy.filled;
    run.hole_cubic[h] = run.hole_cubic[h] || cy.cubic;
  }
  for (int k = 0; k < holes.count; ++k) {
    const bool filled = cycles[k] > 0 && open[k] == 0;
    run.hole_filled.push_back(filled);
    run.holes_filled += filled;
  }
  return run;
}

// ------------------------------------------------------------- report

struct Row {
  const Case* c;
  int vertices = 0, faces = 0, loops = 0, holes = 0, pinched = 0;
  int max_loop = 0;          // vertices of the largest loop
  int64_t input_pairs = 0;   // intersecting pairs of the input itself
  int64_t truth_pairs = -1;  // of the ground truth with the input
  FillStage stage;
  Run dot, dot_mt, cgal;
  int cubic_holes = 0;
  double dot_cubic_ms = NAN, cgal_cubic_ms = NAN;
};

bool SelfIntersecting(const Run& r) {
  return r.judged && (r.verdict.pairs > 0 || r.verdict.degenerate > 0);
}

std::string Yes(bool b) { return b ? "yes" : "no"; }

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
        {"dot", &row.dot}, {"dot_mt", &row.dot_mt}, {"cgal", &row.cgal}};
    for (const auto& [method, r] : runs) {
      const bool cgal = std::string(method) == "cgal";
      const Verdict& v = r->verdict;
      csv << row.c->name << "," << row.c->kind << "," << row.c->base << ","
          << row.vertices << "," << row.faces << "," << row.loops << ","
          << row.holes << "," << row.pinched << "," << row.max_loop << ","
          << FillStageName(row.stage) << "," << method << ","
          << (cgal                           ? "1"
              : std::string(method) == "dot" ? "1"
                                             : "0")
          << "," << r->status << "," << r->time.runs << "," << r->time.ms << ","
          << r->time.heap << "," << r->loops << "," << r->loops_filled << ","
          << r->holes_filled << ",";
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
};

StageSummary Summarize(const std::vector<Row>& rows, FillStage stage) {
  StageSummary s;
  for (const Row& row : rows) {
    if (row.stage != stage) continue;
    ++s.meshes;
    s.holes += row.holes;
    s.dot_filled += row.dot.holes_filled;
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
           << ").\n";
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
           << "protection or all triangles " << escalated
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

}  // namespace

int RunFill(const Config& config, std::ostream& report) {
  const std::vector<Case> cases = MakeCases(config);
  std::vector<Row> rows;
  int invalid = 0;
  const auto t_start = Clock::now();
  for (size_t ci = 0; ci < cases.size(); ++ci) {
    const Case& c = cases[ci];
    const Holes holes = FindHoles(c.mesh);
    const Judge judge = MakeJudge(c);
    const bool soup = NeedsSoup(c.mesh);
    SurfaceMesh check;
    const bool have_sm = BuildSurfaceMesh(c.mesh, soup, &check);
    std::unordered_map<Vec3, int32_t, ByPoint> input_ids;
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
            Evaluate(judge, ours.mesh.vertices, ours.mesh.triangles);
        row.dot.judged = true;
        // A defect: an output reported as filled that is not valid.
        const Verdict& v = row.dot.verdict;
        std::string defect;
        if (v.pairs > 0 || v.degenerate > 0) {
          defect = std::to_string(v.pairs) + " intersecting pairs, " +
                   std::to_string(v.degenerate) + " degenerate new faces";
        } else if (v.non_manifold > 0 || v.misoriented > 0) {
          defect = std::to_string(v.non_manifold) + " non-manifold and " +
                   std::to_string(v.misoriented) + " misoriented edges";
        } else if (v.closed != ours.report.closed) {
          defect = "report.closed is " + Yes(ours.report.closed) +
                   ", the mesh is " + (v.closed ? "" : "not ") + "closed";
        } else if (ours.report.filled == ours.report.loops && !v.closed) {
          defect = "every hole reported filled, the mesh is not closed";
        } else if (!std::equal(c.mesh.vertices.begin(), c.mesh.vertices.end(),
                               ours.mesh.vertices.begin())) {
          defect = "input vertices changed";
        }
        if (!defect.empty()) {
          ++invalid;
          std::cerr << "dot-bench fill: DEFECT " << c.name << " stage "
                    << FillStageName(stage) << ": " << defect << "\n";
          row.dot.note = defect;
        }
      }
      if (ours_mt.status.ok()) {
        if (ours_mt.mesh.vertices == ours.mesh.vertices &&
            ours_mt.mesh.triangles == ours.mesh.triangles) {
          row.dot_mt.verdict = row.dot.verdict;
        } else {
          row.dot_mt.verdict =
              Evaluate(judge, ours_mt.mesh.vertices, ours_mt.mesh.triangles);
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
              Evaluate(judge, cgal_mesh.vertices, cgal_mesh.triangles);
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

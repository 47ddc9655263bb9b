// SPDX-License-Identifier: AGPL-3.0-or-later
// One patch of a network: DOT over its cycle, then Liepa refinement of the
// patch alone (its curves are its border, which refinement never splits or
// flips, so neighbouring patches still meet vertex for vertex).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/refine.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <chrono>
#include <map>

#include "dot/triangulate.h"
#include "fill/refine_limits.h"
#include "network/surface_steps.h"
#include "util/run_control.h"

namespace dot {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
using FaceIndex = SurfaceMesh::Face_index;
namespace PMP = CGAL::Polygon_mesh_processing;

Problem PatchProblem(const std::vector<Vec3>& vertices,
                     const std::vector<std::vector<int32_t>>& loops,
                     const std::vector<Vec3>& normals,
                     const std::vector<std::pair<int32_t, int32_t>>& forbidden,
                     const SurfaceOptions& options, std::vector<int32_t>* ids) {
  Problem p;
  std::map<int32_t, int32_t> position;
  std::vector<int32_t> next;  // local: the next vertex of its loop
  double perimeter = 0;
  for (const auto& loop : loops) {
    const auto first = static_cast<int32_t>(ids->size());
    for (size_t k = 0; k < loop.size(); ++k) {
      position[loop[k]] = static_cast<int32_t>(ids->size());
      ids->push_back(loop[k]);
      p.vertices.push_back(vertices[loop[k]]);
      if (!normals.empty()) p.normals.push_back(normals[loop[k]]);
      next.push_back(k + 1 < loop.size() ? first + static_cast<int32_t>(k) + 1
                                         : first);
      perimeter +=
          Distance(vertices[loop[k]], vertices[loop[(k + 1) % loop.size()]]);
    }
    if (loops.size() > 1) {
      p.loop_sizes.push_back(static_cast<int32_t>(loop.size()));
    }
  }
  for (const auto& [a, b] : forbidden) {
    auto i = position.find(a), j = position.find(b);
    if (i == position.end() || j == position.end()) continue;
    if (next[i->second] == j->second || next[j->second] == i->second) continue;
    p.forbidden_edges.emplace_back(i->second, j->second);
  }
  std::sort(p.forbidden_edges.begin(), p.forbidden_edges.end());
  p.forbidden_edges.erase(
      std::unique(p.forbidden_edges.begin(), p.forbidden_edges.end()),
      p.forbidden_edges.end());
  p.weights = options.weights;
  // Without a normal at every vertex (the first pass, or a vertex whose
  // patches all failed it) the patch is solved without the normal metric.
  const bool all_normals =
      !p.normals.empty() &&
      std::all_of(p.normals.begin(), p.normals.end(),
                  [](const Vec3& n) { return Norm(n) > 0; });
  if (!all_normals) {
    p.normals.clear();
    p.weights[Metric::kNormalDeviation] = 0;
    if (!HasNonZeroWeight(p.weights)) p.weights[Metric::kArea] = 1;
  }
  if (options.scale_free_weights && perimeter > 0) {
    const double edge = perimeter / static_cast<double>(p.vertices.size());
    p.weights[Metric::kArea] /= edge * edge;
    p.weights[Metric::kPerimeter] /= edge;
  }
  return p;
}

}  // namespace

Status TriangulatePatch(
    const std::vector<Vec3>& vertices,
    const std::vector<std::vector<int32_t>>& loops,
    const std::vector<Vec3>& normals,
    const std::vector<std::pair<int32_t, int32_t>>& forbidden,
    const SurfaceOptions& options, const Control& control, PatchMesh* patch,
    PatchReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<int32_t> ids;
  const Problem problem =
      PatchProblem(vertices, loops, normals, forbidden, options, &ids);
  Options o = options.triangulate;
  o.protect_edges = false;   // a vertex on a curve would split it for one side
  o.reorient_loops = false;  // loops run as the embedding orients them
  // One loop, by default (kAuto): the Delaunay triangles, then (at most
  // all_space_max_vertices points) the optimum over every triangle if it is
  // intersection-free; then, below, every triangle with the Delaunay ones
  // first, and the optimum of bending alone. Several loops: the Delaunay
  // triangles (the multi-loop solver's own fallbacks).
  if (o.space == SearchSpace::kAuto && loops.size() > 1) {
    o.space = SearchSpace::kDelaunay;
  }
  Result r = Triangulate(problem, o, control);
  std::string reasons;
  const bool bent = r.status.code == StatusCode::kNoTriangulation &&
                    loops.size() == 1 && o.space != SearchSpace::kAll &&
                    o.space != SearchSpace::kDelaunayFirst;
  if (bent && static_cast<int>(ids.size()) <= o.delaunay_first_max_vertices) {
    reasons = (o.space == SearchSpace::kAuto &&
                       static_cast<int>(ids.size()) <= o.all_space_max_vertices
                   ? "over the Delaunay triangles, then every triangle: "
                   : "over the Delaunay triangles: ") +
              r.status.message + "; ";
    o.space = SearchSpace::kDelaunayFirst;
    o.validate_output = true;
    r = Triangulate(problem, o, control);
    if (r.status.ok() && r.intersecting_pairs > 0) {
      r.status =
          MakeStatus(StatusCode::kNoTriangulation,
                     "with the Delaunay ones first it crosses itself (" +
                         std::to_string(r.intersecting_pairs) + " pairs)");
    }
  }
  // A short loop whose surfaces under these weights cross themselves may
  // still have one that does not under bending alone (the weights shape
  // only the coarse surface, which refinement and fairing reshape): the
  // optimum of squared dihedral angles over every triangle, taken if it is
  // intersection-free.
  bool bent_alone = false;
  if (bent && r.status.code == StatusCode::kNoTriangulation &&
      static_cast<int>(ids.size()) <= o.all_space_max_vertices) {
    Problem bending = problem;
    bending.weights = {};
    bending.weights[Metric::kSquaredDihedral] = 1;
    bending.normals.clear();
    o.space = SearchSpace::kAll;
    o.validate_output = true;
    Result b = Triangulate(bending, o, control);
    if (b.status.ok() && b.intersecting_pairs == 0) {
      r = std::move(b);
      bent_alone = true;
    } else if (b.status.ok() || b.status.code == StatusCode::kNoTriangulation) {
      reasons += r.status.message + "; ";
      r.status = MakeStatus(
          StatusCode::kNoTriangulation,
          "by bending alone over every triangle " +
              (b.status.ok()
                   ? "it crosses itself (" +
                         std::to_string(b.intersecting_pairs) + " pairs)"
                   : "none either"));
    } else {
      r.status = b.status;  // stopped, or out of memory: as it is
    }
  }
  report->triangulate_ms = MsSince(t0);
  if (!r.status.ok()) {
    if (r.status.code == StatusCode::kNoTriangulation) {
      r.status.message = reasons + r.status.message;
    }
    return r.status;
  }
  // The note says how this solve went (a re-solve may not need bending
  // alone where the first did, or may where it did not).
  const std::string note = kBendingAloneNote;
  const size_t at = report->reason.find(note);
  if (!bent_alone && at != std::string::npos) {
    const size_t from = at >= 2 ? at - 2 : at;  // with its "; " before
    report->reason.erase(from, at - from + note.size());
    if (from == 0 && report->reason.rfind("; ", 0) == 0) {
      report->reason.erase(0, 2);
    }
  } else if (bent_alone && at == std::string::npos) {
    report->reason += (report->reason.empty() ? "" : "; ") + note;
  }
  report->space = r.space_used;
  report->solver = r.solver;
  report->cost = r.total_cost;
  *patch = {};
  for (const Triangle& t : r.triangles) {
    patch->faces.push_back({ids[t[0]], ids[t[1]], ids[t[2]]});
  }
  return OkStatus();
}

Status FanPatch(const std::vector<Vec3>& vertices,
                const std::vector<std::vector<int32_t>>& loops, int32_t centre,
                PatchMesh* patch) {
  if (loops.size() != 1) {
    return MakeStatus(StatusCode::kNoTriangulation,
                      "no fan joins several loops");
  }
  const auto& loop = loops[0];
  Vec3 sum;
  for (int32_t v : loop) sum = sum + vertices[v];
  *patch = {};
  patch->new_vertices = {(1.0 / static_cast<double>(loop.size())) * sum};
  for (size_t k = 0; k < loop.size(); ++k) {
    patch->faces.push_back({loop[k], loop[(k + 1) % loop.size()], centre});
  }
  return OkStatus();
}

Status RefinePatch(const NetworkGraph& graph, const SurfaceOptions& options,
                   const Control& control, int32_t first_new, size_t cap,
                   PatchMesh* patch, PatchReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  RunTicker ticker(control, "refinement");
  if (!ticker.Poll()) return ticker.status();

  // Local numbering, moved to the origin and scaled to unit size (as
  // FillHoles refines: no underflow at tiny coordinates). The faces of a
  // seam patch's piece 1 have their own copies of its vertices (keyed ~v):
  // refined apart, the two pieces keep the seam and the new path as borders
  // (with edges of both pieces around them, Liepa's scale would be the
  // long chords').
  auto key = [&](size_t f, int32_t v) {
    return !patch->piece.empty() && patch->piece[f] == 1 ? ~v : v;
  };
  std::map<int32_t, int32_t> local;
  std::vector<int32_t> global;
  for (size_t f = 0; f < patch->faces.size(); ++f) {
    for (int32_t v : patch->faces[f]) {
      if (local.emplace(key(f, v), static_cast<int32_t>(global.size()))
              .second) {
        global.push_back(v);
      }
    }
  }
  auto position = [&](int32_t id) -> const Vec3& {
    return id < first_new ? graph.vertices[id]
                          : patch->new_vertices[id - first_new];
  };
  Vec3 lo = position(global[0]), hi = lo;
  for (int32_t id : global) {
    const Vec3& p = position(id);
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const Vec3 center = 0.5 * (lo + hi);
  const double size = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  const double scale = size > 0 && std::isfinite(1.0 / size) ? 1.0 / size : 1;
  SurfaceMesh sm;
  for (int32_t id : global) {
    const Vec3 p = scale * (position(id) - center);
    sm.add_vertex(K::Point_3(p.x, p.y, p.z));
  }
  std::vector<FaceIndex> faces;
  for (size_t k = 0; k < patch->faces.size(); ++k) {
    const Triangle& t = patch->faces[k];
    const FaceIndex f = sm.add_face(VertexIndex(local[key(k, t[0])]),
                                    VertexIndex(local[key(k, t[1])]),
                                    VertexIndex(local[key(k, t[2])]));
    if (f == SurfaceMesh::null_face()) {
      report->reason = "not refined: the patch is not a manifold surface";
      return OkStatus();
    }
    faces.push_back(f);
  }
  // The original vertices, by the slot they had (remeshing may free and
  // reuse slots).
  auto original = sm.add_property_map<VertexIndex, int32_t>("v:dot", -1).first;
  for (VertexIndex v : sm.vertices()) {
    original[v] = static_cast<int32_t>(v.idx());
  }
  bool interior = false;  // a fan's centre
  double longest = 0, area = 0;
  for (VertexIndex v : sm.vertices()) interior = interior || !sm.is_border(v);
  for (FaceIndex f : faces) {
    area += CGAL::to_double(PMP::face_area(f, sm));
  }
  for (auto h : sm.halfedges()) {
    if (sm.is_border(h)) {
      longest = std::max(
          longest, std::sqrt(CGAL::to_double(PMP::squared_edge_length(h, sm))));
    }
  }
  if (interior) {
    // Isotropic remeshing needs a valid manifold mesh of proper triangles
    // (network_fuzz crashed it inside CGAL with less), ...
    bool fit = CGAL::is_valid_polygon_mesh(sm);
    for (VertexIndex v : sm.vertices()) {
      fit = fit && !PMP::is_non_manifold_vertex(v, sm);
    }
    for (FaceIndex f : faces) {
      fit = fit && !PMP::is_degenerate_triangle_face(f, sm);
    }
    // ... nor edges a millionth of the patch's size (coordinates far
    // apart in magnitude: one crashed it too).
    for (auto e : sm.edges()) {
      fit = fit && PMP::edge_length(e, sm) > 1e-6;
    }
    if (!fit) {
      report->reason += std::string(report->reason.empty() ? "" : "; ") +
                        "not refined: a pinched vertex, a flat triangle or "
                        "an edge a millionth of the patch";
      return OkStatus();
    }
  }
  std::vector<FaceIndex> new_faces;
  std::vector<VertexIndex> new_vertices;
  try {
    if (interior) {
      // Liepa's scale at a vertex is its edges' mean length, the spokes of
      // a fan included once any vertex is inside: it would barely refine.
      // Isotropic remeshing to the curves' spacing (every border edge at
      // most 4/3 of the target, so none is split) instead.
      const double target = 0.75 * longest * (1 + 1e-9);
      const double estimate = area / (0.433 * target * target);
      // At most 100,000 new vertices: about a second per iteration.
      if (target <= 0 || estimate > std::min(static_cast<double>(cap), 1e5)) {
        throw StopRefining{OkStatus()};
      }
      // One iteration at a time, polled between (CGAL's remesher has no
      // stop of its own).
      for (int iteration = 0; iteration < 3; ++iteration) {
        PMP::isotropic_remeshing(
            faces, target, sm,
            CGAL::parameters::number_of_iterations(1).protect_constraints(
                true));
        if (!ticker.Poll()) return ticker.status();
        faces.assign(sm.faces().begin(), sm.faces().end());
      }
      for (VertexIndex v : sm.vertices()) {
        if (original[v] < 0) new_vertices.push_back(v);
      }
    } else {
      PMP::refine(sm, faces, std::back_inserter(new_faces),
                  CountingVertexOut<VertexIndex>{&new_vertices, cap, &ticker},
                  CGAL::parameters::density_control_factor(options.density));
    }
  } catch (const StopRefining& stop) {
    if (!stop.status.ok()) return stop.status;
    report->refine_ms = MsSince(t0);
    report->reason = "refinement stopped past " + std::to_string(cap) +
                     " new vertices, this patch's share of the memory "
                     "budget: kept the unrefined patch";
    return OkStatus();
  }
  // Curve vertices keep their ids; the patch's own (a fan's centre, a
  // seam's new path, and what refinement added) are numbered anew, both
  // copies of one alike.
  std::vector<int32_t> id_of(sm.num_vertices());
  std::map<int32_t, int32_t> renumbered;
  PatchMesh refined;
  for (VertexIndex v : sm.vertices()) {
    const int32_t was = original[v];
    if (was >= 0 && global[was] < first_new) {
      id_of[v.idx()] = global[was];
      continue;
    }
    if (was >= 0) {  // both copies of one alike
      const auto [it, added] = renumbered.emplace(
          global[was],
          first_new + static_cast<int32_t>(refined.new_vertices.size()));
      id_of[v.idx()] = it->second;
      if (!added) continue;
      if (!interior) {  // Liepa moves no vertex: exactly where it was
        refined.new_vertices.push_back(position(global[was]));
        continue;
      }
    }
    id_of[v.idx()] =
        first_new + static_cast<int32_t>(refined.new_vertices.size());
    const auto& p = sm.point(v);
    refined.new_vertices.push_back(center +
                                   (1.0 / scale) * Vec3{p.x(), p.y(), p.z()});
  }
  for (FaceIndex f : sm.faces()) {
    Triangle t;
    int k = 0;
    for (VertexIndex v : sm.vertices_around_face(sm.halfedge(f))) {
      t[k++] = id_of[v.idx()];
    }
    refined.faces.push_back(t);
  }
  *patch = std::move(refined);
  report->refined_vertices = static_cast<int32_t>(new_vertices.size());
  report->refine_ms = MsSince(t0);
  return OkStatus();
}

}  // namespace dot

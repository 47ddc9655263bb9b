// SPDX-License-Identifier: AGPL-3.0-or-later
// Liepa refinement and fairing of one patch with CGAL's Polygon Mesh
// Processing (refine, fair: Eigen's sparse LU, fair_solver.h), on a small
// surface mesh made of the patch and three rings of faces around it: enough for
// the fixed neighbours of a Laplacian of order up to 3, and never the whole
// mesh.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/fair.h>
#include <CGAL/Polygon_mesh_processing/refine.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unordered_map>

#include "dot/fill_holes.h"
#include "fill/fair_solver.h"
#include "fill/patch_check.h"
#include "fill/refine_limits.h"
#include "mesh/topology.h"
#include "util/run_control.h"

namespace dot {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
using FaceIndex = SurfaceMesh::Face_index;
namespace PMP = CGAL::Polygon_mesh_processing;

constexpr int kRings = 3;

// The patch's neighbourhood: local vertex numbering and context faces.
struct Neighbourhood {
  std::vector<int32_t> global;  // local -> global id
  std::unordered_map<int32_t, int32_t> local;
  std::vector<Triangle> context;  // global ids
  std::vector<Triangle> patch;    // global ids

  int32_t Local(int32_t id) {
    auto [it, added] = local.emplace(id, static_cast<int32_t>(global.size()));
    if (added) global.push_back(id);
    return it->second;
  }
};

Neighbourhood Gather(const MeshData& mesh, const MeshTopology& topo,
                     int32_t first_new_id, const HolePatch& patch) {
  Neighbourhood nb;
  std::unordered_map<int32_t, const std::vector<Triangle>*> split;
  for (size_t k = 0; k < patch.split_faces.size(); ++k) {
    split[patch.split_faces[k]] = &patch.pieces[k];
  }
  std::vector<int32_t> frontier, faces;
  for (const Triangle& t : patch.faces) {
    for (int32_t v : t) {
      if (v < first_new_id) frontier.push_back(v);
    }
  }
  std::unordered_map<int32_t, bool> taken_face, taken_vertex;
  for (int ring = 0; ring < kRings && !frontier.empty(); ++ring) {
    std::vector<int32_t> next;
    for (int32_t v : frontier) {
      if (!taken_vertex.emplace(v, true).second) continue;
      for (int32_t k = topo.face_begin[v]; k < topo.face_begin[v + 1]; ++k) {
        const int32_t f = topo.faces[k];
        if (!taken_face.emplace(f, true).second) continue;
        faces.push_back(f);
        for (int32_t w : mesh.triangles[f]) next.push_back(w);
      }
    }
    frontier.swap(next);
  }
  std::sort(faces.begin(), faces.end());
  for (int32_t f : faces) {
    auto it = split.find(f);
    if (it == split.end()) {
      nb.context.push_back(mesh.triangles[f]);
    } else {
      nb.context.insert(nb.context.end(), it->second->begin(),
                        it->second->end());
    }
  }
  nb.patch = patch.faces;
  for (const auto* set : {&nb.patch, &nb.context}) {
    for (const Triangle& t : *set) {
      for (int32_t v : t) nb.Local(v);
    }
  }
  return nb;
}

// The patch as mesh ids once refine/fair changed `sm`: gathered vertices
// keep their ids (and an inserted boundary vertex its position), vertices
// beyond them are new.
template <typename Unscale>
void ExtractPatch(const SurfaceMesh& sm,
                  const SurfaceMesh::Property_map<FaceIndex, bool>& is_context,
                  const std::vector<int32_t>& global, int32_t first_new_id,
                  const Unscale& unscale, HolePatch* patch) {
  const size_t known = global.size();
  std::vector<int32_t> id_of(sm.number_of_vertices());
  for (VertexIndex v : sm.vertices()) {
    if (v.idx() < known) {
      id_of[v.idx()] = global[v.idx()];
    } else {
      id_of[v.idx()] =
          first_new_id + static_cast<int32_t>(patch->new_vertices.size());
      patch->new_vertices.push_back(unscale(sm.point(v)));
    }
  }
  patch->faces.clear();
  for (FaceIndex f : sm.faces()) {
    if (is_context[f]) continue;
    Triangle t;
    int k = 0;
    for (VertexIndex v : sm.vertices_around_face(sm.halfedge(f))) {
      t[k++] = id_of[v.idx()];
    }
    patch->faces.push_back(t);
  }
}

}  // namespace

Status RefineAndFairPatch(const MeshData& mesh, const MeshTopology& topology,
                          const FillOptions& options, const Control& control,
                          int32_t first_new_id, HolePatch* patch,
                          HoleReport* report) {
  if (options.stage == FillStage::kTriangulate) return OkStatus();
  RunTicker ticker(control, "refinement and fairing");
  if (!ticker.Poll()) return ticker.status();
  auto t0 = std::chrono::steady_clock::now();
  Neighbourhood nb = Gather(mesh, topology, first_new_id, *patch);
  auto original = [&](int32_t id) -> const Vec3& {
    return id < first_new_id ? mesh.vertices[id]
                             : patch->new_vertices[id - first_new_id];
  };
  // Refinement and fairing run on the neighbourhood moved to the origin and
  // scaled to unit size: at coordinates around 1e-150 fairing's system
  // underflowed into NaN vertices. New vertices are mapped back.
  Box3 box;
  for (int32_t id : nb.global) box.Add(original(id));
  const Vec3 center = 0.5 * (box.lo + box.hi);
  const double size =
      std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y,
                box.hi.z - box.lo.z});  // no squares: no underflow
  const double scale = size > 0 && std::isfinite(1.0 / size) ? 1.0 / size : 1.0;
  auto point = [&](int32_t id) {
    const Vec3 p = scale * (original(id) - center);
    return K::Point_3(p.x, p.y, p.z);
  };
  auto unscale = [&](const K::Point_3& p) {
    return center + (1.0 / scale) * Vec3{p.x(), p.y(), p.z()};
  };
  SurfaceMesh sm;
  for (int32_t id : nb.global) sm.add_vertex(point(id));
  auto [is_context, created] =
      sm.add_property_map<FaceIndex, bool>("f:context", false);
  auto add = [&](const Triangle& t) {
    return sm.add_face(VertexIndex(nb.local[t[0]]), VertexIndex(nb.local[t[1]]),
                       VertexIndex(nb.local[t[2]]));
  };
  for (const Triangle& t : nb.context) {
    const FaceIndex f = add(t);
    if (f == SurfaceMesh::null_face()) {
      report->reason =
          "not refined: the faces around the hole do not form a "
          "manifold surface";
      return OkStatus();
    }
    is_context[f] = true;
  }
  std::vector<FaceIndex> patch_faces;
  for (const Triangle& t : nb.patch) {
    const FaceIndex f = add(t);
    if (f == SurfaceMesh::null_face()) {
      report->reason =
          "not refined: the patch does not join the surface as a "
          "manifold";
      return OkStatus();
    }
    patch_faces.push_back(f);
  }
  std::vector<FaceIndex> new_faces;
  std::vector<VertexIndex> new_vertices;
  const size_t cap =
      RefinedVertexCap(static_cast<size_t>(report->boundary_vertices),
                       options.triangulate.memory_budget_bytes);
  try {
    PMP::refine(sm, patch_faces, std::back_inserter(new_faces),
                CountingVertexOut<VertexIndex>{&new_vertices, cap, &ticker},
                CGAL::parameters::density_control_factor(options.density));
  } catch (const StopRefining& stop) {
    if (!stop.status.ok()) return stop.status;
    report->refine_ms = MsSince(t0);
    report->reason = "refinement stopped past " + std::to_string(cap) +
                     " new vertices, the most allowed for a hole of " +
                     std::to_string(report->boundary_vertices) +
                     " boundary vertices within the memory budget (density " +
                     std::to_string(options.density) +
                     "): kept the unrefined DOT patch";
    report->patch_triangles = static_cast<int32_t>(patch->faces.size());
    return OkStatus();
  }
  report->refine_ms = MsSince(t0);
  report->refined_vertices = static_cast<int32_t>(new_vertices.size());
  if (!ticker.Poll()) return ticker.status();

  const HolePatch unrefined = *patch;
  ExtractPatch(sm, is_context, nb.global, first_new_id, unscale, patch);
  if (options.stage == FillStage::kFair && !new_vertices.empty()) {
    t0 = std::chrono::steady_clock::now();
    std::vector<K::Point_3> refined;
    for (VertexIndex v : new_vertices) refined.push_back(sm.point(v));
    const FairSolver solver(control, &ticker);
    report->faired = PMP::fair(
        sm, new_vertices,
        CGAL::parameters::fairing_continuity(options.fairing_continuity)
            .sparse_linear_solver(solver));
    report->fair_ms = MsSince(t0);
    if (solver.stopped()) return solver.stop_status();
    if (!report->faired) {
      report->reason = "fairing failed (" +
                       (solver.error().empty() ? std::string("singular system")
                                               : solver.error()) +
                       "): kept the refined patch";
    } else {
      HolePatch faired = unrefined;
      ExtractPatch(sm, is_context, nb.global, first_new_id, unscale, &faired);
      if (!ticker.Poll()) return ticker.status();
      int64_t pairs = 0;
      const Status s = PatchIntersections(mesh, topology, first_new_id, faired,
                                          control, &pairs);
      if (!s.ok()) return s;
      if (pairs == 0) {
        *patch = std::move(faired);
      } else {
        report->faired = false;
        report->reason = "fairing undone: it made " + std::to_string(pairs) +
                         " pairs of faces intersect; kept the refined patch";
      }
    }
  }
  report->patch_triangles = static_cast<int32_t>(patch->faces.size());
  return OkStatus();
}

}  // namespace dot

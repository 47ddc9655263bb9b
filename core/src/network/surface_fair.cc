// SPDX-License-Identifier: AGPL-3.0-or-later
// Fairing of a whole network's surface at once (CGAL's fair(): Laplacian
// energy of order continuity + 1 with cotangent weights, solved by the
// stoppable FairSolver). One system over every patch: the free vertices on
// both sides of a curve see each other through the curve's Laplacians, so
// the patches meet without a crease where the curves allow it.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/fair.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>

#include "fill/fair_solver.h"
#include "network/surface_steps.h"
#include "util/run_control.h"

namespace dot {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
namespace PMP = CGAL::Polygon_mesh_processing;

}  // namespace

Status FairMesh(MeshData* mesh, int32_t first_free,
                const std::vector<char>& fixed, int continuity,
                const Control& control, bool* faired, std::string* why) {
  *faired = false;
  why->clear();
  RunTicker ticker(control, "fairing");
  if (!ticker.Poll()) return ticker.status();
  Vec3 lo = mesh->vertices.empty() ? Vec3{} : mesh->vertices[0], hi = lo;
  for (const Vec3& p : mesh->vertices) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const Vec3 center = 0.5 * (lo + hi);
  const double size = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  const double scale = size > 0 && std::isfinite(1.0 / size) ? 1.0 / size : 1;
  SurfaceMesh sm;
  for (const Vec3& v : mesh->vertices) {
    const Vec3 p = scale * (v - center);
    sm.add_vertex(K::Point_3(p.x, p.y, p.z));
  }
  for (const Triangle& t : mesh->triangles) {
    if (sm.add_face(VertexIndex(t[0]), VertexIndex(t[1]), VertexIndex(t[2])) ==
        SurfaceMesh::null_face()) {
      *why =
          "the patches do not form one manifold, consistently oriented "
          "surface";
      return OkStatus();
    }
  }
  std::vector<VertexIndex> free;
  for (size_t v = static_cast<size_t>(first_free); v < mesh->vertices.size();
       ++v) {
    if (fixed.empty() || !fixed[v]) free.push_back(VertexIndex(v));
  }
  if (free.empty()) return OkStatus();
  const FairSolver solver(control, &ticker);
  const bool ok = PMP::fair(sm, free,
                            CGAL::parameters::fairing_continuity(continuity)
                                .sparse_linear_solver(solver));
  if (solver.stopped()) return solver.stop_status();
  if (!ok) {
    *why = "fairing failed (" +
           (solver.error().empty() ? std::string("singular system")
                                   : solver.error()) +
           ")";
    return OkStatus();
  }
  for (VertexIndex v : free) {
    const auto& p = sm.point(v);
    const Vec3 q = center + (1.0 / scale) * Vec3{p.x(), p.y(), p.z()};
    if (!IsFinite(q)) {
      *why = "fairing gave a vertex that is not finite";
      return OkStatus();
    }
  }
  for (VertexIndex v : free) {
    const auto& p = sm.point(v);
    mesh->vertices[v.idx()] =
        center + (1.0 / scale) * Vec3{p.x(), p.y(), p.z()};
  }
  *faired = true;
  return OkStatus();
}

}  // namespace dot

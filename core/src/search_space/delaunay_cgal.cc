// SPDX-License-Identifier: AGPL-3.0-or-later
// The CGAL Delaunay backend: exact predicates, re-entrant, and inserted one
// point at a time in spatial-sort order (what CGAL's range insert does), so
// cancel and deadline are honoured inside the tetrahedralization too.
#include "search_space/delaunay_cgal.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <new>
#include <utility>

#include "util/run_control.h"

namespace dot {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int32_t, Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_3<VertexBase>;
using Delaunay3 = CGAL::Delaunay_triangulation_3<Kernel, DataStructure>;
using IndexedPoint = std::pair<Kernel::Point_3, int32_t>;

Status Triangulate3(const std::vector<Vec3>& points, const Control& control,
                    Delaunay3* dt) {
  std::vector<IndexedPoint> sorted;
  sorted.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    sorted.emplace_back(Kernel::Point_3(p.x, p.y, p.z),
                        static_cast<int32_t>(i));
  }
  using Traits = CGAL::Spatial_sort_traits_adapter_3<
      Kernel, CGAL::First_of_pair_property_map<IndexedPoint>>;
  CGAL::spatial_sort(sorted.begin(), sorted.end(), Traits());

  RunTicker ticker(control, Stage::kDelaunay);
  const double count = static_cast<double>(sorted.size());
  Delaunay3::Cell_handle hint;
  for (size_t k = 0; k < sorted.size(); ++k) {
    // One insertion can cost thousands of new cells on cospherical input.
    if (k % 64 == 0 && !ticker.Poll(static_cast<double>(k) / count)) {
      return ticker.status();
    }
    const Delaunay3::Vertex_handle v = dt->insert(sorted[k].first, hint);
    v->info() = sorted[k].second;
    hint = v->cell();
  }
  if (dt->number_of_vertices() != points.size()) {
    return InvalidArgument(
        std::to_string(points.size() - dt->number_of_vertices()) +
        " vertices coincide with others");
  }
  if (dt->dimension() < 3) {
    return InvalidArgument("the polygon's vertices are coplanar");
  }
  return OkStatus();
}

}  // namespace

Status CgalDelaunayFaces(const std::vector<Vec3>& points,
                         const Control& control, std::vector<Triangle>* faces,
                         int64_t* tetrahedra) {
  try {
    Delaunay3 dt;
    Status s = Triangulate3(points, control, &dt);
    if (!s.ok()) return s;
    *tetrahedra = static_cast<int64_t>(dt.number_of_finite_cells());
    faces->clear();
    faces->reserve(2 * dt.number_of_cells());
    RunTicker ticker(control, Stage::kDelaunay);
    for (auto f = dt.finite_facets_begin(); f != dt.finite_facets_end(); ++f) {
      if (!ticker.Tick()) return ticker.status();
      const Delaunay3::Cell_handle c = f->first;
      const int i = f->second;
      Triangle t = {c->vertex((i + 1) & 3)->info(),
                    c->vertex((i + 2) & 3)->info(),
                    c->vertex((i + 3) & 3)->info()};
      std::sort(t.begin(), t.end());
      faces->push_back(t);
    }
    return OkStatus();
  } catch (const std::bad_alloc&) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "CGAL's Delaunay tetrahedralization ran out of memory "
                      "on " +
                          std::to_string(points.size()) + " points");
  }
}

}  // namespace dot

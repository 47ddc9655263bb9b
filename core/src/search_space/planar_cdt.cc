// SPDX-License-Identifier: AGPL-3.0-or-later
// Planar polygons: CGAL's 2D constrained Delaunay triangulation, in the
// coordinate plane closest to the polygon's plane (paper, Lemma 4.4).
#include "search_space/planar_cdt.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <optional>
#include <utility>

namespace dot {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = K::Point_2;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int32_t, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
    K, Tds, CGAL::No_constraint_intersection_tag>;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, int32_t>;

Point2 Project(const Vec3& p, int drop_axis) {
  switch (drop_axis) {
    case 0:
      return {p.y, p.z};
    case 1:
      return {p.z, p.x};
    default:
      return {p.x, p.y};
  }
}

// The first pair (lowest indices) of polygon edges that meet other than at a
// shared endpoint, decided exactly; edge i runs from vertex i to i + 1.
std::optional<std::pair<int32_t, int32_t>> FindCrossingEdges(
    const std::vector<Point2>& p, const std::vector<int32_t>& successor) {
  const auto n = static_cast<int32_t>(p.size());
  auto next = [&](int32_t i) { return successor[i]; };
  std::vector<Box> boxes;
  boxes.reserve(n);
  for (int32_t i = 0; i < n; ++i) {
    boxes.emplace_back(p[i].bbox() + p[next(i)].bbox(), i);
  }
  std::optional<std::pair<int32_t, int32_t>> found;
  auto report = [&](int32_t a, int32_t b) {
    const std::pair<int32_t, int32_t> pair = std::minmax(a, b);
    if (!found || pair < *found) found = pair;
  };
  CGAL::box_self_intersection_d(
      boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
        const int32_t i = x.info(), j = y.info();
        if (next(i) == j || next(j) == i) {
          // Adjacent edges overlap only when they fold back along one line.
          const int32_t a = next(i) == j ? i : j, b = next(a), c = next(b);
          if (CGAL::orientation(p[a], p[b], p[c]) == CGAL::COLLINEAR &&
              !CGAL::collinear_are_strictly_ordered_along_line(p[a], p[b],
                                                               p[c])) {
            report(i, j);
          }
          return;
        }
        if (CGAL::do_intersect(K::Segment_2(p[i], p[next(i)]),
                               K::Segment_2(p[j], p[next(j)]))) {
          report(i, j);
        }
      });
  return found;
}

}  // namespace

Status PlanarCdtTriangles(const std::vector<Vec3>& loop,
                          const std::vector<int32_t>& next, int drop_axis,
                          std::vector<Triangle>* triangles) {
  const auto n = static_cast<int32_t>(loop.size());
  std::vector<Point2> p;
  p.reserve(n);
  for (const Vec3& v : loop) p.push_back(Project(v, drop_axis));
  if (auto crossing = FindCrossingEdges(p, next)) {
    const auto [i, j] = *crossing;
    return InvalidArgument("planar polygon is self-intersecting: edge " +
                           std::to_string(i) + "-" + std::to_string(next[i]) +
                           " meets edge " + std::to_string(j) + "-" +
                           std::to_string(next[j]));
  }
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles(n);
  try {
    for (int32_t i = 0; i < n; ++i) {
      handles[i] = cdt.insert(p[i]);
      handles[i]->info() = i;
    }
    for (int32_t i = 0; i < n; ++i) {
      cdt.insert_constraint(handles[i], handles[next[i]]);
    }
  } catch (const std::exception& e) {
    return InvalidArgument(
        std::string("planar polygon is self-intersecting (") + e.what() + ")");
  }
  if (static_cast<int32_t>(cdt.number_of_vertices()) != n) {
    return InvalidArgument(
        "planar polygon has two vertices at one point of its "
        "plane");
  }
  triangles->clear();
  triangles->reserve(cdt.number_of_faces());
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    Triangle t = {f->vertex(0)->info(), f->vertex(1)->info(),
                  f->vertex(2)->info()};
    std::sort(t.begin(), t.end());
    triangles->push_back(t);
  }
  std::sort(triangles->begin(), triangles->end());
  return OkStatus();
}

}  // namespace dot

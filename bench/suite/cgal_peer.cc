// SPDX-License-Identifier: AGPL-3.0-or-later
#include "cgal_peer.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include <iterator>

namespace dot::bench {

std::vector<Triangle> CgalFillHole(const std::vector<Vec3>& loop) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<Kernel::Point_3> points;
  points.reserve(loop.size());
  for (const Vec3& p : loop) points.emplace_back(p.x, p.y, p.z);
  std::vector<CGAL::Triple<int, int, int>> patch;
  CGAL::Polygon_mesh_processing::triangulate_hole_polyline(
      points, std::back_inserter(patch),
      CGAL::parameters::use_delaunay_triangulation(true)
          .do_not_use_cubic_algorithm(true));
  std::vector<Triangle> out;
  out.reserve(patch.size());
  for (const auto& t : patch) out.push_back({t.first, t.second, t.third});
  return out;
}

}  // namespace dot::bench

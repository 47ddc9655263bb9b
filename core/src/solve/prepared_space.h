// SPDX-License-Identifier: AGPL-3.0-or-later
// Everything about a search space that does not depend on the metric
// weights: what SpaceCache keeps between solves.
#ifndef DOT_CORE_SEARCH_SPACE_PREPARED_SPACE_H_
#define DOT_CORE_SEARCH_SPACE_PREPARED_SPACE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "dot/control.h"
#include "dot/problem.h"
#include "polygon/polygon_loop.h"
#include "solve/adjacency.h"

namespace dot {

struct PreparedSpace {
  PolygonLoop loop;                 // after edge protection
  std::vector<Triangle> triangles;  // candidates over loop positions
  SpaceUsed space = SpaceUsed::kNone;
  Adjacency adjacency;
  std::vector<Vec3> unit_normals;  // per candidate; empty unless needed
  int64_t tetrahedra = 0;
  int64_t delaunay_triangles = 0;

  int64_t Bytes() const;
};

// The cache key of a problem's search space: its exact coordinates and
// normals, and every option that shapes the space.
std::string SpaceCacheKey(const Problem& problem, const Options& options);

}  // namespace dot

#endif  // DOT_CORE_SEARCH_SPACE_PREPARED_SPACE_H_

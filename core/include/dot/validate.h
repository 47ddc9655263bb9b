// SPDX-License-Identifier: AGPL-3.0-or-later
// Checks a triangle set against the polygon it should span. Used on every
// output in the tests, and by callers who want proof rather than trust.
#ifndef DOT_VALIDATE_H_
#define DOT_VALIDATE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "dot/control.h"
#include "dot/geometry.h"
#include "dot/mesh.h"
#include "dot/status.h"

namespace dot {

struct MeshReport {
  bool indices_in_range = false;
  int64_t degenerate_triangles = 0;  // repeated index or zero area (exact)
  int64_t non_manifold_edges = 0;    // edges on more than two triangles
  int64_t misoriented_edges = 0;     // interior edges used twice the same way
  bool boundary_is_polygon = false;  // boundary edges == polygon edges
  // Connected, manifold vertices, Euler characteristic 2 - loops: a disk for
  // one loop, a sphere with that many holes for several.
  bool disk = false;
  // Pairs of triangles meeting other than in a shared edge or vertex, decided
  // with exact predicates; -1 when not computed.
  int64_t intersecting_pairs = -1;
  std::string first_problem;  // human-readable, empty when valid
  bool valid() const { return first_problem.empty(); }
};

// `polygon` lists the loop as indices into `vertices`.
MeshReport ValidateMesh(const std::vector<Vec3>& vertices,
                        const std::vector<int32_t>& polygon,
                        const std::vector<Triangle>& triangles,
                        bool check_intersections = true);
// Several loops (Result::polygon cut by Result::loop_sizes): the boundary
// must be exactly their edges, each loop's edges running its way in the
// triangles (or every loop's the other way), on a surface of genus 0.
MeshReport ValidateSurface(const std::vector<Vec3>& vertices,
                           const std::vector<std::vector<int32_t>>& loops,
                           const std::vector<Triangle>& triangles,
                           bool check_intersections = true);

// The topology of a triangle mesh over the vertices its faces use: its
// pieces (faces joined by shared vertices) and its Euler characteristic
// V - E + F (2 - 2 genus - borders per closed-up piece, summed).
struct MeshShape {
  int64_t pieces = 0;
  int64_t euler = 0;
};
MeshShape ShapeOf(const MeshData& mesh);

// Number of triangle pairs that intersect other than along a shared edge or
// at a shared vertex (exact predicates, box-intersection candidate pairs).
// Only pairs with at least one triangle among the first `checked` count
// (for example a new patch against its surroundings).
int64_t CountIntersectingPairs(const std::vector<Vec3>& vertices,
                               const std::vector<Triangle>& triangles,
                               size_t checked = SIZE_MAX);
// The same, polling `control` as it goes (a patch of 40,000 faces takes
// about a second): kCancelled or kDeadlineExceeded, with `pairs` unset, when
// it says stop.
Status CountIntersectingPairs(const std::vector<Vec3>& vertices,
                              const std::vector<Triangle>& triangles,
                              size_t checked, const Control& control,
                              int64_t* pairs);
// The pairs themselves (triangle indices, the smaller first), in no
// particular order.
Status ListIntersectingPairs(const std::vector<Vec3>& vertices,
                             const std::vector<Triangle>& triangles,
                             size_t checked, const Control& control,
                             std::vector<std::pair<int32_t, int32_t>>* pairs);

// The symmetric Hausdorff distance between two triangle meshes, to within
// `error_bound` (CGAL's bounded-error algorithm, Polygon Mesh Processing):
// how far a surface strays from a reference. kInvalidArgument when either
// mesh has no face or is not an oriented 2-manifold with boundary.
Status HausdorffDistance(const MeshData& a, const MeshData& b,
                         double error_bound, double* distance);

}  // namespace dot

#endif  // DOT_VALIDATE_H_

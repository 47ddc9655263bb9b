// SPDX-License-Identifier: AGPL-3.0-or-later
// Mesh validation, in steps: index ranges, degenerate triangles, edges
// (from the edge index), boundary, disk topology, self-intersections.
// Intersections use CGAL's box intersection for candidate pairs and exact
// predicates (Epick) for the test itself, so "intersection-free" is a
// proof, not a tolerance.
#include "dot/validate.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "mesh/edge_index.h"
#include "util/run_control.h"
#include "util/union_find.h"

namespace dot {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P3 = K::Point_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int32_t>;

P3 ToPoint(const Vec3& v) { return {v.x, v.y, v.z}; }

// Do triangles s and t intersect anywhere but in the vertices and edge they
// share? `shared` counts their common vertices.
bool Overlaps(const std::vector<P3>& p, const Triangle& s, const Triangle& t) {
  int shared = 0;
  for (int32_t a : s)
    for (int32_t b : t) shared += a == b;
  const K::Triangle_3 ts(p[s[0]], p[s[1]], p[s[2]]);
  const K::Triangle_3 tt(p[t[0]], p[t[1]], p[t[2]]);
  if (shared == 0) return CGAL::do_intersect(ts, tt);
  auto rest = [](const Triangle& x, const Triangle& y) {  // x minus y
    std::vector<int32_t> r;
    for (int32_t a : x)
      if (std::find(y.begin(), y.end(), a) == y.end()) r.push_back(a);
    return r;
  };
  const std::vector<int32_t> rs = rest(s, t), rt = rest(t, s);
  if (shared == 1) {
    // They meet beyond the shared vertex iff the edge opposite it in one
    // triangle meets the other triangle (see the contract in validate.h).
    return CGAL::do_intersect(K::Segment_3(p[rs[0]], p[rs[1]]), tt) ||
           CGAL::do_intersect(K::Segment_3(p[rt[0]], p[rt[1]]), ts);
  }
  if (shared == 2) {
    // Sharing an edge, they overlap only when folded onto one plane.
    std::vector<int32_t> common;
    for (int32_t a : s)
      if (std::find(t.begin(), t.end(), a) != t.end()) common.push_back(a);
    const P3 &a = p[common[0]], &b = p[common[1]], &c = p[rs[0]], &d = p[rt[0]];
    return CGAL::orientation(a, b, c, d) == CGAL::COPLANAR &&
           CGAL::coplanar_orientation(a, b, c, d) == CGAL::POSITIVE;
  }
  return true;  // the same triangle twice
}

void NoteProblem(const std::string& what, MeshReport* r) {
  if (r->first_problem.empty()) r->first_problem = what;
}

bool IndicesInRange(int32_t vertex_count, const std::vector<int32_t>& polygon,
                    const std::vector<Triangle>& triangles) {
  bool ok = true;
  for (const Triangle& t : triangles) {
    for (int32_t v : t) ok &= v >= 0 && v < vertex_count;
  }
  for (int32_t v : polygon) ok &= v >= 0 && v < vertex_count;
  return ok;
}

// A repeated index or three exactly collinear corners.
void CountDegenerate(const std::vector<Vec3>& vertices,
                     const std::vector<Triangle>& triangles, MeshReport* r) {
  for (size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& t = triangles[i];
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (repeated ||
        CGAL::collinear(ToPoint(vertices[t[0]]), ToPoint(vertices[t[1]]),
                        ToPoint(vertices[t[2]]))) {
      ++r->degenerate_triangles;
      NoteProblem("triangle " + std::to_string(i) + " is degenerate", r);
    }
  }
}

// What the pass over edges finds besides the report's counters.
struct EdgeFindings {
  int64_t edges = 0;
  std::vector<std::pair<int32_t, int32_t>> boundary;  // directed sides
  std::vector<int32_t> joins;  // per vertex: interior edges at it
};

// Each edge is on one triangle (boundary), two with opposite directions
// (interior), or else is misoriented or non-manifold.
EdgeFindings CheckEdges(size_t vertex_count,
                        const std::vector<Triangle>& triangles,
                        UnionFind* components, MeshReport* r) {
  EdgeFindings f;
  f.joins.assign(vertex_count, 0);
  ForEachEdge(BuildEdgeIndex(triangles), [&](const EdgeUses& edge) {
    ++f.edges;
    const std::string name =
        std::to_string(edge.lo()) + "-" + std::to_string(edge.hi());
    if (edge.size() == 1) {
      f.boundary.emplace_back(edge[0].from(), edge[0].to());
    } else if (edge.size() == 2) {
      if (edge[0].from() == edge[1].from()) {
        ++r->misoriented_edges;
        NoteProblem("edge " + name + " is used twice in the same direction", r);
      }
      components->Join(edge[0].triangle, edge[1].triangle);
      ++f.joins[edge.lo()];
      ++f.joins[edge.hi()];
    } else {
      ++r->non_manifold_edges;
      NoteProblem("edge " + name + " is on " + std::to_string(edge.size()) +
                      " triangles",
                  r);
    }
  });
  return f;
}

// The boundary must be exactly the loops' edges, all in their direction or
// all against it.
void CheckBoundary(const std::vector<std::vector<int32_t>>& loops,
                   std::vector<std::pair<int32_t, int32_t>> boundary,
                   MeshReport* r) {
  int32_t n = 0;
  std::vector<std::pair<int32_t, int32_t>> forward, backward;
  for (const std::vector<int32_t>& polygon : loops) {
    const auto size = static_cast<int32_t>(polygon.size());
    n += size;
    for (int32_t i = 0; i < size; ++i) {
      forward.emplace_back(polygon[i], polygon[(i + 1) % size]);
      backward.emplace_back(polygon[(i + 1) % size], polygon[i]);
    }
  }
  std::sort(boundary.begin(), boundary.end());
  std::sort(forward.begin(), forward.end());
  std::sort(backward.begin(), backward.end());
  r->boundary_is_polygon = boundary == forward || boundary == backward;
  if (!r->boundary_is_polygon) {
    NoteProblem("the boundary (" + std::to_string(boundary.size()) +
                    " edges) is not the polygon (" + std::to_string(n) +
                    " edges)",
                r);
  }
}

// A disk is connected, has Euler characteristic V - E + F = 1, and the
// triangles around every vertex form a single fan; a sphere with k holes
// has 2 - k.
void CheckDisk(size_t vertex_count, const std::vector<Triangle>& triangles,
               const EdgeFindings& edges, int64_t loops, UnionFind* components,
               MeshReport* r) {
  std::vector<int32_t> used;
  for (const Triangle& t : triangles) {
    used.insert(used.end(), t.begin(), t.end());
  }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  const int64_t component_count = components->Count();
  const int64_t euler = static_cast<int64_t>(used.size()) - edges.edges +
                        static_cast<int64_t>(triangles.size());
  // Around a vertex the triangles of an edge-manifold mesh form paths and
  // cycles; it is a single fan when its interior edges (joins) number its
  // triangles minus one (a path) or the count itself (a cycle).
  std::vector<int32_t> degree(vertex_count, 0);
  for (const Triangle& t : triangles) {
    for (int32_t v : t) ++degree[v];
  }
  bool fans_ok = true;
  for (int32_t v : used) fans_ok &= edges.joins[v] >= degree[v] - 1;
  r->disk = !triangles.empty() && component_count == 1 && euler == 2 - loops &&
            fans_ok && r->non_manifold_edges == 0;
  if (!r->disk) {
    NoteProblem(
        std::string(loops == 1 ? "not a disk: " : "not a sphere with holes: ") +
            std::to_string(component_count) +
            " components, Euler characteristic " + std::to_string(euler) +
            (fans_ok ? "" : ", a vertex with several fans"),
        r);
  }
}

}  // namespace

int64_t CountIntersectingPairs(const std::vector<Vec3>& vertices,
                               const std::vector<Triangle>& triangles,
                               size_t checked) {
  int64_t pairs = 0;
  CountIntersectingPairs(vertices, triangles, checked, Control{}, &pairs);
  return pairs;
}

namespace {

// Calls found(a, b) for each intersecting pair (a < b), polling `control`.
template <typename Found>
Status VisitIntersectingPairs(const std::vector<Vec3>& vertices,
                              const std::vector<Triangle>& triangles,
                              size_t checked, const Control& control,
                              Found found) {
  RunTicker ticker(control, "the intersection check");
  std::vector<P3> p;
  p.reserve(vertices.size());
  for (const Vec3& v : vertices) p.push_back(ToPoint(v));
  std::vector<Box> boxes;
  boxes.reserve(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    if (!ticker.Tick()) return ticker.status();
    const Triangle& t = triangles[i];
    boxes.emplace_back(p[t[0]].bbox() + p[t[1]].bbox() + p[t[2]].bbox(),
                       static_cast<int32_t>(i));
  }
  // CGAL's box intersection has no way to stop but an exception.
  struct Stop {};
  try {
    CGAL::box_self_intersection_d(
        boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
          if (!ticker.Tick()) throw Stop{};
          if (static_cast<size_t>(x.info()) >= checked &&
              static_cast<size_t>(y.info()) >= checked) {
            return;
          }
          if (Overlaps(p, triangles[x.info()], triangles[y.info()])) {
            found(std::min(x.info(), y.info()), std::max(x.info(), y.info()));
          }
        });
  } catch (const Stop&) {
    return ticker.status();
  }
  return OkStatus();
}

}  // namespace

Status CountIntersectingPairs(const std::vector<Vec3>& vertices,
                              const std::vector<Triangle>& triangles,
                              size_t checked, const Control& control,
                              int64_t* pairs) {
  int64_t count = 0;
  Status s = VisitIntersectingPairs(vertices, triangles, checked, control,
                                    [&](int32_t, int32_t) { ++count; });
  if (s.ok()) *pairs = count;
  return s;
}

Status ListIntersectingPairs(const std::vector<Vec3>& vertices,
                             const std::vector<Triangle>& triangles,
                             size_t checked, const Control& control,
                             std::vector<std::pair<int32_t, int32_t>>* pairs) {
  pairs->clear();
  Status s = VisitIntersectingPairs(
      vertices, triangles, checked, control,
      [&](int32_t a, int32_t b) { pairs->emplace_back(a, b); });
  if (!s.ok()) pairs->clear();
  return s;
}

MeshReport ValidateMesh(const std::vector<Vec3>& vertices,
                        const std::vector<int32_t>& polygon,
                        const std::vector<Triangle>& triangles,
                        bool check_intersections) {
  return ValidateSurface(vertices, {polygon}, triangles, check_intersections);
}

MeshReport ValidateSurface(const std::vector<Vec3>& vertices,
                           const std::vector<std::vector<int32_t>>& loops,
                           const std::vector<Triangle>& triangles,
                           bool check_intersections) {
  MeshReport r;
  std::vector<int32_t> polygon;
  for (const std::vector<int32_t>& l : loops) {
    polygon.insert(polygon.end(), l.begin(), l.end());
  }
  r.indices_in_range =
      IndicesInRange(static_cast<int32_t>(vertices.size()), polygon, triangles);
  if (!r.indices_in_range) {
    NoteProblem("a vertex index is out of range", &r);
    return r;
  }
  CountDegenerate(vertices, triangles, &r);
  UnionFind components(triangles.size());
  EdgeFindings edges = CheckEdges(vertices.size(), triangles, &components, &r);
  CheckBoundary(loops, std::move(edges.boundary), &r);
  CheckDisk(vertices.size(), triangles, edges,
            static_cast<int64_t>(loops.size()), &components, &r);
  if (check_intersections && r.degenerate_triangles == 0) {
    r.intersecting_pairs = CountIntersectingPairs(vertices, triangles);
    if (r.intersecting_pairs > 0) {
      NoteProblem(std::to_string(r.intersecting_pairs) +
                      " pairs of triangles intersect",
                  &r);
    }
  }
  return r;
}

MeshShape ShapeOf(const MeshData& mesh) {
  UnionFind pieces(mesh.vertices.size());
  std::vector<bool> used(mesh.vertices.size(), false);
  std::vector<uint64_t> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      used[t[k]] = true;
      pieces.Join(t[k], t[(k + 1) % 3]);
      edges.push_back(UndirectedEdgeKey(t[k], t[(k + 1) % 3]));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  MeshShape shape;
  int64_t vertices = 0;
  for (size_t v = 0; v < used.size(); ++v) {
    if (!used[v]) continue;
    ++vertices;
    shape.pieces +=
        pieces.Find(static_cast<int32_t>(v)) == static_cast<int32_t>(v);
  }
  shape.euler = vertices - static_cast<int64_t>(edges.size()) +
                static_cast<int64_t>(mesh.triangles.size());
  return shape;
}

namespace {

using HausdorffMesh = CGAL::Surface_mesh<
    CGAL::Exact_predicates_inexact_constructions_kernel::Point_3>;

Status ToSurfaceMesh(const MeshData& m, const char* which, HausdorffMesh* sm) {
  if (m.triangles.empty()) {
    return InvalidArgument(std::string(which) + " mesh has no faces");
  }
  for (const Vec3& p : m.vertices) sm->add_vertex({p.x, p.y, p.z});
  for (const Triangle& t : m.triangles) {
    for (int32_t v : t) {
      if (v < 0 || static_cast<size_t>(v) >= m.vertices.size()) {
        return InvalidArgument(std::string(which) +
                               " mesh has a face index out of range");
      }
    }
    using V = HausdorffMesh::Vertex_index;
    if (sm->add_face(V(t[0]), V(t[1]), V(t[2])) == HausdorffMesh::null_face()) {
      return InvalidArgument(std::string(which) +
                             " mesh is not an oriented 2-manifold");
    }
  }
  return OkStatus();
}

}  // namespace

Status HausdorffDistance(const MeshData& a, const MeshData& b,
                         double error_bound, double* distance) {
  if (!(error_bound > 0) || !std::isfinite(error_bound)) {
    return InvalidArgument(
        "the Hausdorff error bound must be a positive "
        "number");
  }
  HausdorffMesh sa, sb;
  Status s = ToSurfaceMesh(a, "the first", &sa);
  if (s.ok()) s = ToSurfaceMesh(b, "the second", &sb);
  if (!s.ok()) return s;
  *distance =
      CGAL::Polygon_mesh_processing::bounded_error_symmetric_Hausdorff_distance<
          CGAL::Sequential_tag>(sa, sb, error_bound);
  return OkStatus();
}

}  // namespace dot

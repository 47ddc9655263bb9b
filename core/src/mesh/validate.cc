// SPDX-License-Identifier: AGPL-3.0-or-later
// Mesh validation. Topology by sorting edge records; intersections by CGAL's
// box intersection for candidate pairs and exact predicates (Epick) for the
// test itself, so "intersection-free" is a proof, not a tolerance.
#include "dot/validate.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <atomic>
#include <numeric>
#include <string>

#include "mesh/edge_key.h"

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

}  // namespace

int64_t CountIntersectingPairs(const std::vector<Vec3>& vertices,
                               const std::vector<Triangle>& triangles) {
  std::vector<P3> p;
  p.reserve(vertices.size());
  for (const Vec3& v : vertices) p.push_back(ToPoint(v));
  std::vector<Box> boxes;
  boxes.reserve(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& t = triangles[i];
    boxes.emplace_back(p[t[0]].bbox() + p[t[1]].bbox() + p[t[2]].bbox(),
                       static_cast<int32_t>(i));
  }
  int64_t count = 0;
  CGAL::box_self_intersection_d(
      boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
        if (Overlaps(p, triangles[x.info()], triangles[y.info()])) ++count;
      });
  return count;
}

MeshReport ValidateMesh(const std::vector<Vec3>& vertices,
                        const std::vector<int32_t>& polygon,
                        const std::vector<Triangle>& triangles,
                        bool check_intersections) {
  MeshReport r;
  auto problem = [&r](const std::string& what) {
    if (r.first_problem.empty()) r.first_problem = what;
  };
  const auto nv = static_cast<int32_t>(vertices.size());
  r.indices_in_range = true;
  for (const Triangle& t : triangles)
    for (int32_t v : t) r.indices_in_range &= v >= 0 && v < nv;
  for (int32_t v : polygon) r.indices_in_range &= v >= 0 && v < nv;
  if (!r.indices_in_range) {
    problem("a vertex index is out of range");
    return r;
  }
  for (size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& t = triangles[i];
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (repeated ||
        CGAL::collinear(ToPoint(vertices[t[0]]), ToPoint(vertices[t[1]]),
                        ToPoint(vertices[t[2]]))) {
      ++r.degenerate_triangles;
      problem("triangle " + std::to_string(i) + " is degenerate");
    }
  }

  // Directed half-edges (from, to) of the triangles, sorted by their
  // undirected edge.
  struct HalfEdge {
    uint64_t key;
    int32_t from, triangle;
  };
  std::vector<HalfEdge> half;
  half.reserve(3 * triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const int32_t a = triangles[i][k], b = triangles[i][(k + 1) % 3];
      half.push_back({UndirectedEdgeKey(a, b), a, static_cast<int32_t>(i)});
    }
  }
  std::sort(half.begin(), half.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.key < y.key || (x.key == y.key && x.triangle < y.triangle);
  });
  std::vector<std::pair<int32_t, int32_t>> boundary;  // directed
  int64_t edge_count = 0;
  std::vector<int32_t> joins(vertices.size(), 0);  // interior edges at v
  // Triangles joined across manifold edges (union-find), for connectivity
  // and for the fans around each vertex.
  std::vector<int32_t> parent(triangles.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&parent](int32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (size_t i = 0; i < half.size();) {
    size_t j = i;
    while (j < half.size() && half[j].key == half[i].key) ++j;
    ++edge_count;
    const size_t uses = j - i;
    const int32_t lo = EdgeKeyLo(half[i].key), hi = EdgeKeyHi(half[i].key);
    if (uses == 1) {
      const int32_t to = half[i].from == lo ? hi : lo;
      boundary.emplace_back(half[i].from, to);
    } else if (uses == 2) {
      if (half[i].from == half[i + 1].from) {
        ++r.misoriented_edges;
        problem("edge " + std::to_string(lo) + "-" + std::to_string(hi) +
                " is used twice in the same direction");
      }
      parent[find(half[i].triangle)] = find(half[i + 1].triangle);
      ++joins[lo];
      ++joins[hi];
    } else {
      ++r.non_manifold_edges;
      problem("edge " + std::to_string(lo) + "-" + std::to_string(hi) +
              " is on " + std::to_string(uses) + " triangles");
    }
    i = j;
  }

  // Boundary: exactly the polygon's edges, all in one direction.
  const auto n = static_cast<int32_t>(polygon.size());
  std::vector<std::pair<int32_t, int32_t>> forward, backward;
  for (int32_t i = 0; i < n; ++i) {
    forward.emplace_back(polygon[i], polygon[(i + 1) % n]);
    backward.emplace_back(polygon[(i + 1) % n], polygon[i]);
  }
  std::sort(boundary.begin(), boundary.end());
  std::sort(forward.begin(), forward.end());
  std::sort(backward.begin(), backward.end());
  r.boundary_is_polygon = boundary == forward || boundary == backward;
  if (!r.boundary_is_polygon) {
    problem("the boundary (" + std::to_string(boundary.size()) +
            " edges) is not the polygon (" + std::to_string(n) + " edges)");
  }

  // Disk: connected, Euler characteristic V - E + F = 1, and the triangles
  // around every vertex form a single fan.
  std::vector<int32_t> used;
  for (const Triangle& t : triangles)
    used.insert(used.end(), t.begin(), t.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  int64_t components = 0;
  for (size_t t = 0; t < triangles.size(); ++t)
    components += find(t) == int32_t(t);
  const int64_t euler = static_cast<int64_t>(used.size()) - edge_count +
                        static_cast<int64_t>(triangles.size());
  // Fans: around a vertex the triangles of an edge-manifold mesh form paths
  // and cycles; it is a single fan when joins (interior edges at v) equal
  // its triangle count minus one (a path) or the count itself (a cycle).
  std::vector<int32_t> degree(vertices.size(), 0);
  for (const Triangle& t : triangles)
    for (int32_t v : t) ++degree[v];
  bool fans_ok = true;
  for (int32_t v : used) fans_ok &= joins[v] >= degree[v] - 1;
  r.disk = !triangles.empty() && components == 1 && euler == 1 && fans_ok &&
           r.non_manifold_edges == 0;
  if (!r.disk) {
    problem("not a disk: " + std::to_string(components) +
            " components, Euler characteristic " + std::to_string(euler) +
            (fans_ok ? "" : ", a vertex with several fans"));
  }
  if (check_intersections && r.degenerate_triangles == 0) {
    r.intersecting_pairs = CountIntersectingPairs(vertices, triangles);
    if (r.intersecting_pairs > 0) {
      problem(std::to_string(r.intersecting_pairs) +
              " pairs of triangles intersect");
    }
  }
  return r;
}

}  // namespace dot

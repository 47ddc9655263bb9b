// SPDX-License-Identifier: AGPL-3.0-or-later
// Judging an output, outside the timings and alike for both methods:
// holes filled, intersecting pairs (exact predicates), closed and
// edge-manifold, distance to the ground truth of cut meshes.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <unordered_map>
#include <unordered_set>

#include "fill_bench/cgal_types.h"
#include "fill_bench/fill_bench.h"
#include "mesh/edge_index.h"
#include "util/union_find.h"

namespace dot::bench::fill {
namespace {

using Tri3 = K::Triangle_3;
using Primitive =
    CGAL::AABB_triangle_primitive<K, std::vector<Tri3>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

std::vector<Tri3> Triangles3(const std::vector<Vec3>& v,
                             const std::vector<Triangle>& faces) {
  std::vector<Tri3> out;
  for (const Triangle& t : faces) {
    Tri3 tri(P(v[t[0]]), P(v[t[1]]), P(v[t[2]]));
    if (!tri.is_degenerate()) out.push_back(tri);
  }
  return out;
}

// Area-weighted sample points: centroids of an L x L subdivision of each
// triangle, L growing with its area over `cell` (about four points on a
// triangle of the mesh's mean edge length).
struct Samples {
  std::vector<K::Point_3> points;
  std::vector<double> weights;
};

Samples SamplePoints(const std::vector<Tri3>& tris, double cell) {
  Samples s;
  for (const Tri3& t : tris) {
    const double area = std::sqrt(CGAL::to_double(t.squared_area()));
    const int l =
        std::clamp(static_cast<int>(std::ceil(std::sqrt(area / cell))), 1, 32);
    const double w = area / (l * l);
    auto add = [&](double u, double v) {
      const double a = 1 - u - v;
      s.points.emplace_back(a * t[0].x() + u * t[1].x() + v * t[2].x(),
                            a * t[0].y() + u * t[1].y() + v * t[2].y(),
                            a * t[0].z() + u * t[1].z() + v * t[2].z());
      s.weights.push_back(w);
    };
    for (int i = 0; i < l; ++i) {
      for (int j = 0; i + j < l; ++j) {
        add((i + 1.0 / 3) / l, (j + 1.0 / 3) / l);
        if (i + j < l - 1) add((i + 2.0 / 3) / l, (j + 2.0 / 3) / l);
      }
    }
  }
  return s;
}

// Weighted mean and max distance of the samples to the tree's surface.
std::pair<double, double> Distances(const Samples& s, const Tree& tree) {
  double sum = 0, weight = 0, most = 0;
  for (size_t i = 0; i < s.points.size(); ++i) {
    const double d =
        std::sqrt(CGAL::to_double(tree.squared_distance(s.points[i])));
    sum += s.weights[i] * d;
    weight += s.weights[i];
    most = std::max(most, d);
  }
  return {weight > 0 ? sum / weight : NAN, weight > 0 ? most : NAN};
}

uint64_t FaceKey(Triangle t) {
  std::sort(t.begin(), t.end());
  return (static_cast<uint64_t>(t[0]) << 42) |
         (static_cast<uint64_t>(t[1]) << 21) | static_cast<uint64_t>(t[2]);
}

}  // namespace

struct Judge {
  std::unordered_set<uint64_t> input_faces;  // sorted corners, 21 bits each
  // Cut meshes: the closed mesh and samples of the removed patches.
  std::vector<Tri3> original_tris;
  std::unique_ptr<Tree> original;
  Samples truth;
  double edge = 0, cell = 0;  // mean edge length of the closed mesh
};

Holes FindHoles(const MeshData& mesh) {
  Holes h;
  if (!FindHoleLoops(mesh, &h.loops).ok()) return h;
  UnionFind holes(h.loops.size());  // loops that share a vertex: one hole
  std::unordered_map<int32_t, int> first;
  for (size_t i = 0; i < h.loops.size(); ++i) {
    h.pinched_loops += h.loops[i].pinched;
    for (int32_t v : h.loops[i].vertices) {
      auto [it, added] = first.emplace(v, static_cast<int>(i));
      if (!added) holes.Join(static_cast<int>(i), it->second);
    }
  }
  std::map<int, int> id;
  for (size_t i = 0; i < h.loops.size(); ++i) {
    auto [it, added] = id.emplace(holes.Find(static_cast<int>(i)),
                                  static_cast<int>(id.size()));
    h.loop_hole.push_back(it->second);
  }
  h.count = static_cast<int>(id.size());
  for (size_t i = 0; i < h.loops.size(); ++i) {
    for (int32_t v : h.loops[i].vertices) h.vertex[v] = h.loop_hole[i];
  }
  return h;
}

std::shared_ptr<const Judge> MakeJudge(const Case& c) {
  auto made = std::make_shared<Judge>();
  Judge& j = *made;
  for (const Triangle& t : c.mesh.triangles) j.input_faces.insert(FaceKey(t));
  if (c.original.triangles.empty()) return made;
  double length = 0;
  for (const Triangle& t : c.original.triangles) {
    for (int k = 0; k < 3; ++k) {
      length += Distance(c.original.vertices[t[k]],
                         c.original.vertices[t[(k + 1) % 3]]);
    }
  }
  j.edge = length / (3.0 * c.original.triangles.size());
  j.cell = j.edge * j.edge * std::sqrt(3.0) / 16;
  j.original_tris = Triangles3(c.original.vertices, c.original.triangles);
  j.original =
      std::make_unique<Tree>(j.original_tris.begin(), j.original_tris.end());
  j.original->accelerate_distance_queries();
  j.truth =
      SamplePoints(Triangles3(c.removed.vertices, c.removed.triangles), j.cell);
  return made;
}

Verdict Evaluate(const Judge& j, const std::vector<Vec3>& vertices,
                 const std::vector<Triangle>& faces) {
  Verdict v;
  std::vector<Triangle> ordered, fresh;
  for (const Triangle& t : faces) {
    if (j.input_faces.count(FaceKey(t))) {
      ordered.push_back(t);
      continue;
    }
    ++v.new_faces;
    const bool degenerate =
        t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
        CGAL::collinear(P(vertices[t[0]]), P(vertices[t[1]]),
                        P(vertices[t[2]]));
    if (degenerate) {
      ++v.degenerate;
    } else {
      fresh.push_back(t);
    }
  }
  // New faces first: pairs with at least one new face are counted.
  const size_t checked = fresh.size();
  fresh.insert(fresh.end(), ordered.begin(), ordered.end());
  v.pairs = CountIntersectingPairs(vertices, fresh, checked);
  std::unordered_map<uint64_t, std::pair<int, int>> edges;  // uses, forward
  for (const Triangle& t : faces) {
    for (int k = 0; k < 3; ++k) {
      auto& e = edges[UndirectedEdgeKey(t[k], t[(k + 1) % 3])];
      ++e.first;
      e.second += t[k] < t[(k + 1) % 3];
    }
  }
  v.closed = true;
  for (const auto& [key, e] : edges) {
    v.closed &= e.first == 2;
    v.non_manifold += e.first > 2;
    v.misoriented += e.first == 2 && e.second != 1;
  }
  if (j.original) {
    fresh.resize(checked);
    const Samples patch = SamplePoints(Triangles3(vertices, fresh), j.cell);
    const auto [patch_mean, patch_max] = Distances(patch, *j.original);
    const std::vector<Tri3> out_tris = Triangles3(vertices, faces);
    Tree out(out_tris.begin(), out_tris.end());
    out.accelerate_distance_queries();
    const auto [truth_mean, truth_max] = Distances(j.truth, out);
    v.d_patch = patch_mean / j.edge;
    v.d_truth = truth_mean / j.edge;
    v.d_mean = 0.5 * (v.d_patch + v.d_truth);
    v.d_max =
        std::max(std::isnan(patch_max) ? 0 : patch_max, truth_max) / j.edge;
  }
  return v;
}

std::string Defect(const Case& c, const FillResult& ours, const Verdict& v) {
  if (v.pairs > 0 || v.degenerate > 0) {
    return std::to_string(v.pairs) + " intersecting pairs, " +
           std::to_string(v.degenerate) + " degenerate new faces";
  }
  if (v.non_manifold > 0 || v.misoriented > 0) {
    return std::to_string(v.non_manifold) + " non-manifold and " +
           std::to_string(v.misoriented) + " misoriented edges";
  }
  if (v.closed != ours.report.closed) {
    return "report.closed is " + Yes(ours.report.closed) + ", the mesh is " +
           (v.closed ? "" : "not ") + "closed";
  }
  if (ours.report.filled == ours.report.loops && !v.closed) {
    return "every hole reported filled, the mesh is not closed";
  }
  if (!std::equal(c.mesh.vertices.begin(), c.mesh.vertices.end(),
                  ours.mesh.vertices.begin())) {
    return "input vertices changed";
  }
  return "";
}

}  // namespace dot::bench::fill

// SPDX-License-Identifier: AGPL-3.0-or-later
// One hole -> one DOT patch: its loops as a Problem (boundary normals, the
// faces across its edges, its existing chords forbidden), the escalation
// Delaunay -> edge protection -> all triangles (small holes) or every
// triangle with the Delaunay ones first (large ones), and the split of the
// faces across boundary edges that edge protection subdivided.
#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "dot/fill_holes.h"
#include "mesh/normals.h"
#include "mesh/topology.h"
#include "polygon/unit_scale.h"

namespace dot {
namespace {

// The hole's loops, concatenated: mesh vertex, face across the edge to the
// next vertex of the same loop, and that next position, per position.
struct HoleRing {
  std::vector<int32_t> vertices, faces, next;
  std::vector<int32_t> sizes;  // per loop
};

HoleRing MakeRing(const std::vector<const HoleLoop*>& loops) {
  HoleRing ring;
  for (const HoleLoop* l : loops) {
    const auto begin = static_cast<int32_t>(ring.vertices.size());
    const auto n = static_cast<int32_t>(l->vertices.size());
    ring.vertices.insert(ring.vertices.end(), l->vertices.begin(),
                         l->vertices.end());
    ring.faces.insert(ring.faces.end(), l->faces.begin(), l->faces.end());
    for (int32_t i = 0; i < n; ++i) ring.next.push_back(begin + (i + 1) % n);
    ring.sizes.push_back(n);
  }
  return ring;
}

// The hole as a Problem in work coordinates: the mesh's scaled by the
// power of two that brings the rim to unit size (exact, see
// polygon/unit_scale.h), so that normals, edge lengths and per-edge weights
// neither overflow nor underflow at any finite scale (before: a mesh at
// 1e160 had zero normals, one at 1e-160 an infinite area weight).
Problem HoleProblem(const MeshData& mesh, const MeshTopology& topo,
                    const HoleRing& ring, const FillOptions& options,
                    const std::vector<std::pair<int32_t, int32_t>>& avoid,
                    UnitScale* scale) {
  Problem p;
  const auto n = static_cast<int32_t>(ring.vertices.size());
  for (int32_t v : ring.vertices) p.vertices.push_back(mesh.vertices[v]);
  *scale = ChooseUnitScale(p.vertices);
  for (Vec3& v : p.vertices) v = scale->ToWork(v);
  auto work = [&](int32_t v) { return scale->ToWork(mesh.vertices[v]); };
  std::unordered_map<int32_t, int32_t> position;
  double perimeter = 0;
  for (int32_t i = 0; i < n; ++i) {
    position[ring.vertices[i]] = i;
    perimeter += Distance(p.vertices[i], p.vertices[ring.next[i]]);
    p.edge_face_normals.push_back(
        Normalized(FaceCross(mesh.triangles[ring.faces[i]], work)));
  }
  for (int32_t i = 0; i < n; ++i) {
    Vec3 sum = AreaWeightedNormal(mesh, topo, ring.vertices[i], work);
    if (Norm(sum) == 0) sum = p.edge_face_normals[i];
    if (Norm(sum) == 0) sum = {0, 0, 1};
    p.normals.push_back(Normalized(sum));
  }
  // Chords the mesh already has: from each hole vertex, the corners of its
  // faces that are later hole vertices, each once.
  std::vector<int32_t> later;
  for (int32_t i = 0; i < n; ++i) {
    const int32_t v = ring.vertices[i];
    later.clear();
    for (int32_t k = topo.face_begin[v]; k < topo.face_begin[v + 1]; ++k) {
      for (int32_t w : mesh.triangles[topo.faces[k]]) {
        auto it = position.find(w);
        if (it == position.end() || it->second <= i) continue;
        const int32_t j = it->second;
        if (ring.next[i] == j || ring.next[j] == i) continue;
        later.push_back(j);
      }
    }
    std::sort(later.begin(), later.end());
    later.erase(std::unique(later.begin(), later.end()), later.end());
    for (int32_t j : later) p.forbidden_edges.emplace_back(i, j);
  }
  for (const auto& [a, b] : avoid) {
    auto i = position.find(a), j = position.find(b);
    if (i == position.end() || j == position.end()) continue;
    if (ring.next[i->second] == j->second || ring.next[j->second] == i->second)
      continue;
    p.forbidden_edges.emplace_back(i->second, j->second);
  }
  if (ring.sizes.size() > 1) p.loop_sizes = ring.sizes;
  p.weights = options.weights;
  if (options.scale_free_weights && perimeter > 0) {
    const double edge = perimeter / n;
    p.weights[Metric::kArea] /= edge * edge;
    p.weights[Metric::kPerimeter] /= edge;
  } else {
    // Weights in the mesh's units: the same objective on work coordinates.
    for (Metric m : kAllMetrics) {
      p.weights[m] =
          std::ldexp(p.weights[m], -LengthDegree(m) * scale->exponent);
    }
  }
  return p;
}

// The pieces of input face `f` once the inserted vertices of its border
// edges are on it. `inserted` maps a directed loop edge (a, b) to the ids
// inserted on it, in loop order.
Status SplitFace(
    const MeshData& mesh, int32_t f,
    const std::map<std::pair<int32_t, int32_t>, std::vector<int32_t>>& inserted,
    const std::vector<Vec3>& new_vertices, int32_t first_new_id,
    std::vector<Triangle>* pieces) {
  const Triangle& t = mesh.triangles[f];
  // The face's boundary with the inserted ids; the loop runs against it.
  std::vector<int32_t> ring;
  std::vector<std::pair<size_t, size_t>> sides;  // ring ranges, corners incl.
  int split_sides = 0, last_split = 0;
  for (int s = 0; s < 3; ++s) {
    const int32_t x = t[s], y = t[(s + 1) % 3];
    const size_t begin = ring.size();
    ring.push_back(x);
    auto it = inserted.find({y, x});
    if (it == inserted.end()) continue;
    ++split_sides;
    last_split = s;
    ring.insert(ring.end(), it->second.rbegin(), it->second.rend());
    sides.emplace_back(begin, ring.size());  // up to the next corner
  }
  auto point = [&](int32_t id) {
    return id < first_new_id ? mesh.vertices[id]
                             : new_vertices[id - first_new_id];
  };
  pieces->clear();
  if (split_sides == 1) {
    // A fan from the corner opposite the split side.
    const int32_t x = t[last_split], y = t[(last_split + 1) % 3],
                  z = t[(last_split + 2) % 3];
    std::vector<int32_t> side{x};
    auto it = inserted.find({y, x});
    side.insert(side.end(), it->second.rbegin(), it->second.rend());
    side.push_back(y);
    for (size_t k = 0; k + 1 < side.size(); ++k) {
      pieces->push_back({side[k], side[k + 1], z});
    }
    return OkStatus();
  }
  // Several split sides: the face is a planar polygon; DOT triangulates it,
  // never joining two vertices of one side (they are collinear: such a
  // chord would make a needle or fold).
  Problem p;
  for (int32_t id : ring) p.vertices.push_back(point(id));
  const auto n = static_cast<int32_t>(ring.size());
  for (const auto& [begin, end] : sides) {
    for (size_t a = begin; a <= end; ++a) {
      for (size_t b = a + 2; b <= end; ++b) {
        const auto i = static_cast<int32_t>(a % n),
                   j = static_cast<int32_t>(b % n);
        if ((i + 1) % n != j && (j + 1) % n != i)
          p.forbidden_edges.emplace_back(i, j);
      }
    }
  }
  Options o;
  o.space = SearchSpace::kAll;
  const Result r = Triangulate(p, o);
  if (!r.status.ok() || r.intersecting_pairs > 0 || !r.inserted.empty()) {
    return MakeStatus(StatusCode::kNoTriangulation,
                      "face " + std::to_string(f) +
                          " cannot be split at the vertices inserted on its "
                          "sides: " +
                          r.status.message);
  }
  for (const Triangle& tr : r.triangles) {
    pieces->push_back({ring[tr[0]], ring[tr[1]], ring[tr[2]]});
  }
  return OkStatus();
}

struct Attempt {
  Escalation escalation;
  SearchSpace space;
  bool protect_edges;
};

}  // namespace

Status TriangulateHole(const MeshData& mesh, const MeshTopology& topology,
                       const HoleLoop& loop, const FillOptions& options,
                       const Control& control, int32_t first_new_id,
                       HolePatch* patch, HoleReport* report) {
  return TriangulateHole(mesh, topology, std::vector<const HoleLoop*>{&loop},
                         options, control, first_new_id, patch, report);
}

Status TriangulateHole(const MeshData& mesh, const MeshTopology& topology,
                       const std::vector<const HoleLoop*>& loops,
                       const FillOptions& options, const Control& control,
                       int32_t first_new_id, HolePatch* patch,
                       HoleReport* report,
                       const std::vector<std::pair<int32_t, int32_t>>& avoid) {
  *patch = {};
  UnitScale scale;
  const HoleRing hole = MakeRing(loops);
  const Problem problem =
      HoleProblem(mesh, topology, hole, options, avoid, &scale);
  const auto n = static_cast<int32_t>(hole.vertices.size());
  std::vector<Attempt> attempts = {
      {Escalation::kDelaunay, SearchSpace::kDelaunay, false},
      {Escalation::kProtectedEdges, SearchSpace::kDelaunay, true}};
  if (n <= options.all_space_max_vertices) {
    attempts.push_back({Escalation::kAllTriangles, SearchSpace::kAll, false});
  } else if (loops.size() == 1 &&
             n <= options.triangulate.delaunay_first_max_vertices) {
    // Cubic time, quadratic memory: the patch may cross itself or the mesh
    // where it leaves the Delaunay triangles; the fill's check decides.
    attempts.push_back(
        {Escalation::kDelaunayFirst, SearchSpace::kDelaunayFirst, false});
  }
  Result r;
  std::string why;
  for (const Attempt& a : attempts) {
    Options o = options.triangulate;
    o.space = a.space;
    o.protect_edges = a.protect_edges;
    // The faces around every loop fix its direction: the patch must agree
    // with them.
    o.reorient_loops = false;
    r = Triangulate(problem, o, control);
    report->escalation = a.escalation;
    if (r.status.ok()) break;
    // Edge protection can also run out of room (more vertices than allowed,
    // an edge too short to halve): the next step may still succeed.
    const bool next_may_help =
        r.status.code == StatusCode::kNoTriangulation ||
        (a.protect_edges && (r.status.code == StatusCode::kResourceExhausted ||
                             r.status.code == StatusCode::kInvalidArgument));
    // The last step's own refusal (its memory budget) still leaves the
    // hole without a patch, with what every step said.
    const bool stopped = r.status.code == StatusCode::kCancelled ||
                         r.status.code == StatusCode::kDeadlineExceeded;
    if (stopped ||
        (!next_may_help && a.escalation != Escalation::kDelaunayFirst)) {
      return r.status;
    }
    why += std::string(why.empty() ? "" : "; ") +
           std::string(EscalationName(a.escalation)) + ": " + r.status.message;
  }
  if (!r.status.ok()) {
    if (r.status.code == StatusCode::kCancelled ||
        r.status.code == StatusCode::kDeadlineExceeded) {
      return r.status;
    }
    return MakeStatus(StatusCode::kNoTriangulation, why);
  }
  report->space = r.space_used;
  report->solver = r.solver;
  report->cost = r.total_cost;
  report->boundary_inserted = static_cast<int32_t>(r.inserted.size());
  report->non_delaunay_triangles =
      static_cast<int32_t>(r.stats.non_delaunay_triangles);

  auto global = [&](int32_t id) {
    return id < n ? hole.vertices[id] : first_new_id + (id - n);
  };
  for (int32_t id = n; id < static_cast<int32_t>(r.vertices.size()); ++id) {
    patch->new_vertices.push_back(scale.ToCaller(r.vertices[id]));
  }
  for (const Triangle& t : r.triangles) {
    patch->faces.push_back({global(t[0]), global(t[1]), global(t[2])});
  }
  report->patch_triangles = static_cast<int32_t>(patch->faces.size());
  if (r.inserted.empty()) return OkStatus();

  // Inserted vertices, per split loop edge, in loop order.
  std::map<std::pair<int32_t, int32_t>, std::vector<int32_t>> inserted;
  std::vector<int32_t> split;
  for (const std::vector<int32_t>& ring : ResultLoops(r)) {
    for (size_t k = 0; k < ring.size(); ++k) {
      if (ring[k] >= n) continue;
      size_t j = (k + 1) % ring.size();
      std::vector<int32_t> on_edge;
      for (; ring[j] >= n; j = (j + 1) % ring.size()) {
        on_edge.push_back(global(ring[j]));
      }
      if (on_edge.empty()) continue;
      inserted[{hole.vertices[ring[k]], hole.vertices[ring[j]]}] = on_edge;
      split.push_back(hole.faces[ring[k]]);
    }
  }
  std::sort(split.begin(), split.end());
  split.erase(std::unique(split.begin(), split.end()), split.end());
  for (int32_t f : split) {
    std::vector<Triangle> pieces;
    Status s = SplitFace(mesh, f, inserted, patch->new_vertices, first_new_id,
                         &pieces);
    if (!s.ok()) return s;
    patch->split_faces.push_back(f);
    patch->pieces.push_back(std::move(pieces));
  }
  report->split_faces = patch->split_faces;
  return OkStatus();
}

}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
// Border cycles of a mesh, split into simple loops.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "dot/fill_holes.h"
#include "mesh/edge_index.h"
#include "mesh/normals.h"
#include "mesh/topology.h"
#include "util/run_control.h"

namespace dot {
namespace {

// A border edge as the loop walks it: against its face's half-edge.
struct HoleEdge {
  int32_t from, to, face;
};

// Edges of `mesh` used by one face only, walked against that face; or the
// first edge that breaks edge-manifoldness or orientation.
Status BorderEdges(const MeshData& mesh, RunTicker& ticker,
                   std::vector<HoleEdge>* border) {
  EdgeIndex index;
  if (!BuildEdgeIndex(mesh.triangles, ticker, &index)) return ticker.status();
  Status status = OkStatus();
  ForEachEdge(index, [&](const EdgeUses& edge) {
    if (!ticker.Tick()) return (status = ticker.status()).ok();
    const auto name = [&] {
      return "edge " + std::to_string(edge.lo()) + "-" +
             std::to_string(edge.hi());
    };
    if (edge.size() > 2) {
      status = InvalidArgument(name() + " is shared by " +
                               std::to_string(edge.size()) +
                               " faces (the mesh is not edge-manifold)");
    } else if (edge.size() == 2 && edge[0].forward == edge[1].forward) {
      status = InvalidArgument(name() + " runs the same way in faces " +
                               std::to_string(edge[0].triangle) + " and " +
                               std::to_string(edge[1].triangle) +
                               " (the faces are not consistently oriented)");
    } else if (edge.size() == 1) {
      border->push_back({edge[0].to(), edge[0].from(), edge[0].triangle});
    }
    return status.ok();
  });
  return status;
}

double Diameter(const MeshData& mesh, const std::vector<int32_t>& ids) {
  constexpr double kBig = std::numeric_limits<double>::infinity();
  Vec3 lo{kBig, kBig, kBig}, hi{-kBig, -kBig, -kBig};
  for (int32_t id : ids) {
    const Vec3& p = mesh.vertices[id];
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return Distance(lo, hi);
}

// Splits one closed walk at its repeated vertices into simple loops: a
// vertex met again closes the loop since its previous visit.
void SplitWalk(const MeshData& mesh, const std::vector<HoleEdge>& walk,
               int32_t border, std::vector<int32_t>* position,
               std::vector<HoleLoop>* loops) {
  std::vector<HoleEdge> stack;
  const bool pinched = [&] {
    std::vector<int32_t> seen;
    for (const HoleEdge& e : walk) seen.push_back(e.from);
    std::sort(seen.begin(), seen.end());
    return std::adjacent_find(seen.begin(), seen.end()) != seen.end();
  }();
  auto emit = [&](size_t first) {
    HoleLoop loop;
    loop.id = static_cast<int32_t>(loops->size());
    loop.border = border;
    loop.pinched = pinched;
    for (size_t k = first; k < stack.size(); ++k) {
      loop.vertices.push_back(stack[k].from);
      loop.faces.push_back(stack[k].face);
      (*position)[stack[k].from] = -1;
    }
    loop.diameter = Diameter(mesh, loop.vertices);
    loops->push_back(std::move(loop));
    stack.resize(first);
  };
  for (const HoleEdge& e : walk) {
    const int32_t p = (*position)[e.from];
    if (p >= 0) emit(static_cast<size_t>(p));
    (*position)[e.from] = static_cast<int32_t>(stack.size());
    stack.push_back(e);
  }
  emit(0);
}

// The border edge that continues the gap `in` arrives through. At an
// ordinary border vertex that is the one unused edge leaving it. At a pinched
// vertex, where fans of faces and gaps alternate around the vertex, it is
// the end of the *next* fan: not the other end of `in`'s own fan (found by
// turning through its faces), and among the rest the first met turning
// clockwise (seen from the vertex normal) from the arriving edge, since
// `in`'s face lies to its left. `topo` is built on first need.
std::vector<HoleEdge>::const_iterator NextAroundFan(
    const MeshData& mesh, const HoleEdge& in,
    const std::vector<HoleEdge>& border,
    std::vector<HoleEdge>::const_iterator first, const std::vector<bool>& used,
    std::shared_ptr<const MeshTopology>* topo) {
  const int32_t v = in.to;
  std::vector<std::vector<HoleEdge>::const_iterator> candidates;
  for (auto it = first; it != border.end() && it->from == v; ++it) {
    if (!used[it - border.begin()]) candidates.push_back(it);
  }
  if (candidates.size() <= 1) {
    return candidates.empty() ? border.end() : candidates[0];
  }
  if (!*topo) *topo = BuildMeshAdjacency(mesh);
  const MeshTopology& t = **topo;
  // The other end of in's fan: turn from in.face across sides w -> v.
  int32_t face = in.face, own_end = -1;
  for (int32_t step = t.face_begin[v]; step < t.face_begin[v + 1]; ++step) {
    const Triangle& f = mesh.triangles[face];
    const int k = f[0] == v ? 0 : f[1] == v ? 1 : 2;
    const int32_t w = f[(k + 2) % 3];
    int32_t across = -1;
    for (int32_t j = t.face_begin[v]; j < t.face_begin[v + 1]; ++j) {
      const Triangle& g = mesh.triangles[t.faces[j]];
      for (int c = 0; c < 3; ++c) {
        if (g[c] == v && g[(c + 1) % 3] == w) across = t.faces[j];
      }
    }
    if (across < 0) {
      own_end = w;
      break;
    }
    face = across;
  }
  const Vec3 normal = AreaWeightedNormal(
      mesh, t, v, [&](int32_t id) -> const Vec3& { return mesh.vertices[id]; });
  const Vec3& p = mesh.vertices[v];
  const Vec3 back = mesh.vertices[in.from] - p;
  auto clockwise = [&](const HoleEdge& e) {
    const Vec3 d = mesh.vertices[e.to] - p;
    const double angle = std::atan2(Dot(normal, Cross(back, d)), Dot(back, d));
    return angle <= 0 ? -angle : 2 * kPi - angle;
  };
  std::vector<HoleEdge>::const_iterator best = border.end();
  double best_angle = 0;
  for (auto it : candidates) {
    if (it->to == own_end && candidates.size() > 1) continue;
    const double a = clockwise(*it);
    if (best == border.end() || a < best_angle) best = it, best_angle = a;
  }
  return best;
}

}  // namespace

Status FindHoleLoops(const MeshData& mesh, std::vector<HoleLoop>* loops,
                     const Control& control) {
  loops->clear();
  RunTicker ticker(control, "the search for the mesh's holes");
  std::vector<HoleEdge> border;
  Status s = BorderEdges(mesh, ticker, &border);
  if (!s.ok()) return s;
  if (!ticker.Poll()) return ticker.status();
  // Deterministic walks: edges by start vertex, then end.
  std::sort(border.begin(), border.end(),
            [](const HoleEdge& a, const HoleEdge& b) {
              return a.from < b.from || (a.from == b.from && a.to < b.to);
            });
  auto out_of = [&](int32_t v) {
    return std::lower_bound(
        border.begin(), border.end(), v,
        [](const HoleEdge& e, int32_t x) { return e.from < x; });
  };
  // Each arrival at a pinched vertex weighs all of its border edges, so a
  // vertex on thousands of them (60,000 triangles sharing one corner and
  // nothing else) made the walk quadratic: minutes for a 6 MB file. No hole
  // meets itself that often; such a vertex is refused by name.
  for (size_t i = 0, j = 0; i < border.size(); i = j) {
    while (j < border.size() && border[j].from == border[i].from) ++j;
    if (j - i > kMaxBorderEdgesAtVertex) {
      return InvalidArgument(
          "vertex " + std::to_string(border[i].from) + " starts " +
          std::to_string(j - i) + " border edges (at most " +
          std::to_string(kMaxBorderEdgesAtVertex) +
          " are accepted): so many surface pieces meeting at one vertex do "
          "not bound holes; split it first");
    }
  }
  std::vector<bool> used(border.size(), false);
  std::shared_ptr<const MeshTopology> topo;  // for pinched vertices
  std::vector<int32_t> position(mesh.vertices.size(), -1);
  int32_t borders = 0;
  for (size_t first = 0; first < border.size(); ++first) {
    if (used[first]) continue;
    std::vector<HoleEdge> walk;
    size_t cur = first;
    for (;;) {
      if (!ticker.Tick()) return ticker.status();
      used[cur] = true;
      walk.push_back(border[cur]);
      const int32_t v = border[cur].to;
      if (v == border[first].from) break;
      auto next =
          NextAroundFan(mesh, border[cur], border, out_of(v), used, &topo);
      if (next == border.end()) {
        return InvalidArgument("border vertex " + std::to_string(v) +
                               " has more border edges arriving than "
                               "leaving (the mesh is not consistently "
                               "oriented around it)");
      }
      cur = static_cast<size_t>(next - border.begin());
    }
    SplitWalk(mesh, walk, borders++, &position, loops);
  }
  // A vertex on several loops pinches them, however the walks went.
  std::vector<int8_t> seen(mesh.vertices.size(), 0);
  for (const HoleLoop& l : *loops) {
    for (int32_t v : l.vertices) seen[v] = std::min(seen[v] + 1, 2);
  }
  for (HoleLoop& l : *loops) {
    for (int32_t v : l.vertices) l.pinched |= seen[v] > 1;
  }
  return OkStatus();
}

}  // namespace dot

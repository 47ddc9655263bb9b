// SPDX-License-Identifier: AGPL-3.0-or-later
// SolveBridged in steps: candidate bridges, a tree of them (Kruskal), the
// weakly simple polygon it makes, the single-loop DP over that polygon, the
// check that the surface is manifold, and the true cost of each tree's
// surface (bridges' bending included) to keep the cheapest.
#include "solve/bridged.h"

#include <algorithm>
#include <map>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "mesh/edge_index.h"
#include "solve/adjacency.h"
#include "solve/solvers.h"
#include "util/run_control.h"
#include "util/union_find.h"

namespace dot {
namespace {

// Trees tried: the shortest, then breadth-first those with one more of the
// bridges already used banned, up to this many, and fewer on large inputs
// (kTreeWork candidate triangles over all trees).
constexpr int kMaxTrees = 32;
constexpr int64_t kTreeWork = 4'000'000;
constexpr int kMaxRetries = 16;  // re-solves without a non-manifold chord

struct Bridge {
  int32_t p, q;  // loop positions, p < q
  double length;
};

struct Loops {
  std::vector<int32_t> loop_of, index_in_loop, next;  // per position
  const std::vector<std::vector<int32_t>>* members;
};

// Edges of candidate triangles between two loops, on at least two
// candidates (a bridge is inside the surface), shortest first.
std::vector<Bridge> CandidateBridges(const Loops& loops,
                                     const std::vector<Triangle>& candidates,
                                     const std::vector<Vec3>& points) {
  std::unordered_map<uint64_t, int> uses;
  for (const Triangle& t : candidates) {
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      if (loops.loop_of[a] != loops.loop_of[b]) ++uses[UndirectedEdgeKey(a, b)];
    }
  }
  std::vector<Bridge> bridges;
  for (const auto& [key, count] : uses) {
    if (count < 2) continue;
    const auto p = static_cast<int32_t>(key >> 32),
               q = static_cast<int32_t>(key & 0xffffffffu);
    bridges.push_back({p, q, Distance(points[p], points[q])});
  }
  std::sort(bridges.begin(), bridges.end(),
            [](const Bridge& a, const Bridge& b) {
              return a.length != b.length
                         ? a.length < b.length
                         : std::make_pair(a.p, a.q) < std::make_pair(b.p, b.q);
            });
  return bridges;
}

// The shortest tree of bridges over the loops avoiding `banned`, each
// position ending at most one bridge; empty when none connects them all.
std::vector<int32_t> Tree(const std::vector<Bridge>& bridges,
                          const Loops& loops, int32_t k,
                          const std::vector<int32_t>& banned) {
  UnionFind joined(k);
  std::vector<bool> used(loops.loop_of.size(), false);
  std::vector<int32_t> tree;
  for (size_t b = 0; b < bridges.size() && tree.size() + 1 < size_t(k); ++b) {
    const Bridge& e = bridges[b];
    if (used[e.p] || used[e.q] ||
        std::find(banned.begin(), banned.end(), static_cast<int32_t>(b)) !=
            banned.end()) {
      continue;
    }
    const int32_t lp = loops.loop_of[e.p], lq = loops.loop_of[e.q];
    if (joined.Find(lp) == joined.Find(lq)) continue;
    joined.Join(lp, lq);
    used[e.p] = used[e.q] = true;
    tree.push_back(static_cast<int32_t>(b));
  }
  if (tree.size() + 1 != size_t(k)) tree.clear();
  return tree;
}

// The walk of the loops from loop 0's first position: each position, and
// at a position that ends a bridge to a loop not yet walked, that loop's
// walk (from the bridge's end round to it again) and the position again.
// Iterative: a chain of thousands of loops must not deepen the stack.
std::vector<int32_t> Walk(const Loops& loops,
                          const std::vector<int32_t>& bridge_at) {
  struct Frame {
    int32_t loop, entry, from, i;
  };
  const std::vector<std::vector<int32_t>>& members = *loops.members;
  std::vector<int32_t> out;
  std::vector<Frame> stack = {{0, members[0][0], -1, 0}};
  while (!stack.empty()) {
    Frame& f = stack.back();
    const std::vector<int32_t>& m = members[f.loop];
    const auto size = static_cast<int32_t>(m.size());
    if (f.i == size) {
      const Frame done = f;
      stack.pop_back();
      if (done.from >= 0) {
        out.push_back(done.entry);
        out.push_back(done.from);
      }
      continue;
    }
    const int32_t p = m[(loops.index_in_loop[f.entry] + f.i) % size];
    ++f.i;
    out.push_back(p);
    const int32_t q = bridge_at[p];
    if (q >= 0 && q != f.from) {
      stack.push_back({loops.loop_of[q], q, p, 0});  // `f` is stale now
    }
  }
  return out;
}

struct Cut {
  std::vector<int32_t> polygon;  // loop position per polygon position
  std::vector<std::vector<int32_t>> copies;  // per loop position
};

// The surface's cost as the annulus solver prices it: every triangle,
// every interior edge's bending, every loop edge's against its face.
double SurfaceCost(const SurfaceCosts& costs, const std::vector<int32_t>& next,
                   const std::vector<Triangle>& triangles) {
  double total = 0;
  std::vector<Vec3> normals;
  for (const Triangle& t : triangles) {
    total += costs.Weight(t);
    normals.push_back(costs.Normal(t));
  }
  if (!costs.bi()) return total;
  std::unordered_map<uint64_t, int32_t> first;
  for (size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      if (next[a] == b) total += costs.BoundaryBend(a, normals[f]);
      auto [it, fresh] =
          first.emplace(UndirectedEdgeKey(a, b), static_cast<int32_t>(f));
      if (!fresh) total += costs.Bend(normals[it->second], normals[f]);
    }
  }
  return total;
}

}  // namespace

Status SolveBridged(const std::vector<std::vector<int32_t>>& members,
                    const std::vector<Triangle>& candidates,
                    const SurfaceCosts& costs, int64_t memory_budget,
                    const Control& control, BridgedSolution* out) {
  *out = {};
  const auto k = static_cast<int32_t>(members.size());
  const auto n = static_cast<int32_t>(costs.points.size());
  Loops loops;
  loops.members = &members;
  loops.loop_of.assign(n, -1);
  loops.index_in_loop.assign(n, -1);
  loops.next.assign(n, -1);
  for (int32_t l = 0; l < k; ++l) {
    const auto size = static_cast<int32_t>(members[l].size());
    for (int32_t i = 0; i < size; ++i) {
      const int32_t p = members[l][i];
      loops.loop_of[p] = l;
      loops.index_in_loop[p] = i;
      loops.next[p] = members[l][(i + 1) % size];
    }
  }
  const std::vector<Bridge> bridges =
      CandidateBridges(loops, candidates, costs.points);
  RunTicker ticker(control, Stage::kDynamicProgram);
  // Loop edges, which the surface uses once (its border).
  std::unordered_set<uint64_t> loop_edges;
  for (int32_t p = 0; p < n; ++p) {
    loop_edges.insert(UndirectedEdgeKey(p, loops.next[p]));
  }

  const int64_t max_trees = std::clamp<int64_t>(
      kTreeWork / std::max<int64_t>(1, 4 * candidates.size()), 1, kMaxTrees);
  std::vector<std::vector<int32_t>> trees;
  std::vector<std::vector<int32_t>> bans = {{}};
  for (size_t next = 0;
       next < bans.size() && static_cast<int64_t>(trees.size()) < max_trees;
       ++next) {
    const std::vector<int32_t> ban = bans[next];
    std::vector<int32_t> t = Tree(bridges, loops, k, ban);
    if (t.empty() || std::find(trees.begin(), trees.end(), t) != trees.end()) {
      continue;
    }
    for (int32_t b : t) {
      std::vector<int32_t> more = ban;
      more.push_back(b);
      if (bans.size() < 16 * kMaxTrees) bans.push_back(std::move(more));
    }
    trees.push_back(std::move(t));
  }
  if (trees.empty()) {
    return MakeStatus(StatusCode::kNoTriangulation,
                      "no candidate edges join the " + std::to_string(k) +
                          " loops into one piece");
  }
  bool found = false;
  Status last = OkStatus();
  for (const std::vector<int32_t>& tree : trees) {
    ++out->trees_tried;
    std::vector<int32_t> bridge_at(n, -1);
    for (int32_t b : tree) {
      bridge_at[bridges[b].p] = bridges[b].q;
      bridge_at[bridges[b].q] = bridges[b].p;
    }
    Cut cut;
    cut.polygon = Walk(loops, bridge_at);
    const auto m = static_cast<int32_t>(cut.polygon.size());
    cut.copies.assign(n, {});
    for (int32_t i = 0; i < m; ++i) cut.copies[cut.polygon[i]].push_back(i);
    // The polygon's border pairs (loop edges and bridges, as loop
    // positions): a chord between other copies of them would use an edge
    // of the border a second time.
    std::unordered_set<uint64_t> border;
    for (int32_t i = 0; i < m; ++i) {
      border.insert(
          UndirectedEdgeKey(cut.polygon[i], cut.polygon[(i + 1) % m]));
    }
    SurfaceCosts at;  // per polygon position
    for (int32_t i = 0; i < m; ++i) {
      const int32_t p = cut.polygon[i], q = cut.polygon[(i + 1) % m];
      at.points.push_back(costs.points[p]);
      if (!costs.normals.empty()) at.normals.push_back(costs.normals[p]);
      if (!costs.edge_normals.empty()) {
        at.edge_normals.push_back(loops.next[p] == q ? costs.edge_normals[p]
                                                     : Vec3{});
      }
    }
    at.weights = costs.weights;
    at.bending = costs.bending;
    std::unordered_set<uint64_t> banned;  // polygon chords
    for (int retry = 0; retry <= kMaxRetries; ++retry) {
      std::vector<Triangle> tris;
      auto chord_ok = [&](int32_t i, int32_t j) {
        if (j - i == 1 || (i == 0 && j == m - 1)) return true;
        return !border.count(
                   UndirectedEdgeKey(cut.polygon[i], cut.polygon[j])) &&
               !banned.count(UndirectedEdgeKey(i, j));
      };
      for (const Triangle& t : candidates) {
        if (!ticker.Tick()) return ticker.status();
        for (int32_t a : cut.copies[t[0]]) {
          for (int32_t b : cut.copies[t[1]]) {
            for (int32_t c : cut.copies[t[2]]) {
              Triangle s{a, b, c};
              std::sort(s.begin(), s.end());
              if (chord_ok(s[0], s[1]) && chord_ok(s[1], s[2]) &&
                  chord_ok(s[0], s[2])) {
                tris.push_back(s);
              }
            }
          }
        }
      }
      const bool bi = costs.bi();
      const int64_t bytes =
          EstimateTableBytes(static_cast<int64_t>(tris.size()), bi);
      if (bytes > memory_budget) {
        if (found) break;  // keep the surface an earlier tree gave
        return MakeStatus(StatusCode::kResourceExhausted,
                          "estimated memory " + std::to_string(bytes >> 20) +
                              " MiB for the bridged polygon exceeds the "
                              "budget of " +
                              std::to_string(memory_budget >> 20) + " MiB");
      }
      Adjacency adj;
      Status s = BuildAdjacency(m, &tris, control, &adj);
      if (!s.ok()) return s;
      CandidateWeights w(tris.size());
      for (size_t t = 0; t < tris.size(); ++t) w[t] = at.Weight(tris[t]);
      DpSolution sol;
      s = bi ? SolveDot2(adj, w, CandidateNormals(at.points, tris),
                         at.edge_normals, at.bending, control, &sol)
             : SolveDot1(adj, w, control, &sol);
      out->states += sol.states;
      out->table_bytes =
          std::max(out->table_bytes, adj.Bytes() + sol.table_bytes);
      if (!s.ok()) {
        if (s.code != StatusCode::kNoTriangulation) return s;
        last = MakeStatus(s.code,
                          "the polygon the bridges make has no "
                          "triangulation among the candidates");
        break;
      }
      std::vector<Triangle> surface;
      for (int32_t id : sol.triangles) {
        const Triangle& t = tris[id];
        surface.push_back(
            {cut.polygon[t[0]], cut.polygon[t[1]], cut.polygon[t[2]]});
      }
      // Manifold: a loop edge once, any other edge twice. A chord used a
      // third time is banned from one of its copies and the tree re-solved.
      std::map<uint64_t, std::vector<std::pair<int32_t, int32_t>>> uses;
      for (int32_t id : sol.triangles) {
        const Triangle& t = tris[id];
        for (int e = 0; e < 3; ++e) {
          const int32_t i = t[e], j = t[(e + 1) % 3];
          uses[UndirectedEdgeKey(cut.polygon[i], cut.polygon[j])].push_back(
              {std::min(i, j), std::max(i, j)});
        }
      }
      bool manifold = true;
      for (const auto& [key, at_edge] : uses) {
        const size_t want = loop_edges.count(key) ? 1 : 2;
        if (at_edge.size() <= want) continue;
        manifold = false;
        // Two copies of one vertex pair: ban the later chord.
        auto chords = at_edge;
        std::sort(chords.begin(), chords.end());
        chords.erase(std::unique(chords.begin(), chords.end()), chords.end());
        banned.insert(
            UndirectedEdgeKey(chords.back().first, chords.back().second));
      }
      if (!manifold) {
        last = MakeStatus(StatusCode::kNoTriangulation,
                          "every surface over the bridges tried reuses an "
                          "edge");
        continue;
      }
      const double cost = SurfaceCost(costs, loops.next, surface);
      if (!found || cost < out->cost) {
        found = true;
        out->cost = cost;
        out->triangles = std::move(surface);
        out->bridges.clear();
        for (int32_t b : tree)
          out->bridges.push_back({bridges[b].p, bridges[b].q});
      }
      break;
    }
  }
  if (!found) {
    return MakeStatus(StatusCode::kNoTriangulation,
                      "no surface joins the " + std::to_string(k) +
                          " loops over the " +
                          std::to_string(out->trees_tried) +
                          " trees of bridges tried (" + last.message + ")");
  }
  return OkStatus();
}

}  // namespace dot

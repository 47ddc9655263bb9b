// SPDX-License-Identifier: AGPL-3.0-or-later
#include "dot/hole_generator.h"

#include <algorithm>
#include <random>

#include "mesh/edge_key.h"

namespace dot {
namespace {

// Triangles across each edge, from sorted edge records.
struct MeshTopology {
  std::vector<int32_t> across;  // 3 per triangle: neighbour over edge k, -1
  std::vector<int32_t> vertex_degree;  // triangles per vertex
  std::vector<bool> on_border;         // vertex on a mesh boundary or
                                       // non-manifold edge
};

MeshTopology BuildTopology(const MeshData& mesh) {
  MeshTopology topo;
  const auto nt = static_cast<int32_t>(mesh.triangles.size());
  topo.across.assign(3 * nt, -1);
  topo.vertex_degree.assign(mesh.vertices.size(), 0);
  topo.on_border.assign(mesh.vertices.size(), false);
  std::vector<std::pair<uint64_t, int32_t>> rec;  // (edge, 3 * t + k)
  for (int32_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int32_t a = mesh.triangles[t][k],
                    b = mesh.triangles[t][(k + 1) % 3];
      rec.emplace_back(UndirectedEdgeKey(a, b), 3 * t + k);
      ++topo.vertex_degree[a];
    }
  }
  std::sort(rec.begin(), rec.end());
  for (size_t i = 0; i < rec.size();) {
    size_t j = i;
    while (j < rec.size() && rec[j].first == rec[i].first) ++j;
    if (j - i == 2) {
      topo.across[rec[i].second] = rec[i + 1].second / 3;
      topo.across[rec[i + 1].second] = rec[i].second / 3;
    } else {
      topo.on_border[EdgeKeyLo(rec[i].first)] = true;
      topo.on_border[EdgeKeyHi(rec[i].first)] = true;
    }
    i = j;
  }
  return topo;
}

}  // namespace

Status GrowHole(const MeshData& mesh, int triangles, uint64_t seed, Hole* out) {
  const auto nt = static_cast<int32_t>(mesh.triangles.size());
  if (nt == 0 || triangles < 1 || triangles >= nt) {
    return MakeStatus(StatusCode::kInvalidArgument,
                      "hole size must be between 1 and the mesh's " +
                          std::to_string(nt) + " triangles");
  }
  const MeshTopology topo = BuildTopology(mesh);
  std::mt19937_64 rng(seed);
  std::vector<bool> in_hole(nt, false);
  std::vector<int32_t> hole_degree(mesh.vertices.size(), 0);
  auto touches_border = [&](int32_t t) {
    for (int32_t v : mesh.triangles[t])
      if (topo.on_border[v]) return true;
    return false;
  };
  // Adding t keeps the hole a disk when t shares exactly one edge with it
  // and its third vertex is new, or two edges and closes the fan around
  // their common vertex.
  auto can_add = [&](int32_t t) {
    if (in_hole[t] || touches_border(t)) return false;
    int shared = 0, free_corner = -1;
    for (int k = 0; k < 3; ++k) {
      const int32_t nb = topo.across[3 * t + k];
      if (nb >= 0 && in_hole[nb]) {
        ++shared;
      } else {
        free_corner = k;  // edge k is not shared
      }
    }
    const Triangle& tri = mesh.triangles[t];
    if (shared == 1) {
      // The vertex opposite the shared edge must not touch the hole.
      for (int k = 0; k < 3; ++k) {
        const int32_t nb = topo.across[3 * t + k];
        if (nb >= 0 && in_hole[nb]) return hole_degree[tri[(k + 2) % 3]] == 0;
      }
    }
    if (shared == 2) {
      // Common vertex of the two shared edges: opposite the free edge.
      const int32_t v = tri[(free_corner + 2) % 3];
      return hole_degree[v] + 1 == topo.vertex_degree[v];
    }
    return false;
  };
  std::vector<int32_t> frontier;
  auto add = [&](int32_t t) {
    in_hole[t] = true;
    for (int32_t v : mesh.triangles[t]) ++hole_degree[v];
    for (int k = 0; k < 3; ++k) {
      const int32_t nb = topo.across[3 * t + k];
      if (nb >= 0 && !in_hole[nb]) frontier.push_back(nb);
    }
  };

  int32_t start = -1;
  for (int attempt = 0; attempt < 1000 && start < 0; ++attempt) {
    const auto t = static_cast<int32_t>(rng() % nt);
    if (!touches_border(t)) start = t;
  }
  if (start < 0) {
    return MakeStatus(StatusCode::kInvalidArgument,
                      "found no interior triangle to start a hole from");
  }
  add(start);
  int grown = 1;
  while (grown < triangles && !frontier.empty()) {
    const size_t pick = rng() % frontier.size();
    const int32_t t = frontier[pick];
    frontier[pick] = frontier.back();
    frontier.pop_back();
    if (!can_add(t)) continue;
    add(t);
    ++grown;
  }
  if (grown < triangles) {
    return MakeStatus(StatusCode::kInvalidArgument,
                      "the hole stopped growing at " + std::to_string(grown) +
                          " of " + std::to_string(triangles) + " triangles");
  }

  // Boundary: directed edges a -> b of hole triangles whose neighbour stays.
  std::vector<int32_t> next(mesh.vertices.size(), -1);
  int32_t first = -1;
  int boundary_edges = 0;
  for (int32_t t = 0; t < nt; ++t) {
    if (!in_hole[t]) continue;
    for (int k = 0; k < 3; ++k) {
      const int32_t nb = topo.across[3 * t + k];
      if (nb >= 0 && in_hole[nb]) continue;
      const int32_t a = mesh.triangles[t][k],
                    b = mesh.triangles[t][(k + 1) % 3];
      if (next[a] != -1) {
        return MakeStatus(StatusCode::kInternal,
                          "hole boundary is not a simple loop");
      }
      next[a] = b;
      first = a;
      ++boundary_edges;
    }
  }
  // Normals: area-weighted normals of the triangles that remain.
  std::vector<Vec3> normal(mesh.vertices.size());
  for (int32_t t = 0; t < nt; ++t) {
    if (in_hole[t]) continue;
    const Triangle& tri = mesh.triangles[t];
    const Vec3& a = mesh.vertices[tri[0]];
    const Vec3 c = Cross(mesh.vertices[tri[1]] - a, mesh.vertices[tri[2]] - a);
    for (int32_t v : tri) normal[v] = normal[v] + c;
  }
  *out = {};
  out->triangles = grown;
  int32_t v = first;
  do {
    out->boundary.vertices.push_back(mesh.vertices[v]);
    out->boundary.normals.push_back(Normalized(normal[v]));
    v = next[v];
  } while (v != first && v != -1 &&
           static_cast<int>(out->boundary.vertices.size()) <= boundary_edges);
  if (v != first ||
      static_cast<int>(out->boundary.vertices.size()) != boundary_edges) {
    return MakeStatus(StatusCode::kInternal,
                      "hole boundary is not a single loop");
  }
  return OkStatus();
}

}  // namespace dot

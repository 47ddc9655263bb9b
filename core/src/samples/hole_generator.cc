// SPDX-License-Identifier: AGPL-3.0-or-later
// GrowHole in steps: index the mesh's topology, pick an interior start
// triangle, grow the hole one triangle at a time while it stays a disk, then
// walk its boundary and take normals from the triangles that remain. The
// index is built once per mesh and the growth's marks are undone after each
// hole, so CutHoles costs the mesh once plus each hole's own size.
#include "dot/hole_generator.h"

#include <algorithm>
#include <random>
#include <string>

#include "mesh/edge_index.h"
#include "mesh/normals.h"
#include "mesh/topology.h"

namespace dot {
namespace {

struct SideAdjacency {
  std::vector<int32_t> across;  // 3 per triangle: neighbour over side k, -1
  std::vector<int32_t> vertex_degree;  // triangles per vertex
  // Vertex on a mesh boundary or non-manifold edge: holes keep off it, so
  // they never open onto the outside or pinch.
  std::vector<bool> on_border;
};

SideAdjacency BuildSides(const MeshData& mesh) {
  SideAdjacency topo;
  topo.across.assign(3 * mesh.triangles.size(), -1);
  topo.vertex_degree.assign(mesh.vertices.size(), 0);
  topo.on_border.assign(mesh.vertices.size(), false);
  for (const Triangle& t : mesh.triangles) {
    for (int32_t v : t) ++topo.vertex_degree[v];
  }
  ForEachEdge(BuildEdgeIndex(mesh.triangles), [&](const EdgeUses& edge) {
    if (edge.size() == 2) {
      topo.across[3 * edge[0].triangle + edge[0].side] = edge[1].triangle;
      topo.across[3 * edge[1].triangle + edge[1].side] = edge[0].triangle;
    } else {
      topo.on_border[edge.lo()] = true;
      topo.on_border[edge.hi()] = true;
    }
  });
  return topo;
}

// The hole while it grows. The marks are mesh-sized and allocated once;
// Clear undoes only what the last hole touched.
struct Growth {
  const MeshData& mesh;
  const SideAdjacency& topo;
  const MeshTopology& faces;  // for the boundary normals
  std::vector<bool> in_hole;
  std::vector<int32_t> hole_degree;  // hole triangles per vertex
  std::vector<int32_t> frontier;     // candidates: neighbours of the hole
  std::vector<int32_t> added;        // the hole's triangles, in order
  std::vector<int32_t> next;         // boundary links (BoundaryLinks)
  int grown = 0;

  Growth(const MeshData& m, const SideAdjacency& t, const MeshTopology& f)
      : mesh(m),
        topo(t),
        faces(f),
        in_hole(m.triangles.size(), false),
        hole_degree(m.vertices.size(), 0),
        next(m.vertices.size(), -1) {}

  bool InHole(int32_t t) const { return t >= 0 && in_hole[t]; }
  void Clear() {
    for (int32_t t : added) {
      in_hole[t] = false;
      for (int32_t v : mesh.triangles[t]) {
        hole_degree[v] = 0;
        next[v] = -1;
      }
    }
    added.clear();
    frontier.clear();
    grown = 0;
  }
};

bool TouchesBorder(const Growth& g, int32_t t) {
  for (int32_t v : g.mesh.triangles[t]) {
    if (g.topo.on_border[v]) return true;
  }
  return false;
}

// Adding t keeps the hole a disk when t shares exactly one side with it and
// its third vertex is new, or two sides and closes the fan around their
// common vertex.
bool KeepsDisk(const Growth& g, int32_t t) {
  if (g.in_hole[t] || TouchesBorder(g, t)) return false;
  int shared = 0, free_side = -1, shared_side = -1;
  for (int k = 0; k < 3; ++k) {
    if (g.InHole(g.topo.across[3 * t + k])) {
      ++shared;
      if (shared_side < 0) shared_side = k;
    } else {
      free_side = k;
    }
  }
  const Triangle& tri = g.mesh.triangles[t];
  if (shared == 1) {
    // The vertex opposite the shared side must not touch the hole.
    return g.hole_degree[tri[(shared_side + 2) % 3]] == 0;
  }
  if (shared == 2) {
    // The common vertex of the two shared sides is opposite the free one.
    const int32_t v = tri[(free_side + 2) % 3];
    return g.hole_degree[v] + 1 == g.topo.vertex_degree[v];
  }
  return false;
}

void Add(Growth* g, int32_t t) {
  g->in_hole[t] = true;
  g->added.push_back(t);
  ++g->grown;
  for (int32_t v : g->mesh.triangles[t]) ++g->hole_degree[v];
  for (int k = 0; k < 3; ++k) {
    const int32_t nb = g->topo.across[3 * t + k];
    if (nb >= 0 && !g->in_hole[nb]) g->frontier.push_back(nb);
  }
}

// A random triangle off the border, or -1 after 1000 tries.
int32_t PickStart(const Growth& g, std::mt19937_64* rng) {
  const auto nt = static_cast<int32_t>(g.mesh.triangles.size());
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const auto t = static_cast<int32_t>((*rng)() % nt);
    if (!TouchesBorder(g, t)) return t;
  }
  return -1;
}

// Adds random frontier triangles that keep the hole a disk until it has
// `triangles` or the frontier runs out.
void GrowTo(int triangles, std::mt19937_64* rng, Growth* g) {
  while (g->grown < triangles && !g->frontier.empty()) {
    const size_t pick = (*rng)() % g->frontier.size();
    const int32_t t = g->frontier[pick];
    g->frontier[pick] = g->frontier.back();
    g->frontier.pop_back();
    if (KeepsDisk(*g, t)) Add(g, t);
  }
}

// The boundary as next[a] = b for each directed side a -> b of a hole
// triangle whose neighbour stays; `first` is one of its vertices.
Status BoundaryLinks(Growth* g, int32_t* first, int* edges) {
  std::vector<int32_t>* next = &g->next;
  *first = -1;
  *edges = 0;
  for (int32_t t : g->added) {
    const Triangle& tri = g->mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (g->InHole(g->topo.across[3 * t + k])) continue;
      const int32_t a = tri[k], b = tri[(k + 1) % 3];
      if ((*next)[a] != -1) {
        return MakeStatus(StatusCode::kInternal,
                          "hole boundary is not a simple loop");
      }
      (*next)[a] = b;
      *first = a;
      ++*edges;
    }
  }
  return OkStatus();
}

// Follows the boundary links once around from `first`.
Status WalkBoundary(const Growth& g, int32_t first, int edges,
                    PolygonData* boundary) {
  const std::vector<int32_t>& next = g.next;
  // Normals of the triangles that remain.
  auto position = [&](int32_t id) -> const Vec3& {
    return g.mesh.vertices[id];
  };
  auto removed = [&](int32_t f) { return g.in_hole[f] != 0; };
  int32_t v = first;
  do {
    boundary->vertices.push_back(g.mesh.vertices[v]);
    boundary->normals.push_back(
        Normalized(AreaWeightedNormal(g.mesh, g.faces, v, position, removed)));
    v = next[v];
  } while (v != first && v != -1 &&
           static_cast<int>(boundary->vertices.size()) <= edges);
  if (v != first || static_cast<int>(boundary->vertices.size()) != edges) {
    return MakeStatus(StatusCode::kInternal,
                      "hole boundary is not a single loop");
  }
  return OkStatus();
}

// One hole in a mesh indexed once; `g` is cleared first.
Status GrowOne(int triangles, uint64_t seed, Growth* g, Hole* out) {
  g->Clear();
  const auto nt = static_cast<int32_t>(g->mesh.triangles.size());
  if (nt == 0 || triangles < 1 || triangles >= nt) {
    return InvalidArgument("hole size must be between 1 and the mesh's " +
                           std::to_string(nt) + " triangles");
  }
  std::mt19937_64 rng(seed);
  const int32_t start = PickStart(*g, &rng);
  if (start < 0) {
    return InvalidArgument("found no interior triangle to start a hole from");
  }
  Add(g, start);
  GrowTo(triangles, &rng, g);
  if (g->grown < triangles) {
    return InvalidArgument("the hole stopped growing at " +
                           std::to_string(g->grown) + " of " +
                           std::to_string(triangles) + " triangles");
  }
  int32_t first = -1;
  int edges = 0;
  Status s = BoundaryLinks(g, &first, &edges);
  if (!s.ok()) return s;
  *out = {};
  out->triangles = g->grown;
  out->removed = g->added;
  std::sort(out->removed.begin(), out->removed.end());
  return WalkBoundary(*g, first, edges, &out->boundary);
}

}  // namespace

Status GrowHole(const MeshData& mesh, int triangles, uint64_t seed, Hole* out) {
  const SideAdjacency sides = BuildSides(mesh);
  const auto faces = BuildMeshAdjacency(mesh);
  Growth growth(mesh, sides, *faces);
  return GrowOne(triangles, seed, &growth, out);
}

MeshData SubMesh(const MeshData& mesh, const std::vector<bool>& keep) {
  MeshData out;
  std::vector<int32_t> id(mesh.vertices.size(), -1);
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (!keep[f]) continue;
    Triangle t = mesh.triangles[f];
    for (int32_t& v : t) {
      if (id[v] < 0) {
        id[v] = static_cast<int32_t>(out.vertices.size());
        out.vertices.push_back(mesh.vertices[v]);
      }
      v = id[v];
    }
    out.triangles.push_back(t);
  }
  return out;
}

namespace {

// Whether the first `island` triangles of the hole's growth (a disk around
// its start, since every prefix of the growth is one) keep off its rim:
// every vertex of theirs has all its triangles in the hole.
bool IslandInside(const Growth& g, int island) {
  for (int k = 0; k < island; ++k) {
    for (int32_t v : g.mesh.triangles[g.added[k]]) {
      if (g.hole_degree[v] != g.topo.vertex_degree[v]) return false;
    }
  }
  return true;
}

Status Cut(const MeshData& mesh, int count, int triangles, int island,
           uint64_t seed, MeshData* holey, MeshData* removed) {
  if (island < 0 || (island > 0 && island >= triangles)) {
    return InvalidArgument("an island must have fewer triangles than its hole");
  }
  std::vector<bool> in_hole(mesh.triangles.size(), false);
  std::vector<bool> near_hole(mesh.vertices.size(), false);
  const SideAdjacency sides = BuildSides(mesh);
  const auto faces = BuildMeshAdjacency(mesh);
  Growth growth(mesh, sides, *faces);
  int cut = 0;
  for (uint64_t attempt = 0; cut < count && attempt < 50u * count; ++attempt) {
    Hole hole;
    if (!GrowOne(triangles, seed * 1000003 + attempt, &growth, &hole).ok()) {
      continue;
    }
    if (island > 0 && !IslandInside(growth, island)) continue;
    bool apart = true;
    for (int32_t f : hole.removed) {
      for (int32_t v : mesh.triangles[f]) apart &= !near_hole[v];
    }
    if (!apart) continue;
    for (int32_t f : hole.removed) {
      for (int32_t v : mesh.triangles[f]) near_hole[v] = true;
    }
    for (size_t k = island; k < growth.added.size(); ++k) {
      in_hole[growth.added[k]] = true;
    }
    ++cut;
  }
  if (cut < count) {
    return InvalidArgument(
        "found room for only " + std::to_string(cut) + " separate holes of " +
        std::to_string(triangles) + " triangles" +
        (island > 0 ? " with an island of " + std::to_string(island) : ""));
  }
  std::vector<bool> kept(in_hole.size());
  for (size_t f = 0; f < in_hole.size(); ++f) kept[f] = !in_hole[f];
  *holey = SubMesh(mesh, kept);
  *removed = SubMesh(mesh, in_hole);
  return OkStatus();
}

}  // namespace

Status CutHoles(const MeshData& mesh, int count, int triangles, uint64_t seed,
                MeshData* holey, MeshData* removed) {
  return Cut(mesh, count, triangles, 0, seed, holey, removed);
}

Status CutIslandHoles(const MeshData& mesh, int count, int triangles,
                      int island_triangles, uint64_t seed, MeshData* holey,
                      MeshData* removed) {
  return Cut(mesh, count, triangles, island_triangles, seed, holey, removed);
}

}  // namespace dot

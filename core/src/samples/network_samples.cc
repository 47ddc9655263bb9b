// SPDX-License-Identifier: AGPL-3.0-or-later
// Curve networks with known surfaces (dot/network_samples.h).
#include "dot/network_samples.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <random>
#include <set>

namespace dot {
namespace {

// Adds the straight curve p -> q in `segments` pieces; ends are `a`, `b`
// (vertex ids already in the network).
void AddStraight(CurveNetwork* net, int32_t a, int32_t b, int segments) {
  const Vec3 p = net->vertices[a], q = net->vertices[b];
  std::vector<int32_t> line = {a};
  for (int k = 1; k < segments; ++k) {
    line.push_back(static_cast<int32_t>(net->vertices.size()));
    net->vertices.push_back(p + (static_cast<double>(k) / segments) * (q - p));
  }
  line.push_back(b);
  net->polylines.push_back(std::move(line));
}

}  // namespace

CurveNetwork CubeNetwork(int segments) {
  segments = std::max(1, segments);
  CurveNetwork net;
  for (int i = 0; i < 8; ++i) {
    net.vertices.push_back({static_cast<double>(i & 1),
                            static_cast<double>((i >> 1) & 1),
                            static_cast<double>((i >> 2) & 1)});
  }
  for (int i = 0; i < 8; ++i) {
    for (int bit = 0; bit < 3; ++bit) {
      const int j = i | (1 << bit);
      if (j != i) AddStraight(&net, i, j, segments);
    }
  }
  return net;
}

CurveNetwork CylinderNetwork(int n, bool seam) {
  n = std::max(3, n);
  CurveNetwork net;
  for (int rim = 0; rim < 2; ++rim) {
    std::vector<int32_t> line;
    for (int k = 0; k < n; ++k) {
      const double a = 2 * kPi * k / n;
      line.push_back(static_cast<int32_t>(net.vertices.size()));
      net.vertices.push_back({std::cos(a), std::sin(a), 2.0 * rim});
    }
    line.push_back(line.front());
    net.polylines.push_back(std::move(line));
  }
  if (seam) AddStraight(&net, 0, n, std::max(1, n / 4));
  return net;
}

CurveNetwork LidNetwork(int segments, int n) {
  CurveNetwork net = CubeNetwork(segments);
  n = std::max(3, n);
  std::vector<int32_t> line;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * kPi * k / n;
    line.push_back(static_cast<int32_t>(net.vertices.size()));
    net.vertices.push_back(
        {0.5 + 0.3 * std::cos(a), 0.5 + 0.3 * std::sin(a), 1.0});
  }
  line.push_back(line.front());
  net.polylines.push_back(std::move(line));
  return net;
}

CurveNetwork PartitionNetwork(int segments) {
  PolygonSoup box;
  for (int x = 0; x < 3; ++x) {
    for (int y = 0; y < 2; ++y) {
      for (int z = 0; z < 2; ++z) {
        box.vertices.push_back({static_cast<double>(x), static_cast<double>(y),
                                static_cast<double>(z)});
      }
    }
  }
  // Vertex 4x + 2y + z: the squares x = 0, 1, 2 (their edges are all the
  // network has across x).
  for (int x = 0; x < 3; ++x) {
    box.faces.push_back({4 * x, 4 * x + 2, 4 * x + 3, 4 * x + 1});
  }
  for (int x = 0; x < 2; ++x) {  // the long edges, as squares' sides
    for (int k : {0, 1, 3, 2}) {
      const int next = k == 0 ? 1 : k == 1 ? 3 : k == 3 ? 2 : 0;
      box.faces.push_back(
          {4 * x + k, 4 * x + 4 + k, 4 * x + 4 + next, 4 * x + next});
    }
  }
  return FaceEdgeNetwork(box, segments);
}

CurveNetwork FaceEdgeNetwork(const PolygonSoup& soup, int segments) {
  segments = std::max(1, segments);
  CurveNetwork net;
  net.vertices = soup.vertices;
  std::set<std::pair<int32_t, int32_t>> done;
  for (FaceView f : soup.faces) {
    for (size_t k = 0; k < f.size(); ++k) {
      const int32_t a = f[k], b = f[(k + 1) % f.size()];
      if (done.insert({std::min(a, b), std::max(a, b)}).second) {
        AddStraight(&net, a, b, segments);
      }
    }
  }
  return net;
}

namespace {

struct Dual {
  std::vector<std::array<int32_t, 3>> across;  // face across each edge
  std::vector<Vec3> centroid;
};

Status BuildDual(const MeshData& mesh, Dual* d) {
  std::map<std::pair<int32_t, int32_t>, std::vector<int32_t>> faces_on;
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      faces_on[{std::min(a, b), std::max(a, b)}].push_back(
          static_cast<int32_t>(f));
    }
  }
  d->across.assign(mesh.triangles.size(), {-1, -1, -1});
  d->centroid.resize(mesh.triangles.size());
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    d->centroid[f] = (1.0 / 3) * (mesh.vertices[t[0]] + mesh.vertices[t[1]] +
                                  mesh.vertices[t[2]]);
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      const auto& on = faces_on[{std::min(a, b), std::max(a, b)}];
      if (on.size() != 2) {
        return InvalidArgument(
            "the mesh is not closed and edge-manifold: "
            "the edge " +
            std::to_string(a) + "-" + std::to_string(b) + " is on " +
            std::to_string(on.size()) + " faces");
      }
      d->across[f][k] = on[0] == static_cast<int32_t>(f) ? on[1] : on[0];
    }
  }
  return OkStatus();
}

// Nearest-seed labels along the dual graph, seeds added one at a time
// (each grows by Dijkstra over the faces it now is nearest to).
struct Regions {
  const Dual* d;
  std::vector<double> dist;
  std::vector<int32_t> label;
  int32_t seeds = 0;

  explicit Regions(const Dual& dual)
      : d(&dual),
        dist(dual.centroid.size(), 1e300),
        label(dual.centroid.size(), -1) {}

  void AddSeed(int32_t face) {
    using Item = std::pair<double, int32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    dist[face] = 0;
    label[face] = seeds;
    queue.push({0, face});
    while (!queue.empty()) {
      const auto [dv, f] = queue.top();
      queue.pop();
      if (dv > dist[f]) continue;
      for (int32_t g : d->across[f]) {
        const double dg = dv + Distance(d->centroid[f], d->centroid[g]);
        if (dg < dist[g]) {
          dist[g] = dg;
          label[g] = seeds;
          queue.push({dg, g});
        }
      }
    }
    ++seeds;
  }
  // The face farthest from its seed (in `region`, or anywhere: -1).
  int32_t Farthest(int32_t region) const {
    int32_t best = -1;
    for (size_t f = 0; f < dist.size(); ++f) {
      if (region >= 0 && label[f] != region) continue;
      if (best < 0 || dist[f] > dist[best]) best = static_cast<int32_t>(f);
    }
    return best;
  }
  // The labels with rims smoothed: a face with at most one neighbour of its
  // own patch joins the patch of two of its neighbours (spikes and one-face
  // bridges pinch rims).
  std::vector<int32_t> Smoothed() const {
    std::vector<int32_t> out = label;
    for (int pass = 0; pass < 10; ++pass) {
      bool changed = false;
      for (size_t f = 0; f < out.size(); ++f) {
        const auto& a = d->across[f];
        int same = 0;
        for (int32_t g : a) same += out[g] == out[f];
        if (same > 1) continue;
        for (int k = 0; k < 3; ++k) {
          if (out[a[k]] != out[f] && out[a[k]] == out[a[(k + 1) % 3]]) {
            out[f] = out[a[k]];
            changed = true;
            break;
          }
        }
      }
      if (!changed) break;
    }
    return out;
  }
};

// The first region that is not a disk with a simple rim; -1: none.
int32_t FirstNonDisk(const MeshData& mesh, const Dual& d,
                     const std::vector<int32_t>& label, int patches) {
  std::vector<int64_t> faces(patches, 0);
  std::vector<std::set<std::pair<int32_t, int32_t>>> edges(patches);
  std::vector<std::set<int32_t>> vertices(patches);
  std::vector<std::map<int32_t, int>> rim_degree(patches);
  std::vector<int64_t> rim_edges(patches, 0);
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const int r = label[f];
    const Triangle& t = mesh.triangles[f];
    ++faces[r];
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      edges[r].insert({std::min(a, b), std::max(a, b)});
      vertices[r].insert(a);
      if (label[d.across[f][k]] != r) {
        ++rim_degree[r][a];
        ++rim_degree[r][b];
        ++rim_edges[r];
      }
    }
  }
  for (int r = 0; r < patches; ++r) {
    if (faces[r] == 0) return r;
    const int64_t chi = static_cast<int64_t>(vertices[r].size()) -
                        static_cast<int64_t>(edges[r].size()) + faces[r];
    bool simple = chi == 1 && rim_edges[r] >= 3 &&
                  static_cast<int64_t>(rim_degree[r].size()) == rim_edges[r];
    for (const auto& [v, degree] : rim_degree[r]) {
      simple = simple && degree == 2;  // else the rim passes v twice
    }
    if (!simple) return r;
  }
  return -1;
}

}  // namespace

Status CutIntoPatches(const MeshData& mesh, int patches, int keep_every,
                      uint64_t seed, CutNetwork* out) {
  *out = {};
  if (patches < 2) return InvalidArgument("cut into at least 2 patches");
  if (mesh.triangles.size() < static_cast<size_t>(patches) * 8) {
    return InvalidArgument("too few faces for " + std::to_string(patches) +
                           " patches");
  }
  keep_every = std::max(1, keep_every);
  Dual d;
  Status s = BuildDual(mesh, &d);
  if (!s.ok()) return s;
  // Farthest-point seeds; then, while a patch is not a disk with a simple
  // rim (it wraps a limb or a handle), one more seed at its farthest face.
  Regions regions(d);
  std::mt19937_64 rng(seed);
  regions.AddSeed(static_cast<int32_t>(rng() % mesh.triangles.size()));
  while (regions.seeds < patches) regions.AddSeed(regions.Farthest(-1));
  std::vector<int32_t> label = regions.Smoothed();
  const int most = 2 * patches + 16;
  for (int32_t bad; (bad = FirstNonDisk(mesh, d, label, regions.seeds)) >= 0;) {
    if (regions.seeds == most) {
      return InvalidArgument("no cut into disks with up to " +
                             std::to_string(most) + " patches");
    }
    int32_t face = regions.Farthest(bad);
    if (face < 0 || regions.dist[face] == 0) face = regions.Farthest(-1);
    regions.AddSeed(face);
    label = regions.Smoothed();
  }
  // The rim edges, one polyline each; the graph chains them into curves.
  CurveNetwork edges;
  edges.vertices = mesh.vertices;
  std::map<std::pair<int32_t, int32_t>, std::pair<int32_t, int32_t>> sides;
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const int32_t g = d.across[f][k];
      if (label[g] != label[f] && static_cast<int32_t>(f) < g) {
        edges.polylines.push_back({t[k], t[(k + 1) % 3]});
        sides[std::minmax(t[k], t[(k + 1) % 3])] = {label[f], label[g]};
      }
    }
  }
  NetworkGraph graph;
  s = BuildNetworkGraph(edges, &graph);
  if (!s.ok()) return s;
  {  // The rim edges' sides by graph ids (which weld repeated points).
    std::map<std::pair<int32_t, int32_t>, std::pair<int32_t, int32_t>> by_id;
    for (const auto& [edge, side] : sides) {
      by_id[std::minmax(graph.vertex_of_input[edge.first],
                        graph.vertex_of_input[edge.second])] = side;
    }
    sides = std::move(by_id);
  }
  // Keep junctions and every keep_every-th vertex between (one at least,
  // two on a closed curve, so no two curves become one edge).
  std::vector<int32_t> id(graph.vertices.size(), -1);
  auto keep = [&](int32_t v) {
    if (id[v] < 0) {
      id[v] = static_cast<int32_t>(out->network.vertices.size());
      out->network.vertices.push_back(graph.vertices[v]);
    }
    return id[v];
  };
  std::vector<std::vector<int32_t>> rims(regions.seeds);
  for (const NetworkCurve& c : graph.curves) {
    const auto& vs = c.vertices;
    const size_t inner = vs.size() - 2;
    const size_t least = c.closed() ? 2 : 1;
    std::vector<size_t> picks;
    for (size_t k = keep_every; k + 1 < vs.size(); k += keep_every) {
      picks.push_back(k);
    }
    if (picks.size() < std::min(least, inner)) {
      picks.clear();
      for (size_t k = 1; k <= std::min(least, inner); ++k) {
        picks.push_back(k * (vs.size() - 1) / (std::min(least, inner) + 1));
      }
    }
    std::vector<int32_t> line = {keep(vs.front())};
    for (size_t k : picks) line.push_back(keep(vs[k]));
    line.push_back(keep(vs.back()));
    // The two patches across the curve's first edge (a mesh edge).
    const auto side = sides.find(std::minmax(vs[0], vs[1]));
    if (side != sides.end()) {
      for (int32_t patch : {side->second.first, side->second.second}) {
        rims[patch].insert(rims[patch].end(), line.begin(), line.end());
      }
    }
    out->network.polylines.push_back(std::move(line));
  }
  for (auto& rim : rims) {
    std::sort(rim.begin(), rim.end());
    rim.erase(std::unique(rim.begin(), rim.end()), rim.end());
  }
  out->face_patch = std::move(label);
  out->patches = regions.seeds;
  out->rims = std::move(rims);
  return OkStatus();
}

// By vertex sets: every curve of a cut keeps a vertex inside, so a set of
// vertices names its curves.
int32_t CountRimsFound(const CutNetwork& cut,
                       const std::vector<std::vector<int32_t>>& cycles) {
  std::set<std::vector<int32_t>> found;
  for (std::vector<int32_t> c : cycles) {
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    found.insert(std::move(c));
  }
  int32_t count = 0;
  for (const auto& rim : cut.rims) count += found.count(rim) > 0;
  return count;
}

}  // namespace dot

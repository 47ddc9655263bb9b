// SPDX-License-Identifier: AGPL-3.0-or-later
#include "dot/mesh_repair.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <sstream>
#include <tuple>
#include <unordered_map>

#include "mesh/edge_index.h"
#include "util/run_control.h"
#include "util/union_find.h"

namespace dot {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

struct VecHash {
  size_t operator()(const Vec3& v) const {
    const std::hash<double> h;
    return h(v.x) * 73856093u ^ h(v.y) * 19349663u ^ h(v.z) * 83492791u;
  }
};

bool ZeroArea(const std::vector<Vec3>& v, const Triangle& t) {
  auto p = [&](int32_t i) { return K::Point_3(v[i].x, v[i].y, v[i].z); };
  return CGAL::collinear(p(t[0]), p(t[1]), p(t[2]));  // exact
}

// Flips faces so that each manifold edge runs opposite ways in its two
// faces, component by component (breadth first from each component's
// first face); closed components end up with positive volume.
Status Orient(const std::vector<Vec3>& v, std::vector<Triangle>* faces,
              RunTicker& ticker, RepairReport* report) {
  EdgeIndex index;
  if (!BuildEdgeIndex(*faces, ticker, &index)) return ticker.status();
  // Per face side: the other use of that edge, or -1.
  std::vector<int32_t> across(3 * faces->size(), -1);
  Status status = OkStatus();
  ForEachEdge(index, [&](const EdgeUses& e) {
    if (!ticker.Tick()) {
      status = ticker.status();
    } else if (e.size() > 2) {
      status = InvalidArgument(
          "edge " + std::to_string(e.lo()) + "-" + std::to_string(e.hi()) +
          " is shared by " + std::to_string(e.size()) + " faces (" +
          std::to_string(e[0].triangle) + ", " + std::to_string(e[1].triangle) +
          ", " + std::to_string(e[2].triangle) + (e.size() > 3 ? ", ..." : "") +
          "): the mesh is not edge-manifold there and cannot be repaired");
    } else if (e.size() == 2) {
      across[3 * e[0].triangle + e[0].side] = 3 * e[1].triangle + e[1].side;
      across[3 * e[1].triangle + e[1].side] = 3 * e[0].triangle + e[0].side;
    }
    return status.ok();
  });
  if (!status.ok()) return status;
  const size_t n = faces->size();
  std::vector<int8_t> flip(n, -1);  // -1 unvisited, 0 kept, 1 flipped
  auto from = [&](int32_t f, int side) {
    const Triangle& t = (*faces)[f];
    return flip[f] ? t[(side + 1) % 3] : t[side];
  };
  std::vector<int32_t> queue, component;
  for (size_t seed = 0; seed < n; ++seed) {
    if (flip[seed] >= 0) continue;
    ++report->components;
    flip[seed] = 0;
    queue = {static_cast<int32_t>(seed)};
    component.clear();
    bool closed = true;
    while (!queue.empty()) {
      if (!ticker.Tick()) return ticker.status();
      const int32_t f = queue.back();
      queue.pop_back();
      component.push_back(f);
      for (int side = 0; side < 3; ++side) {
        const int32_t other = across[3 * f + side];
        if (other < 0) {
          closed = false;
          continue;
        }
        const int32_t g = other / 3, gs = other % 3;
        // Consistent when the shared edge starts at different corners.
        const bool agree_if_kept = (*faces)[g][gs] != from(f, side);
        if (flip[g] < 0) {
          flip[g] = agree_if_kept ? 0 : 1;
          queue.push_back(g);
        } else if (from(g, gs) == from(f, side)) {
          return InvalidArgument(
              "faces " + std::to_string(f) + " and " + std::to_string(g) +
              " cannot be oriented consistently: their component is not "
              "orientable (a Moebius-like band)");
        }
      }
    }
    if (closed) {
      // Outward: the signed volume of a closed component is positive.
      double volume = 0;
      for (int32_t f : component) {
        Triangle t = (*faces)[f];
        if (flip[f]) std::swap(t[1], t[2]);
        volume += Dot(v[t[0]], Cross(v[t[1]], v[t[2]]));
      }
      if (volume < 0) {
        for (int32_t f : component) flip[f] = 1 - flip[f];
      }
    }
  }
  for (size_t f = 0; f < n; ++f) {
    if (flip[f] == 1) {
      std::swap((*faces)[f][1], (*faces)[f][2]);
      ++report->reoriented_faces;
    }
  }
  return OkStatus();
}

// Vertices whose faces form more than one fan (joined across edges).
Status CountNonManifoldVertices(size_t vertex_count,
                                const std::vector<Triangle>& faces,
                                RunTicker& ticker, int64_t* count) {
  // Union-find over face corners: corners of one vertex in faces sharing an
  // edge through it are one fan.
  UnionFind corners(3 * faces.size());
  auto corner = [&](int32_t f, int32_t v) {
    for (int k = 0; k < 3; ++k) {
      if (faces[f][k] == v) return 3 * f + k;
    }
    return -1;
  };
  EdgeIndex index;
  if (!BuildEdgeIndex(faces, ticker, &index)) return ticker.status();
  bool stopped = false;
  ForEachEdge(index, [&](const EdgeUses& e) {
    if (!ticker.Tick()) return !(stopped = true);
    if (e.size() == 2) {
      for (int32_t v : {e.lo(), e.hi()}) {
        corners.Join(corner(e[0].triangle, v), corner(e[1].triangle, v));
      }
    }
    return true;
  });
  if (stopped) return ticker.status();
  std::vector<int32_t> fans(vertex_count, 0);
  for (size_t c = 0; c < 3 * faces.size(); ++c) {
    if (!ticker.Tick()) return ticker.status();
    if (corners.Find(static_cast<int32_t>(c)) == static_cast<int32_t>(c)) {
      ++fans[faces[c / 3][c % 3]];
    }
  }
  *count =
      std::count_if(fans.begin(), fans.end(), [](int32_t k) { return k > 1; });
  return OkStatus();
}

}  // namespace

std::string RepairReport::Summary() const {
  std::ostringstream s;
  s << "merged " << merged_vertices << " duplicate vertices, dropped "
    << degenerate_faces << " degenerate and " << duplicate_faces
    << " duplicate faces, triangulated " << triangulated_polygons
    << " polygons, reoriented " << reoriented_faces << " faces; "
    << non_manifold_vertices << " non-manifold vertices, " << components
    << " components";
  return s.str();
}

Status RepairMesh(const PolygonSoup& soup, MeshData* out,
                  RepairReport* report) {
  return RepairMesh(soup, Control{}, out, report);
}

Status RepairMesh(const PolygonSoup& soup, const Control& control,
                  MeshData* out, RepairReport* report) {
  *report = {};
  RunTicker ticker(control, "the repair of the mesh");
  // Merge identical coordinates, first occurrence first.
  PolygonSoup merged;
  std::unordered_map<Vec3, int32_t, VecHash> first;
  report->vertex_map.resize(soup.vertices.size());
  for (size_t i = 0; i < soup.vertices.size(); ++i) {
    if (!ticker.Tick()) return ticker.status();
    auto [it, added] = first.emplace(
        soup.vertices[i], static_cast<int32_t>(merged.vertices.size()));
    if (added) {
      merged.vertices.push_back(soup.vertices[i]);
    } else {
      ++report->merged_vertices;
    }
    report->vertex_map[i] = it->second;
  }
  std::vector<int32_t> merged_origin;  // merged face -> soup face
  for (size_t i = 0; i < soup.faces.size(); ++i) {
    if (!ticker.Tick()) return ticker.status();
    const auto& face = soup.faces[i];
    std::vector<int32_t> f;
    for (int32_t v : face) {
      if (v < 0 || static_cast<size_t>(v) >= soup.vertices.size()) {
        return InvalidArgument("face " + std::to_string(i) +
                               " has vertex index " + std::to_string(v) +
                               ", outside 0.." +
                               std::to_string(soup.vertices.size() - 1));
      }
      const int32_t m = report->vertex_map[v];
      if (f.empty() || f.back() != m) f.push_back(m);
    }
    while (f.size() > 1 && f.front() == f.back()) f.pop_back();
    std::vector<int32_t> sorted = f;
    std::sort(sorted.begin(), sorted.end());
    if (f.size() < 3 ||
        std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      ++report->degenerate_faces;
      continue;
    }
    if (f.size() > 3) ++report->triangulated_polygons;
    merged.faces.push_back(std::move(f));
    merged_origin.push_back(static_cast<int32_t>(i));
  }
  MeshData tri;
  std::vector<int32_t> tri_origin;
  Status s = TriangulateSoup(merged, control, &tri, &tri_origin);
  if (!s.ok()) return s;
  if (!ticker.Poll()) return ticker.status();
  out->vertices = std::move(tri.vertices);
  out->triangles.clear();
  // Duplicates by sorting (corner set, position): the first one is kept.
  std::vector<std::pair<Triangle, int32_t>> keys;
  keys.reserve(tri.triangles.size());
  for (size_t f = 0; f < tri.triangles.size(); ++f) {
    Triangle key = tri.triangles[f];
    std::sort(key.begin(), key.end());
    keys.emplace_back(key, static_cast<int32_t>(f));
  }
  std::sort(keys.begin(), keys.end());
  std::vector<bool> duplicate(tri.triangles.size(), false);
  for (size_t k = 1; k < keys.size(); ++k) {
    if (keys[k].first == keys[k - 1].first) duplicate[keys[k].second] = true;
  }
  keys = {};
  if (!ticker.Poll()) return ticker.status();
  for (size_t f = 0; f < tri.triangles.size(); ++f) {
    const Triangle& t = tri.triangles[f];
    if (ZeroArea(out->vertices, t)) {
      ++report->degenerate_faces;
    } else if (duplicate[f]) {
      ++report->duplicate_faces;
    } else {
      out->triangles.push_back(t);
      report->face_origin.push_back(merged_origin[tri_origin[f]]);
    }
  }
  if (out->triangles.empty()) {
    return InvalidArgument(
        "nothing is left of the mesh after repair: its " +
        std::to_string(soup.faces.size()) + " faces are all degenerate (" +
        std::to_string(report->degenerate_faces) + ") or duplicates (" +
        std::to_string(report->duplicate_faces) + ")");
  }
  if (!ticker.Poll()) return ticker.status();
  s = Orient(out->vertices, &out->triangles, ticker, report);
  if (!s.ok()) return s;
  return CountNonManifoldVertices(out->vertices.size(), out->triangles, ticker,
                                  &report->non_manifold_vertices);
}

}  // namespace dot

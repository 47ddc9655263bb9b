// SPDX-License-Identifier: AGPL-3.0-or-later
#include "dot/mesh_repair.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <numeric>
#include <sstream>
#include <tuple>

#include "mesh/edge_index.h"
#include "mesh_io/polygon_triangles.h"
#include "util/run_control.h"
#include "util/union_find.h"

namespace dot {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

bool ZeroArea(const std::vector<Vec3>& v, const Triangle& t) {
  auto p = [&](int32_t i) { return K::Point_3(v[i].x, v[i].y, v[i].z); };
  return CGAL::collinear(p(t[0]), p(t[1]), p(t[2]));  // exact
}

// Flips faces so that each manifold edge runs opposite ways in its two
// faces, component by component (breadth first from each component's
// first face); closed components end up with positive volume. `index`
// receives the faces' edge index; flips keep its edges and triangles (not
// its sides).
Status Orient(const std::vector<Vec3>& v, std::vector<Triangle>* faces,
              RunTicker& ticker, RepairReport* report, EdgeIndex* edges) {
  EdgeIndex& index = *edges;
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

// Vertices whose faces form more than one fan (joined across edges);
// `index`: the faces' edge index (its sides are not used).
Status CountNonManifoldVertices(size_t vertex_count,
                                const std::vector<Triangle>& faces,
                                const EdgeIndex& index, RunTicker& ticker,
                                int64_t* count) {
  // Union-find over face corners: corners of one vertex in faces sharing an
  // edge through it are one fan.
  UnionFind corners(3 * faces.size());
  auto corner = [&](int32_t f, int32_t v) {
    for (int k = 0; k < 3; ++k) {
      if (faces[f][k] == v) return 3 * f + k;
    }
    return -1;
  };
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

// The distinct coordinates of `v` in order of first occurrence into
// `merged`, and each vertex's id among them into `map`. Sorting ids by
// coordinates needs 4 bytes a vertex where a hash map took about 60.
Status MergeVertices(const std::vector<Vec3>& v, RunTicker& ticker,
                     std::vector<int32_t>* map, std::vector<Vec3>* merged) {
  for (size_t i = 0; i < v.size(); ++i) {
    if (!ticker.Tick()) return ticker.status();
    if (!IsFinite(v[i])) {  // and the sort below needs an order
      return InvalidArgument("vertex " + std::to_string(i) +
                             " has a non-finite coordinate");
    }
  }
  std::vector<int32_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  tbb::parallel_sort(order.begin(), order.end(), [&v](int32_t a, int32_t b) {
    const Vec3 &p = v[a], &q = v[b];
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    if (p.z != q.z) return p.z < q.z;
    return a < b;  // the first occurrence leads its run
  });
  if (!ticker.Poll()) return ticker.status();
  // Each vertex -> the first occurrence of its coordinates, then (in id
  // order, where that first one comes earlier) -> its merged id.
  map->resize(v.size());
  for (size_t k = 0; k < order.size(); ++k) {
    const bool same = k > 0 && v[order[k]] == v[order[k - 1]];
    (*map)[order[k]] = same ? (*map)[order[k - 1]] : order[k];
  }
  order = {};
  merged->clear();
  for (size_t i = 0; i < v.size(); ++i) {
    if (!ticker.Tick()) return ticker.status();
    const int32_t first = (*map)[i];
    if (first == static_cast<int32_t>(i)) {
      (*map)[i] = static_cast<int32_t>(merged->size());
      merged->push_back(v[i]);
    } else {
      (*map)[i] = (*map)[first];
    }
  }
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

namespace {

// RepairMesh; when `owned` (== &soup) is given, it is released as soon as
// its faces are converted, before orientation, the repair's largest step.
Status Repair(const PolygonSoup& soup, PolygonSoup* owned,
              const Control& control, MeshData* out, RepairReport* report) {
  *report = {};
  RunTicker ticker(control, "the repair of the mesh");
  Status s =
      MergeVertices(soup.vertices, ticker, &report->vertex_map, &out->vertices);
  if (!s.ok()) return s;
  report->merged_vertices =
      static_cast<int64_t>(soup.vertices.size() - out->vertices.size());
  // Faces over the merged ids, in order: a corner repeated next to itself
  // dropped, a face left with fewer than 3 corners or a repeated one
  // degenerate, a polygon triangulated.
  std::vector<Triangle> tri;
  std::vector<int32_t> tri_origin;  // triangle -> soup face
  tri.reserve(soup.faces.corners() / 3);
  tri_origin.reserve(soup.faces.corners() / 3);
  std::vector<int32_t> corners, sorted;
  for (size_t i = 0; i < soup.faces.size(); ++i) {
    if (!ticker.Tick()) return ticker.status();
    corners.clear();
    for (int32_t v : soup.faces[i]) {
      if (v < 0 || static_cast<size_t>(v) >= soup.vertices.size()) {
        return InvalidArgument("face " + std::to_string(i) +
                               " has vertex index " + std::to_string(v) +
                               ", outside 0.." +
                               std::to_string(soup.vertices.size() - 1));
      }
      const int32_t m = report->vertex_map[v];
      if (corners.empty() || corners.back() != m) corners.push_back(m);
    }
    while (corners.size() > 1 && corners.front() == corners.back())
      corners.pop_back();
    bool repeated = corners.size() < 3;
    if (corners.size() == 3) {  // most faces: no sort
      repeated = corners[0] == corners[1] || corners[1] == corners[2] ||
                 corners[0] == corners[2];
    } else if (!repeated) {
      sorted = corners;
      std::sort(sorted.begin(), sorted.end());
      repeated =
          std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
    }
    if (repeated) {
      ++report->degenerate_faces;
      continue;
    }
    if (corners.size() == 3) {
      tri.push_back({corners[0], corners[1], corners[2]});
    } else {
      ++report->triangulated_polygons;
      s = TriangulatePolygon(
          out->vertices,
          FaceView(corners.data(), corners.data() + corners.size()), control,
          &tri);
      if (!s.ok()) return s;
    }
    tri_origin.resize(tri.size(), static_cast<int32_t>(i));
  }
  const size_t soup_faces = soup.faces.size();
  if (owned != nullptr) *owned = {};  // `soup` is not read after this
  if (!ticker.Poll()) return ticker.status();
  // Duplicates: ids sorted by (corner set, id), the first of each set
  // kept; zero-area faces (exact) dropped. Both in parallel, and the kept
  // faces compacted in place: no second copy of the faces.
  auto corner_set = [&tri](int32_t f) {
    Triangle k = tri[f];
    if (k[0] > k[1]) std::swap(k[0], k[1]);
    if (k[1] > k[2]) std::swap(k[1], k[2]);
    if (k[0] > k[1]) std::swap(k[0], k[1]);
    return k;
  };
  // Faces bucketed by their lowest corner (a counting sort: linear), then
  // each bucket's few faces ordered by (corner set, id).
  const auto nf = static_cast<int32_t>(tri.size());
  std::vector<int32_t> start(out->vertices.size() + 1, 0);
  for (int32_t f = 0; f < nf; ++f) ++start[corner_set(f)[0] + 1];
  for (size_t v = 0; v + 1 < start.size(); ++v) start[v + 1] += start[v];
  std::vector<int32_t> by_corners(tri.size());
  {
    std::vector<int32_t> next(start.begin(), start.end() - 1);
    for (int32_t f = 0; f < nf; ++f) by_corners[next[corner_set(f)[0]]++] = f;
  }
  std::vector<uint8_t> drop(tri.size(), 0);  // 1 duplicate, 2 zero area
  for (size_t v = 0; v + 1 < start.size(); ++v) {
    const auto first = by_corners.begin() + start[v];
    const auto last = by_corners.begin() + start[v + 1];
    std::sort(first, last, [&](int32_t a, int32_t b) {
      const Triangle ka = corner_set(a), kb = corner_set(b);
      return ka != kb ? ka < kb : a < b;
    });
    for (auto it = first; it != last && it + 1 != last; ++it) {
      if (corner_set(it[1]) == corner_set(it[0])) drop[it[1]] = 1;
    }
  }
  by_corners = {};
  start = {};
  tbb::parallel_for(size_t{0}, tri.size(), [&](size_t f) {
    if (ZeroArea(out->vertices, tri[f])) drop[f] = 2;
  });
  if (!ticker.Poll()) return ticker.status();
  size_t kept = 0;
  for (size_t f = 0; f < tri.size(); ++f) {
    if (drop[f] == 2) {
      ++report->degenerate_faces;
    } else if (drop[f] == 1) {
      ++report->duplicate_faces;
    } else {
      tri[kept] = tri[f];
      tri_origin[kept++] = tri_origin[f];
    }
  }
  tri.resize(kept);
  tri_origin.resize(kept);
  out->triangles = std::move(tri);
  report->face_origin = std::move(tri_origin);
  if (out->triangles.empty()) {
    return InvalidArgument(
        "nothing is left of the mesh after repair: its " +
        std::to_string(soup_faces) + " faces are all degenerate (" +
        std::to_string(report->degenerate_faces) + ") or duplicates (" +
        std::to_string(report->duplicate_faces) + ")");
  }
  if (!ticker.Poll()) return ticker.status();
  EdgeIndex edges;  // built once for both
  s = Orient(out->vertices, &out->triangles, ticker, report, &edges);
  if (!s.ok()) return s;
  return CountNonManifoldVertices(out->vertices.size(), out->triangles, edges,
                                  ticker, &report->non_manifold_vertices);
}

}  // namespace

Status RepairMesh(const PolygonSoup& soup, const Control& control,
                  MeshData* out, RepairReport* report) {
  return Repair(soup, nullptr, control, out, report);
}

Status RepairMesh(PolygonSoup&& soup, const Control& control, MeshData* out,
                  RepairReport* report) {
  return Repair(soup, &soup, control, out, report);
}

}  // namespace dot

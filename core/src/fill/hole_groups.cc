// SPDX-License-Identifier: AGPL-3.0-or-later
// Holes with islands: which border loops one patch joins. Automatic: the
// outer border of a smaller piece of the mesh is an island of the nearest
// wider loop of a larger piece whose box holds it. Explicit: groups of loop
// ids.
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "dot/fill_holes.h"
#include "mesh/face_tree.h"
#include "util/run_control.h"
#include "util/union_find.h"

namespace dot {
namespace {

// A loop's vertices, their centre and box.
struct Outline {
  std::vector<Vec3> points;
  Vec3 centre;
  Box3 box;
  double diameter = 0;
};

Outline MakeOutline(const MeshData& mesh, const HoleLoop& loop) {
  Outline o;
  Vec3 sum;
  for (int32_t id : loop.vertices) {
    o.points.push_back(mesh.vertices[id]);
    o.box.Add(mesh.vertices[id]);
    sum = sum + mesh.vertices[id];
  }
  o.centre = (1.0 / static_cast<double>(o.points.size())) * sum;
  o.diameter = loop.diameter;
  return o;
}

// A loop's box grown by a quarter of its diameter each way: a flat rim's
// box is a thin slab, and an island may bulge out of the rim's plane (a
// hole in a sphere).
Box3 Reach(const Outline& o) {
  const double pad = 0.25 * o.diameter;
  Box3 b = o.box;
  b.lo = b.lo - Vec3{pad, pad, pad};
  b.hi = b.hi + Vec3{pad, pad, pad};
  return b;
}

// At most this many rims are weighed per island (the narrowest whose
// reach holds it): a mesh of thousands of overlapping copies must not
// make the pairs quadratic.
constexpr size_t kRimsPerIsland = 16;

// Mean distance from a vertex of `inner` to the nearest vertex of `outer`,
// over at most kGapSamples of each, evenly spaced along the loops: a
// choice between rims, bounded for rims of 100,000 vertices.
constexpr size_t kGapSamples = 128;

double MeanGap(const Outline& inner, const Outline& outer) {
  const size_t ni = inner.points.size(), no = outer.points.size();
  const size_t si = std::min(ni, kGapSamples), so = std::min(no, kGapSamples);
  double sum = 0;
  for (size_t a = 0; a < si; ++a) {
    const Vec3& p = inner.points[a * ni / si];
    double best = std::numeric_limits<double>::infinity();
    for (size_t b = 0; b < so; ++b) {
      best = std::min(best, Distance(p, outer.points[b * no / so]));
    }
    sum += best;
  }
  return sum / static_cast<double>(si);
}

// The piece of the mesh (faces joined by shared vertices) of each loop,
// and the faces of each piece (by its root vertex).
std::vector<int32_t> LoopPieces(const MeshData& mesh,
                                const std::vector<HoleLoop>& loops,
                                std::vector<int64_t>* faces) {
  UnionFind pieces(mesh.vertices.size());
  for (const Triangle& t : mesh.triangles) {
    pieces.Join(t[0], t[1]);
    pieces.Join(t[1], t[2]);
  }
  faces->assign(mesh.vertices.size(), 0);
  for (const Triangle& t : mesh.triangles) ++(*faces)[pieces.Find(t[0])];
  std::vector<int32_t> piece;
  for (const HoleLoop& l : loops) piece.push_back(pieces.Find(l.vertices[0]));
  return piece;
}

Status ExplicitGroups(const std::vector<HoleLoop>& loops,
                      const std::vector<std::vector<int32_t>>& join,
                      std::vector<int32_t>* rim, std::vector<bool>* named) {
  for (size_t g = 0; g < join.size(); ++g) {
    const std::string group = "join group " + std::to_string(g);
    if (join[g].size() < 2) {
      return InvalidArgument(group + " names fewer than 2 loops");
    }
    int32_t widest = -1;
    for (int32_t id : join[g]) {
      if (id < 0 || static_cast<size_t>(id) >= loops.size()) {
        return InvalidArgument(group + ": there is no hole " +
                               std::to_string(id) + ": the mesh has " +
                               std::to_string(loops.size()) + " holes");
      }
      if ((*named)[id]) {
        return InvalidArgument(group + ": hole " + std::to_string(id) +
                               " is named twice");
      }
      (*named)[id] = true;
      if (widest < 0 || loops[id].diameter > loops[widest].diameter) {
        widest = id;
      }
    }
    // Loops through one vertex cannot bound one surface of genus 0 there.
    std::vector<int32_t> vertices;
    for (int32_t id : join[g]) {
      vertices.insert(vertices.end(), loops[id].vertices.begin(),
                      loops[id].vertices.end());
    }
    std::sort(vertices.begin(), vertices.end());
    auto twice = std::adjacent_find(vertices.begin(), vertices.end());
    if (twice != vertices.end()) {
      return InvalidArgument(group + ": two of its holes share vertex " +
                             std::to_string(*twice));
    }
    for (int32_t id : join[g]) (*rim)[id] = widest;
  }
  return OkStatus();
}

}  // namespace

Status GroupHoleLoops(const MeshData& mesh, const std::vector<HoleLoop>& loops,
                      IslandMode mode,
                      const std::vector<std::vector<int32_t>>& join,
                      std::vector<int32_t>* rim, const Control& control) {
  rim->resize(loops.size());
  std::iota(rim->begin(), rim->end(), 0);
  std::vector<bool> named(loops.size(), false);
  Status s = ExplicitGroups(loops, join, rim, &named);
  if (!s.ok() || mode == IslandMode::kOff || loops.size() < 2) return s;

  RunTicker ticker(control, "the search for islands");
  std::vector<int64_t> faces;
  const std::vector<int32_t> piece = LoopPieces(mesh, loops, &faces);
  std::vector<Outline> outlines;
  for (const HoleLoop& l : loops) outlines.push_back(MakeOutline(mesh, l));
  // A piece's widest loop is its outer border; its other loops are holes.
  std::vector<int32_t> widest(mesh.vertices.size(), -1);
  for (const HoleLoop& l : loops) {
    int32_t& w = widest[piece[l.id]];
    if (w < 0 || l.diameter > loops[w].diameter) w = l.id;
  }
  // Islands first, then their rims: a loop that is an island cannot be a
  // rim (the outer border of a ring-shaped island is joined to the hole
  // around it; a further island inside the ring joins the ring's hole).
  // Which loops' boxes hold which outer borders' centres (CGAL's box
  // intersection: thousands of fragments and holes without a quadratic
  // scan).
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int32_t>;
  std::vector<Box> centres, boxes;
  for (size_t i = 0; i < loops.size(); ++i) {
    const auto id = static_cast<int32_t>(i);
    const Outline& o = outlines[i];
    if (!named[i] && widest[piece[i]] == id) {
      const Vec3& c = o.centre;
      centres.emplace_back(CGAL::Bbox_3(c.x, c.y, c.z, c.x, c.y, c.z), id);
    }
    const Box3 r = Reach(o);
    boxes.emplace_back(
        CGAL::Bbox_3(r.lo.x, r.lo.y, r.lo.z, r.hi.x, r.hi.y, r.hi.z), id);
  }
  // The cheap conditions are tested as pairs come, and each island keeps
  // its kRimsPerIsland narrowest rims, so memory stays linear.
  std::vector<std::vector<int32_t>> around(loops.size());
  struct Stop {};
  try {
    CGAL::box_intersection_d(centres.begin(), centres.end(), boxes.begin(),
                             boxes.end(), [&](const Box& c, const Box& b) {
                               if (!ticker.Tick()) throw Stop{};
                               const int32_t i = c.info(), r = b.info();
                               if (piece[r] == piece[i] || named[r] ||
                                   faces[piece[r]] <= faces[piece[i]] ||
                                   !(loops[r].diameter > loops[i].diameter)) {
                                 return;
                               }
                               std::vector<int32_t>& a = around[i];
                               auto narrower = [&](int32_t x, int32_t y) {
                                 return loops[x].diameter != loops[y].diameter
                                            ? loops[x].diameter <
                                                  loops[y].diameter
                                            : x < y;
                               };
                               if (a.size() < kRimsPerIsland) {
                                 a.push_back(r);
                                 std::push_heap(a.begin(), a.end(), narrower);
                               } else if (narrower(r, a.front())) {
                                 std::pop_heap(a.begin(), a.end(), narrower);
                                 a.back() = r;
                                 std::push_heap(a.begin(), a.end(), narrower);
                               }
                             });
  } catch (const Stop&) {
    return ticker.status();
  }
  auto candidates = [&](int32_t i, const std::vector<bool>* islands,
                        int32_t* nearest) -> Status {
    *nearest = -1;
    std::sort(around[i].begin(), around[i].end());  // deterministic ties
    double best = std::numeric_limits<double>::infinity();
    for (int32_t r : around[i]) {
      if (!ticker.Tick()) return ticker.status();
      if (islands != nullptr && (*islands)[r]) continue;
      // Near: within the rim's diameter, on average.
      const double gap = MeanGap(outlines[i], outlines[r]);
      if (gap <= loops[r].diameter && gap < best) {
        best = gap;
        *nearest = r;
      }
    }
    return OkStatus();
  };
  std::vector<bool> island(loops.size(), false);
  for (size_t i = 0; i < loops.size(); ++i) {
    int32_t r = -1;
    Status c = candidates(static_cast<int32_t>(i), nullptr, &r);
    if (!c.ok()) return c;
    island[i] = r >= 0;
  }
  for (size_t i = 0; i < loops.size(); ++i) {
    if (!island[i]) continue;
    int32_t r = -1;
    Status c = candidates(static_cast<int32_t>(i), &island, &r);
    if (!c.ok()) return c;
    if (r >= 0) (*rim)[i] = r;
  }
  return OkStatus();
}

}  // namespace dot

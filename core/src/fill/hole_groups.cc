// SPDX-License-Identifier: AGPL-3.0-or-later
// Holes with islands: which border loops one patch joins. Automatic: a loop
// is an island of the innermost loop around it, when that loop belongs to
// another piece of the mesh. Explicit: groups of loop ids.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "dot/fill_holes.h"
#include "mesh/face_tree.h"
#include "polygon/plane_fit.h"
#include "util/run_control.h"
#include "util/union_find.h"

namespace dot {
namespace {

// A loop seen along its least-squares plane's normal.
struct Outline {
  Vec3 origin, u, v, normal;  // orthonormal frame of the plane
  std::vector<double> x, y;   // the loop's vertices in (u, v)
  Box3 box;
  double diameter = 0;
};

Outline MakeOutline(const MeshData& mesh, const HoleLoop& loop) {
  Outline o;
  std::vector<Vec3> points;
  for (int32_t id : loop.vertices) {
    points.push_back(mesh.vertices[id]);
    o.box.Add(mesh.vertices[id]);
  }
  // Newell's vector area: the direction in which the loop encloses the
  // most area, also for a loop far from planar (the rim of a hole over the
  // tip of a limb), where a least-squares plane may lie across the hole.
  Vec3 area, centroid;
  for (size_t i = 0; i < points.size(); ++i) {
    area = area + Cross(points[i], points[(i + 1) % points.size()]);
    centroid = centroid + points[i];
  }
  o.origin = (1.0 / static_cast<double>(points.size())) * centroid;
  o.normal = Norm(area) > 0 ? Normalized(area) : FitPlane(points).normal;
  const Vec3 axis = std::abs(o.normal.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  o.u = Normalized(Cross(o.normal, axis));
  o.v = Cross(o.normal, o.u);
  for (const Vec3& p : points) {
    o.x.push_back(Dot(p - o.origin, o.u));
    o.y.push_back(Dot(p - o.origin, o.v));
  }
  o.diameter = loop.diameter;
  return o;
}

// Winding number of the outline around (px, py).
int Winding(const Outline& o, double px, double py) {
  int w = 0;
  const size_t n = o.x.size();
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    const double ax = o.x[i] - px, ay = o.y[i] - py;
    const double bx = o.x[j] - px, by = o.y[j] - py;
    const double side = ax * by - ay * bx;
    if (ay <= 0 && by > 0 && side > 0) ++w;
    if (ay > 0 && by <= 0 && side < 0) --w;
  }
  return w;
}

// Whether `outer` is around the centre of a loop: seen along its normal the
// centre is inside it, within half its diameter of its plane. The centre,
// not every vertex: a ring hole one face wide on a curved surface lets an
// island's own border overhang its rim's outline.
bool Around(const Outline& outer, const Vec3& centre) {
  const Vec3 d = centre - outer.origin;
  return std::abs(Dot(d, outer.normal)) <= 0.5 * outer.diameter &&
         Winding(outer, Dot(d, outer.u), Dot(d, outer.v)) != 0;
}

// The piece of the mesh (faces joined by shared vertices) of each loop.
std::vector<int32_t> LoopComponents(const MeshData& mesh,
                                    const std::vector<HoleLoop>& loops) {
  UnionFind pieces(mesh.vertices.size());
  for (const Triangle& t : mesh.triangles) {
    pieces.Join(t[0], t[1]);
    pieces.Join(t[1], t[2]);
  }
  std::vector<int32_t> component;
  for (const HoleLoop& l : loops) {
    component.push_back(pieces.Find(l.vertices[0]));
  }
  return component;
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
  const std::vector<int32_t> component = LoopComponents(mesh, loops);
  std::vector<Outline> outlines;
  for (const HoleLoop& l : loops) outlines.push_back(MakeOutline(mesh, l));
  // Widest first: the innermost loop around a loop is the last one found.
  std::vector<int32_t> order(loops.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) {
    return loops[a].diameter > loops[b].diameter;
  });
  for (size_t k = 0; k < order.size(); ++k) {
    const int32_t island = order[k];
    if (named[island]) continue;
    const Outline& in = outlines[island];
    const Vec3& centre = in.origin;
    int32_t innermost = -1;
    for (size_t j = 0; j < k; ++j) {
      if (!ticker.Tick()) return ticker.status();
      const int32_t outer = order[j];
      const Outline& out = outlines[outer];
      if (!(out.diameter > in.diameter)) continue;
      // Cheap reject: the centre must be within half a diameter of the
      // outer loop's box (its plane test allows that much).
      Box3 reach = out.box;
      const Vec3 pad{0.5 * out.diameter, 0.5 * out.diameter,
                     0.5 * out.diameter};
      reach.lo = reach.lo - pad;
      reach.hi = reach.hi + pad;
      Box3 point;
      point.Add(centre);
      if (!reach.Meets(point)) continue;
      if (Around(out, centre)) innermost = outer;
    }
    // An island's rim is a hole's rim, never itself an island.
    if (innermost < 0 || component[innermost] == component[island] ||
        named[innermost] || (*rim)[innermost] != innermost) {
      continue;
    }
    (*rim)[island] = innermost;
  }
  return OkStatus();
}

}  // namespace dot

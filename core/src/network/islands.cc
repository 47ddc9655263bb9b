// SPDX-License-Identifier: AGPL-3.0-or-later
// Lone loops into islands: a closed curve drawn alone on a face of the
// network (a circle on a box's lid, a ring inside a ring) is a boundary of
// that face's patch. Alone, the rotation system makes it a disk that
// overlaps the face around it, and one of the two is left out.
#include "network/islands.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "network/seam.h"
#include "util/union_find.h"

namespace dot {
namespace {

// A face's outer loop as seen along its normal.
struct Outline {
  std::vector<int32_t> vertices;
  Vec3 vector_area;  // half the sum of p_i x p_i+1 (Newell)
  Vec3 centre, normal, u, v;
  double area = 0;           // |vector_area|
  double reach = 0;          // how far from its plane a point may lie in it
  Vec3 lo, hi;               // bounding box, grown by reach
  std::vector<double> x, y;  // the loop in the plane's (u, v) coordinates
};

Outline MakeOutline(const NetworkGraph& g, const std::vector<CurveUse>& loop) {
  Outline o;
  o.vertices = LoopVertices(g, loop);
  const size_t n = o.vertices.size();
  for (size_t k = 0; k < n; ++k) {
    const Vec3& p = g.vertices[o.vertices[k]];
    const Vec3& q = g.vertices[o.vertices[(k + 1) % n]];
    o.vector_area = o.vector_area + 0.5 * Cross(p, q);
    o.centre = o.centre + (1.0 / static_cast<double>(n)) * p;
  }
  o.area = Norm(o.vector_area);
  if (!(o.area > 0)) return o;
  o.normal = (1.0 / o.area) * o.vector_area;
  // Any unit vector across the normal, and the third of the frame.
  const Vec3 axis = std::abs(o.normal.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  o.u = Normalized(Cross(o.normal, axis));
  o.v = Cross(o.normal, o.u);
  double off_plane = 0;
  o.lo = o.hi = g.vertices[o.vertices[0]];
  for (int32_t id : o.vertices) {
    const Vec3 d = g.vertices[id] - o.centre;
    off_plane = std::max(off_plane, std::abs(Dot(d, o.normal)));
    o.x.push_back(Dot(d, o.u));
    o.y.push_back(Dot(d, o.v));
    const Vec3& p = g.vertices[id];
    o.lo = {std::min(o.lo.x, p.x), std::min(o.lo.y, p.y),
            std::min(o.lo.z, p.z)};
    o.hi = {std::max(o.hi.x, p.x), std::max(o.hi.y, p.y),
            std::max(o.hi.z, p.z)};
  }
  // A curved face's loop already leaves its plane; a quarter of the
  // radius more lets a loop drawn on a gently domed face in, and keeps out
  // a tube's far rim (a tube is rarely shorter than half its radius).
  o.reach = off_plane + 0.25 * std::sqrt(o.area / M_PI);
  const Vec3 grow{o.reach, o.reach, o.reach};
  o.lo = o.lo - grow;
  o.hi = o.hi + grow;
  return o;
}

// Whether p is inside the outline seen along its normal (winding number).
bool Inside(const Outline& o, const Vec3& p) {
  const Vec3 d = p - o.centre;
  if (std::abs(Dot(d, o.normal)) > o.reach) return false;
  const double px = Dot(d, o.u), py = Dot(d, o.v);
  int winding = 0;
  const size_t n = o.x.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t m = (k + 1) % n;
    const double side =
        (o.x[m] - o.x[k]) * (py - o.y[k]) - (px - o.x[k]) * (o.y[m] - o.y[k]);
    if (o.y[k] <= py) {
      if (o.y[m] > py && side > 0) ++winding;
    } else if (o.y[m] <= py && side < 0) {
      --winding;
    }
  }
  return winding != 0;
}

bool InBox(const Outline& o, const Vec3& p) {
  return p.x >= o.lo.x && p.x <= o.hi.x && p.y >= o.lo.y && p.y <= o.hi.y &&
         p.z >= o.lo.z && p.z <= o.hi.z;
}

std::vector<CurveUse> Reversed(std::vector<CurveUse> loop) {
  std::reverse(loop.begin(), loop.end());
  for (CurveUse& u : loop) u.reversed = !u.reversed;
  return loop;
}

std::string CurveList(const std::vector<CurveUse>& loop) {
  std::string out;
  for (const CurveUse& u : loop) {
    out += (out.empty() ? "" : " ") + std::to_string(u.curve);
  }
  return out;
}

}  // namespace

std::string_view NetworkIslandsName(NetworkIslands m) {
  switch (m) {
    case NetworkIslands::kInset:
      return "inset";
    case NetworkIslands::kHole:
      return "hole";
    case NetworkIslands::kOff:
      return "off";
  }
  return "unknown";
}

bool PairIslands(const NetworkGraph& g, NetworkIslands mode,
                 std::vector<NetworkCycle>* cycles,
                 std::vector<std::string>* notes, RunTicker* ticker) {
  if (mode == NetworkIslands::kOff || cycles->size() < 2) return true;
  // The network's parts, and how many curves each has.
  UnionFind parts(g.vertices.size());
  std::vector<char> live(g.curves.size(), 0);
  for (const NetworkCycle& c : *cycles) {
    for (const auto& loop : c.loops) {
      for (const CurveUse& u : loop) live[u.curve] = 1;
    }
  }
  for (size_t c = 0; c < g.curves.size(); ++c) {
    if (live[c]) {
      parts.Join(g.curves[c].vertices.front(), g.curves[c].vertices.back());
    }
  }
  std::vector<int32_t> curves_in(g.vertices.size(), 0);
  for (size_t c = 0; c < g.curves.size(); ++c) {
    if (live[c]) ++curves_in[parts.Find(g.curves[c].vertices.front())];
  }
  auto part_of = [&](const NetworkCycle& c) {
    return parts.Find(g.curves[c.loops[0][0].curve].vertices.front());
  };

  const size_t count = cycles->size();
  std::vector<Outline> outlines(count);
  std::vector<char> usable(count, 0), lone(count, 0);
  for (size_t k = 0; k < count; ++k) {
    const NetworkCycle& c = (*cycles)[k];
    if (c.loops.size() != 1 || RunsACurveTwice(c.loops[0])) continue;
    outlines[k] = MakeOutline(g, c.loops[0]);
    usable[k] = outlines[k].area > 0;
    lone[k] = static_cast<int32_t>(c.loops[0].size()) == curves_in[part_of(c)];
  }

  // Outer loops first, so that a loop's host has its final direction
  // (an inset loop may have been turned) and is known to be a hole or not.
  std::vector<size_t> order;
  for (size_t l = 0; l < count; ++l) {
    if (lone[l] && usable[l]) order.push_back(l);
  }
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return outlines[a].area > outlines[b].area;
  });
  std::vector<char> dropped(count, 0);
  std::vector<std::pair<size_t, std::string>> pairs;  // (host, loop's curves)
  for (size_t l : order) {
    // The face it lies in: the smallest that holds every point of it.
    const int32_t part = part_of((*cycles)[l]);
    int32_t host = -1;
    for (size_t f = 0; f < count; ++f) {
      if (!usable[f] || part_of((*cycles)[f]) == part) continue;
      if (host >= 0 && outlines[f].area >= outlines[host].area) continue;
      bool inside = true;
      for (int32_t id : outlines[l].vertices) {
        if (!ticker->Tick()) return false;
        const Vec3& p = g.vertices[id];
        if (!InBox(outlines[f], p) || !Inside(outlines[f], p)) {
          inside = false;
          break;
        }
      }
      if (inside) host = static_cast<int32_t>(f);
    }
    // In no face, or in a hole (no surface there): a patch of its own.
    if (host < 0 || dropped[host]) continue;
    NetworkCycle& loop = (*cycles)[l];
    const bool along = Dot(outlines[l].vector_area, outlines[host].normal) > 0;
    // An island runs against its face's outer loop; its own patch faces
    // as that face does.
    (*cycles)[host].loops.push_back(along ? Reversed(loop.loops[0])
                                          : loop.loops[0]);
    if (mode == NetworkIslands::kHole) {
      dropped[l] = 1;
    } else if (!along) {
      loop.loops[0] = Reversed(loop.loops[0]);
      outlines[l].vector_area = -1.0 * outlines[l].vector_area;
      outlines[l].normal = -1.0 * outlines[l].normal;
    }
    pairs.emplace_back(host, CurveList(loop.loops[0]));
  }
  std::vector<int32_t> new_id(count, -1);
  std::vector<NetworkCycle> kept;
  for (size_t k = 0; k < count; ++k) {
    if (dropped[k]) continue;
    new_id[k] = static_cast<int32_t>(kept.size());
    kept.push_back(std::move((*cycles)[k]));
  }
  *cycles = std::move(kept);
  if (notes != nullptr) {
    for (const auto& [f, curves] : pairs) {
      notes->push_back(
          "a lone loop (curves " + curves + ") lies in the face of patch " +
          std::to_string(new_id[f]) + ": an island of it" +
          (mode == NetworkIslands::kHole ? " (a hole)"
                                         : ", and a patch of its own"));
    }
  }
  return true;
}

}  // namespace dot

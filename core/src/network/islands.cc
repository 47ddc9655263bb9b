// SPDX-License-Identifier: AGPL-3.0-or-later
// Lone loops into islands: a closed curve drawn alone on a face of the
// network (a circle on a box's lid, a ring inside a ring) is a boundary of
// that face's patch. Alone, the rotation system makes it a disk that
// overlaps the face around it, which the crossing checks can only keep
// apart from it or leave out.
#include "network/islands.h"

#include <algorithm>
#include <cmath>

#include "network/outline.h"
#include "network/seam.h"
#include "util/union_find.h"

namespace dot {
namespace {

// How far beyond the face's own distance from its plane the loop lies,
// or -1 when the face does not hold it: a vertex outside it seen along its
// normal, an edge crossing its outline there, the loop farther beyond the
// plane than its own radius (or a quarter of the face's: Inside), or
// turned more than 45 degrees from it. -2: the ticker says stop.
double Excess(const NetworkGraph& g, const Outline& face, const Outline& loop,
              RunTicker* ticker) {
  if (std::abs(Dot(face.normal, loop.normal)) < std::sqrt(0.5)) return -1;
  double excess = 0;
  const size_t n = loop.vertices.size();
  for (size_t k = 0; k < n; ++k) {
    if (!ticker->Tick()) return -2;
    const Vec3& p = g.vertices[loop.vertices[k]];
    if (!Inside(face, p)) return -1;
    excess = std::max(
        excess, std::abs(Dot(p - face.centre, face.normal)) - face.off_plane);
  }
  if (excess > loop.radius) return -1;
  for (size_t k = 0; k < n; ++k) {
    if (!ticker->Tick()) return -2;
    if (CrossesOutline(face, g.vertices[loop.vertices[k]],
                       g.vertices[loop.vertices[(k + 1) % n]])) {
      return -1;
    }
  }
  return excess;
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
    // A curved face's loop already leaves its plane; a quarter of the
    // radius more lets a loop drawn on a gently domed face in, and keeps
    // out a tube's far rim (a tube is rarely shorter than half its radius).
    outlines[k] = MakeOutline(g, LoopVertices(g, c.loops[0]), 0.25);
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
    // The face it lies in: of those that hold it, the nearest to it (a
    // thin slab's lid, not its bottom), then the smallest (the ring just
    // around it, not the disk around that).
    const int32_t part = part_of((*cycles)[l]);
    const double tie = 1e-3 * outlines[l].radius;
    int32_t host = -1;
    double host_excess = 0;
    for (size_t f = 0; f < count; ++f) {
      if (!usable[f] || part_of((*cycles)[f]) == part) continue;
      const double excess = Excess(g, outlines[f], outlines[l], ticker);
      if (excess == -2) return false;
      if (excess < 0) continue;
      if (host < 0 || excess < host_excess - tie ||
          (excess <= host_excess + tie &&
           outlines[f].area < outlines[host].area)) {
        host = static_cast<int32_t>(f);
        host_excess = excess;
      }
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

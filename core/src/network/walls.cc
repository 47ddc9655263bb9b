// SPDX-License-Identifier: AGPL-3.0-or-later
// Walls: the patches a rotation system cannot give, where three patches or
// more meet on a curve. In the spirit of Zhuang et al. (2013), who group
// the curves at each junction into the corners of cycles: the corners the
// faces found leave unused are where a further patch may turn.
#include "network/walls.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "network/outline.h"

namespace dot {
namespace {

constexpr int kMaxWallCurves = 8;
constexpr int64_t kMaxSteps = 200000;
constexpr double kFlat = 0.05;  // off its plane, per radius

// Dart 2c + e: curve c leaving from its first vertex (e = 0) or its last.
int32_t JunctionOf(const NetworkGraph& g, int32_t dart) {
  const auto& vs = g.curves[dart / 2].vertices;
  return (dart & 1) ? vs.back() : vs.front();
}

std::pair<int32_t, int32_t> Corner(int32_t a, int32_t b) {
  return {std::min(a, b), std::max(a, b)};
}

CurveUse UseOf(int32_t dart) { return {dart / 2, (dart & 1) == 1}; }

struct Search {
  const NetworkGraph& g;
  const std::set<std::pair<int32_t, int32_t>>& used;
  const std::map<int32_t, std::vector<int32_t>>& darts_at;
  RunTicker* ticker;
  std::vector<std::vector<int32_t>> found;  // darts of each cycle
  std::set<std::vector<int32_t>> seen;      // their sorted curves
  std::vector<int32_t> path;                // darts so far
  std::set<int32_t> visited;                // junctions so far
  int64_t steps = 0;
  bool stopped = false;  // by the ticker
  bool cut = false;      // by the step bound

  bool Unused(int32_t a, int32_t b) const {
    return a / 2 != b / 2 && !used.count(Corner(a, b));
  }

  // `path` leaves junction `start` by path[0]; extend it from its end.
  void Extend(int32_t start) {
    if (stopped || cut) return;
    if (++steps > kMaxSteps) {
      cut = true;
      return;
    }
    if (!ticker->Tick()) {
      stopped = true;
      return;
    }
    const int32_t arrive = path.back() ^ 1;
    const int32_t at = JunctionOf(g, arrive);
    if (at == start) {
      if (path.size() >= 2 && Unused(arrive, path.front())) {
        std::vector<int32_t> key;
        for (int32_t d : path) key.push_back(d / 2);
        std::sort(key.begin(), key.end());
        if (seen.insert(key).second) found.push_back(path);
      }
      return;
    }
    // Each cycle from its least junction only.
    if (at < start || visited.count(at) ||
        static_cast<int>(path.size()) == kMaxWallCurves) {
      return;
    }
    visited.insert(at);
    for (int32_t next : darts_at.at(at)) {
      if (next == arrive || !Unused(arrive, next)) continue;
      path.push_back(next);
      Extend(start);
      path.pop_back();
    }
    visited.erase(at);
  }
};

// Whether the cycle lies flat and holds no other point of the network.
bool IsWall(const NetworkGraph& g, const std::vector<int32_t>& darts,
            const std::vector<char>& live, double* flatness) {
  std::vector<CurveUse> loop;
  std::set<int32_t> own;
  for (int32_t d : darts) {
    loop.push_back(UseOf(d));
    own.insert(d / 2);
  }
  const Outline o = MakeOutline(g, LoopVertices(g, loop), kFlat);
  if (!(o.area > 0) || o.off_plane > kFlat * o.radius) return false;
  *flatness = o.off_plane / o.radius;
  const std::set<int32_t> rim(o.vertices.begin(), o.vertices.end());
  for (size_t c = 0; c < g.curves.size(); ++c) {
    if (!live[c] || own.count(static_cast<int32_t>(c))) continue;
    const auto& vs = g.curves[c].vertices;
    for (size_t k = 0; k < vs.size(); ++k) {
      const Vec3& p = g.vertices[vs[k]];
      // A curve's end on the wall's rim is no point inside it.
      if (!rim.count(vs[k]) && Inside(o, p)) return false;
      if (k + 1 < vs.size() && Inside(o, 0.5 * (p + g.vertices[vs[k + 1]]))) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace

bool FindWalls(const NetworkGraph& g, std::vector<NetworkCycle>* cycles,
               std::vector<std::string>* notes, RunTicker* ticker) {
  std::set<std::pair<int32_t, int32_t>> used;
  std::vector<char> live(g.curves.size(), 0);
  for (const NetworkCycle& c : *cycles) {
    for (const auto& loop : c.loops) {
      for (size_t k = 0; k < loop.size(); ++k) {
        const CurveUse& u = loop[k];
        const CurveUse& next = loop[(k + 1) % loop.size()];
        live[u.curve] = 1;
        // Arriving by u's far end, leaving by next's near end.
        const int32_t arrive = 2 * u.curve + (u.reversed ? 0 : 1);
        const int32_t leave = 2 * next.curve + (next.reversed ? 1 : 0);
        used.insert(Corner(arrive, leave));
      }
    }
  }
  std::map<int32_t, std::vector<int32_t>> darts_at;
  for (size_t c = 0; c < g.curves.size(); ++c) {
    if (!live[c] || g.curves[c].closed()) continue;
    for (int32_t end : {0, 1}) {
      const auto dart = static_cast<int32_t>(2 * c + end);
      darts_at[JunctionOf(g, dart)].push_back(dart);
    }
  }
  Search search{g, used, darts_at, ticker, {}, {}, {}, {}};
  for (const auto& [at, darts] : darts_at) {
    if (darts.size() < 4) continue;  // three curves: every corner is a face's
    for (int32_t d : darts) {
      search.path = {d};
      search.visited = {at};
      search.Extend(at);
    }
  }
  if (search.stopped) return false;
  if (search.cut && notes != nullptr) {
    notes->push_back(
        "the search for walls (a third patch on a curve) "
        "stopped after " +
        std::to_string(kMaxSteps) + " steps");
  }

  // Smallest and flattest first; each unused corner in one wall.
  struct Candidate {
    size_t index;
    double flatness;
  };
  std::vector<Candidate> walls;
  for (size_t k = 0; k < search.found.size(); ++k) {
    double flatness = 0;
    if (IsWall(g, search.found[k], live, &flatness)) {
      walls.push_back({k, flatness});
    }
  }
  std::sort(walls.begin(), walls.end(), [&](const auto& a, const auto& b) {
    const size_t la = search.found[a.index].size();
    const size_t lb = search.found[b.index].size();
    return la != lb ? la < lb : a.flatness < b.flatness;
  });
  std::set<std::pair<int32_t, int32_t>> taken;
  for (const Candidate& w : walls) {
    const auto& darts = search.found[w.index];
    std::vector<std::pair<int32_t, int32_t>> corners;
    for (size_t k = 0; k < darts.size(); ++k) {
      corners.push_back(Corner(darts[k] ^ 1, darts[(k + 1) % darts.size()]));
    }
    if (std::any_of(corners.begin(), corners.end(),
                    [&](const auto& c) { return taken.count(c) > 0; })) {
      continue;
    }
    taken.insert(corners.begin(), corners.end());
    std::vector<CurveUse> loop;
    std::string ids;
    for (int32_t d : darts) {
      loop.push_back(UseOf(d));
      ids += (ids.empty() ? "" : " ") + std::to_string(d / 2);
    }
    if (notes != nullptr) {
      notes->push_back("a wall: patch " + std::to_string(cycles->size()) +
                       " (curves " + ids +
                       ") makes a third patch on each of its curves");
    }
    cycles->push_back({{std::move(loop)}});
  }
  return true;
}

}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
// Walls: the patches a rotation system cannot give, where three patches or
// more meet on a curve. In the spirit of Zhuang et al. (2013), who group
// the curves at each junction into the corners of cycles: the corners the
// rotation leaves out are where a further patch may turn.
#include "network/walls.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "network/outline.h"

namespace dot {
namespace {

constexpr int kMaxWallCurves = 8;
constexpr int64_t kStepsPerStart = 20000;
constexpr double kFlat = 0.05;  // off its plane, per radius

// Dart 2c + e: curve c leaving from its first vertex (e = 0) or its last.
int32_t JunctionOf(const NetworkGraph& g, int32_t dart) {
  const auto& vs = g.curves[dart / 2].vertices;
  return (dart & 1) ? vs.back() : vs.front();
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
  int64_t steps = 0;                        // from the current start
  bool stopped = false;                     // by the ticker
  bool cut = false;                         // a start ran out of steps

  bool Unused(int32_t a, int32_t b) const {
    return a / 2 != b / 2 && !used.count(Corner(a, b));
  }

  // `path` leaves junction `start` by path[0]; extend it from its end.
  void Extend(int32_t start) {
    if (stopped || steps > kStepsPerStart) return;
    if (++steps > kStepsPerStart) {
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

// Whether the cycle lies flat and holds no other point of the network: no
// vertex or edge midpoint of another curve (dangling ones too) inside it,
// no edge through it, or across its rim in its plane. -1: the ticker says
// stop.
int IsWall(const NetworkGraph& g, const std::vector<int32_t>& darts,
           RunTicker* ticker, double* flatness) {
  std::vector<CurveUse> loop;
  std::set<int32_t> own;
  for (int32_t d : darts) {
    loop.push_back(UseOf(d));
    own.insert(d / 2);
  }
  const Outline o = MakeOutline(g, LoopVertices(g, loop), kFlat);
  if (!(o.area > 0) || o.off_plane > kFlat * o.radius) return 0;
  *flatness = o.off_plane / o.radius;
  const std::set<int32_t> rim(o.vertices.begin(), o.vertices.end());
  auto height = [&](const Vec3& p) { return Dot(p - o.centre, o.normal); };
  for (size_t c = 0; c < g.curves.size(); ++c) {
    if (!ticker->Tick()) return -1;
    if (own.count(static_cast<int32_t>(c))) continue;
    const auto& vs = g.curves[c].vertices;
    for (size_t k = 0; k < vs.size(); ++k) {
      const Vec3& p = g.vertices[vs[k]];
      // A curve's end on the wall's rim is no point inside it.
      if (!rim.count(vs[k]) && Inside(o, p)) return 0;
      if (k + 1 == vs.size()) continue;
      const Vec3& q = g.vertices[vs[k + 1]];
      const double hp = height(p), hq = height(q);
      if (Inside(o, 0.5 * (p + q))) return 0;
      if (std::abs(hp) <= o.reach && std::abs(hq) <= o.reach &&
          CrossesOutline(o, p, q)) {
        return 0;  // in its plane, across its rim
      }
      if ((hp > o.reach && hq < -o.reach) || (hp < -o.reach && hq > o.reach)) {
        if (Inside(o, p + (hp / (hp - hq)) * (q - p))) return 0;  // through
      }
    }
  }
  return 1;
}

}  // namespace

std::pair<int32_t, int32_t> Corner(int32_t a, int32_t b) {
  return {std::min(a, b), std::max(a, b)};
}

bool FindWalls(const NetworkGraph& g,
               const std::set<std::pair<int32_t, int32_t>>& used,
               std::vector<NetworkCycle>* cycles,
               std::vector<std::string>* notes, RunTicker* ticker) {
  std::vector<char> live(g.curves.size(), 0);
  for (const NetworkCycle& c : *cycles) {
    for (const auto& loop : c.loops) {
      for (const CurveUse& u : loop) live[u.curve] = 1;
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
    if (darts.size() < 4) continue;  // three curves: every corner is used
    search.steps = 0;
    for (int32_t d : darts) {
      search.path = {d};
      search.visited = {at};
      search.Extend(at);
    }
  }
  if (search.stopped) return false;
  if (search.cut && notes != nullptr) {
    notes->push_back(
        "the search for walls (a third patch on a curve) stopped after " +
        std::to_string(kStepsPerStart) +
        " steps from some junctions: walls through them may be missing");
  }

  // Smallest and flattest first.
  struct Candidate {
    size_t index;
    double flatness;
  };
  std::vector<Candidate> walls;
  for (size_t k = 0; k < search.found.size(); ++k) {
    double flatness = 0;
    const int is = IsWall(g, search.found[k], ticker, &flatness);
    if (is < 0) return false;
    if (is > 0) walls.push_back({k, flatness});
  }
  std::sort(walls.begin(), walls.end(), [&](const auto& a, const auto& b) {
    const size_t la = search.found[a.index].size();
    const size_t lb = search.found[b.index].size();
    return la != lb ? la < lb : a.flatness < b.flatness;
  });
  // Each corner in one wall; and two walls through one junction that share
  // no curve there cross (curves that cross share a vertex), as a + of
  // partitions whose centre line no curve draws: the later is left out.
  std::set<std::pair<int32_t, int32_t>> taken;
  std::map<int32_t, std::vector<std::pair<int32_t, int32_t>>> walls_at;
  for (const Candidate& w : walls) {
    const auto& darts = search.found[w.index];
    std::vector<std::pair<int32_t, int32_t>> corners;
    std::vector<std::pair<int32_t, std::pair<int32_t, int32_t>>> at;
    for (size_t k = 0; k < darts.size(); ++k) {
      const int32_t next = darts[(k + 1) % darts.size()];
      corners.push_back(Corner(darts[k] ^ 1, next));
      at.push_back({JunctionOf(g, next), {darts[k] / 2, next / 2}});
    }
    bool clash = std::any_of(corners.begin(), corners.end(),
                             [&](const auto& c) { return taken.count(c); });
    for (const auto& [junction, mine] : at) {
      for (const auto& other : walls_at[junction]) {
        const bool share =
            mine.first == other.first || mine.first == other.second ||
            mine.second == other.first || mine.second == other.second;
        clash = clash || !share;
      }
    }
    if (clash) continue;
    taken.insert(corners.begin(), corners.end());
    for (const auto& [junction, mine] : at) {
      walls_at[junction].push_back(mine);
    }
    std::vector<CurveUse> loop;
    std::string ids;
    for (int32_t d : darts) {
      loop.push_back(UseOf(d));
      ids += (ids.empty() ? "" : " ") + std::to_string(d / 2);
    }
    if (notes != nullptr) {
      notes->push_back("a wall (curves " + ids +
                       ") makes a third patch on each of its curves");
    }
    cycles->push_back({{std::move(loop)}, /*wall=*/true});
  }
  return true;
}

}  // namespace dot

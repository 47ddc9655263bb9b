// SPDX-License-Identifier: AGPL-3.0-or-later
// The cycles that bound patches. FindNetworkCycles embeds the network on a
// surface by a rotation system: at each junction the curves leaving it are
// ordered counter-clockwise around a normal (given, or the normal of the
// plane that best fits their directions), the normals' signs are made to
// agree along a maximum spanning tree of the junctions (a normal carried
// along a curve, kept perpendicular to it, must meet the next one's), then
// with most of each junction's curves, then with the faces (rotation.h:
// more and simpler faces; sign_cost.h: cheaper faces as DOT patches), and
// the faces of the embedding are traced: leaving each junction by the next
// curve clockwise from the one arrived by keeps the face on the left. Every
// curve then bounds two faces, run in opposite directions, so the patches
// are consistently oriented and a closed network gives a closed surface,
// whatever its genus (Euler's formula holds by construction).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <set>
#include <unordered_map>

#include "dot/network.h"
#include "network/face_cost.h"
#include "network/islands.h"
#include "network/rotation.h"
#include "network/seam.h"
#include "network/sign_cost.h"
#include "network/walls.h"
#include "util/run_control.h"

namespace dot {
namespace {

// A curve leaving a junction: the curve and which end it leaves from
// (0: its first vertex, run forward; 1: its last, run backward).
struct Dart {
  int32_t curve;
  int end;
  bool operator<(const Dart& o) const {
    return curve != o.curve ? curve < o.curve : end < o.end;
  }
  bool operator==(const Dart& o) const {
    return curve == o.curve && end == o.end;
  }
};

// The curve's vertices as the dart leaves along it.
std::vector<int32_t> DartPath(const NetworkGraph& g, const Dart& d) {
  std::vector<int32_t> vs = g.curves[d.curve].vertices;
  if (d.end == 1) std::reverse(vs.begin(), vs.end());
  return vs;
}

// Where the curve heads: towards its point kDirectionFraction of its length
// along (robust to a jagged first edge, as rims cut from a mesh have, and
// near enough to stay in the surface's tangent plane).
constexpr double kDirectionFraction = 0.1;
Vec3 DartDirection(const NetworkGraph& g, const Dart& d) {
  const std::vector<int32_t> vs = DartPath(g, d);
  double length = 0;
  for (size_t k = 0; k + 1 < vs.size(); ++k) {
    length += Distance(g.vertices[vs[k]], g.vertices[vs[k + 1]]);
  }
  const double target = length * kDirectionFraction;
  double run = 0;
  Vec3 at = g.vertices[vs[1]];
  for (size_t k = 0; k + 1 < vs.size(); ++k) {
    const Vec3& p = g.vertices[vs[k]];
    const Vec3& q = g.vertices[vs[k + 1]];
    const double step = Distance(p, q);
    if (run + step >= target) {
      const double t = step > 0 ? (target - run) / step : 0;
      at = p + t * (q - p);
      break;
    }
    run += step;
  }
  const Vec3 dir = at - g.vertices[vs[0]];
  return Norm(dir) > 0 ? Normalized(dir)
                       : Normalized(g.vertices[vs[1]] - g.vertices[vs[0]]);
}

// The junction's normal: that of the plane that best fits the directions
// (the eigenvector of the smallest eigenvalue of sum t t^T) when they lie
// near one; otherwise (a corner, as a cube's, where every direction fits
// equally badly) the mean direction, which points into the corner.
Vec3 FitNormal(const std::vector<Vec3>& dirs) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  Vec3 mean;
  for (const Vec3& t : dirs) {
    const Eigen::Vector3d v(t.x, t.y, t.z);
    m += v * v.transpose();
    mean = mean + t;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m);
  const Eigen::Vector3d lambda = eig.eigenvalues();
  if (lambda(0) >= 0.5 * lambda(1) &&
      Norm(mean) > 0.1 * static_cast<double>(dirs.size())) {
    return Normalized(mean);
  }
  const Eigen::Vector3d n = eig.eigenvectors().col(0);
  return Normalized(Vec3{n.x(), n.y(), n.z()});
}

// `n` carried from the curve's first vertex to its last, turned at each
// vertex by the least rotation that takes one edge's direction to the
// next (a discrete rotation-minimizing frame). Projecting n onto each edge's
// normal plane instead flips it at turns past 90 degrees, as a curve over a
// thin fold (an ear's rim) makes; a full reversal keeps n (a zigzag in the
// surface, as rims cut along mesh edges make, is far more common).
Vec3 Transport(const NetworkGraph& g, const std::vector<int32_t>& path,
               Vec3 n) {
  Vec3 t;
  for (size_t k = 0; k + 1 < path.size(); ++k) {
    const Vec3 edge = g.vertices[path[k + 1]] - g.vertices[path[k]];
    if (Norm(edge) == 0) continue;
    const Vec3 u = Normalized(edge);
    if (k > 0) {
      const Vec3 axis = Cross(t, u);
      const double sin_a = Norm(axis), cos_a = Dot(t, u);
      if (sin_a > 1e-12) {
        const Vec3 axis_unit = (1.0 / sin_a) * axis;
        n = cos_a * n + sin_a * Cross(axis_unit, n) +
            ((1 - cos_a) * Dot(axis_unit, n)) * axis_unit;
      }
    }
    t = u;
  }
  return Normalized(n);
}

struct Junction {
  std::vector<Dart> darts;  // counter-clockwise around `normal`
  Vec3 normal;
  bool has_normal = false;
  int32_t parent = -1;  // in the spanning tree that oriented the normals
};

void SortAround(const NetworkGraph& g, Junction* j) {
  if (!j->has_normal || j->darts.size() < 3) return;
  const Vec3 n = j->normal;
  Vec3 u = Cross(n, Vec3{1, 0, 0});
  if (Norm(u) < 0.5) u = Cross(n, Vec3{0, 1, 0});
  u = Normalized(u);
  const Vec3 w = Cross(n, u);
  std::vector<std::pair<double, Dart>> keyed;
  for (const Dart& d : j->darts) {
    const Vec3 t = DartDirection(g, d);
    keyed.push_back({std::atan2(Dot(t, w), Dot(t, u)), d});
  }
  std::sort(keyed.begin(), keyed.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t k = 0; k < keyed.size(); ++k) j->darts[k] = keyed[k].second;
}

// Signs of the fitted normals, made to agree along a maximum spanning tree
// of the junction graph weighted by how well carried normals agree.
void OrientNormals(const NetworkGraph& g, std::map<int32_t, Junction>* js,
                   const std::vector<char>& live,
                   std::vector<int>* curve_votes) {
  struct Link {
    double weight;
    int32_t from, to;
    bool flip;
    bool operator<(const Link& o) const { return weight < o.weight; }
  };
  std::map<int32_t, std::vector<std::pair<int32_t, int32_t>>> curves_at;
  for (size_t c = 0; c < g.curves.size(); ++c) {
    if (!live[c]) continue;
    const auto& vs = g.curves[c].vertices;
    if (vs.front() == vs.back()) continue;
    curves_at[vs.front()].push_back({static_cast<int32_t>(c), 0});
    curves_at[vs.back()].push_back({static_cast<int32_t>(c), 1});
  }
  std::set<int32_t> done;
  for (auto& [root, junction] : *js) {
    if (!junction.has_normal || done.count(root)) continue;
    done.insert(root);
    std::priority_queue<Link> queue;
    auto push_from = [&](int32_t v) {
      const Vec3 n = (*js)[v].normal;
      for (const auto& [c, end] : curves_at[v]) {
        std::vector<int32_t> path = g.curves[c].vertices;
        if (end == 1) std::reverse(path.begin(), path.end());
        const int32_t w = path.back();
        const Junction& jw = (*js)[w];
        if (!jw.has_normal || done.count(w)) continue;
        const double d = Dot(Transport(g, path, n), jw.normal);
        queue.push({std::abs(d), v, w, d < 0});
      }
    };
    push_from(root);
    while (!queue.empty()) {
      const Link link = queue.top();
      queue.pop();
      if (done.count(link.to)) continue;
      done.insert(link.to);
      Junction& j = (*js)[link.to];
      if (link.flip) {
        j.normal = -1.0 * j.normal;
        std::reverse(j.darts.begin(), j.darts.end());
      }
      j.parent = link.from;
      push_from(link.to);
    }
  }
  // Then each junction takes the sign most of its curves carry to it: a
  // tree link can be the one curve whose carried normal is wrong (over a
  // fold, or long and bent on a coarse network), and the others outvote
  // it. One vote per curve, +1 when the normal carried from one end meets
  // the other's, -1 when it opposes it (votes weighted by agreement found
  // fewer of the rims of cut meshes); a flip negates the votes of its
  // curves, so each curve is carried once. Passes until no junction
  // changes (a few; capped).
  std::map<int32_t, std::vector<std::pair<int32_t, int>>> votes_at;
  curve_votes->assign(g.curves.size(), 0);
  for (const auto& [v, at] : curves_at) {
    if (!(*js)[v].has_normal) continue;
    for (const auto& [c, end] : at) {
      if (end != 0) continue;  // each curve once, from its first vertex
      const auto& path = g.curves[c].vertices;
      const Junction& to = (*js)[path.back()];
      if (!to.has_normal) continue;
      const double d = Dot(Transport(g, path, (*js)[v].normal), to.normal);
      const int vote = (d > 0) - (d < 0);
      votes_at[v].push_back({path.back(), vote});
      votes_at[path.back()].push_back({v, vote});
      (*curve_votes)[c] = vote;
    }
  }
  std::map<int32_t, int> sign;  // -1: flipped since the votes were taken
  for (const auto& [v, votes] : votes_at) sign[v] = 1;
  for (int pass = 0; pass < 20; ++pass) {
    bool flipped = false;
    for (const auto& [v, votes] : votes_at) {
      int sum = 0;
      for (const auto& [w, vote] : votes) sum += vote * sign[w];
      int& s = sign[v];
      if (s * sum < 0) {
        s = -s;
        flipped = true;
      }
    }
    if (!flipped) break;
  }
  for (const auto& [v, s] : sign) {
    if (s > 0) continue;
    Junction& j = (*js)[v];
    j.normal = -1.0 * j.normal;
    std::reverse(j.darts.begin(), j.darts.end());
  }
  for (size_t c = 0; c < g.curves.size(); ++c) {
    const auto& vs = g.curves[c].vertices;
    if ((*curve_votes)[c] != 0) {
      (*curve_votes)[c] *= sign[vs.front()] * sign[vs.back()];
    }
  }
}

constexpr int64_t kPricedPoints = 250000;

}  // namespace

Status FindNetworkCycles(const NetworkGraph& graph,
                         std::vector<NetworkCycle>* cycles,
                         std::vector<std::string>* notes,
                         const Control& control, const CycleOptions& options) {
  cycles->clear();
  RunTicker ticker(control, "the network's cycle search");
  std::vector<char> live(graph.curves.size(), 1);
  for (int32_t c : graph.dangling) live[c] = 0;
  std::map<int32_t, Junction> junctions;
  for (size_t c = 0; c < graph.curves.size(); ++c) {
    if (!live[c]) continue;
    const auto& vs = graph.curves[c].vertices;
    junctions[vs.front()].darts.push_back({static_cast<int32_t>(c), 0});
    junctions[vs.back()].darts.push_back({static_cast<int32_t>(c), 1});
  }
  for (auto& [v, j] : junctions) {
    if (!ticker.Tick()) return ticker.status();
    if (!graph.normals.empty()) {
      j.normal = graph.normals[v];
      j.has_normal = true;
    } else if (j.darts.size() >= 3) {
      std::vector<Vec3> dirs;
      for (const Dart& d : j.darts) dirs.push_back(DartDirection(graph, d));
      j.normal = FitNormal(dirs);
      j.has_normal = true;
      // Refined as the normal of the fan the directions make around it,
      // in the order they take around the first guess (a saddle's or a
      // corner's directions fit no plane, but their fan has a normal).
      for (int round = 0; round < 2; ++round) {
        SortAround(graph, &j);
        Vec3 fan;
        for (size_t k = 0; k < j.darts.size(); ++k) {
          fan = fan +
                Cross(DartDirection(graph, j.darts[k]),
                      DartDirection(graph, j.darts[(k + 1) % j.darts.size()]));
        }
        if (Norm(fan) < 1e-9) break;
        j.normal = Normalized(fan);
      }
    }
  }
  std::vector<int> votes;
  if (graph.normals.empty()) OrientNormals(graph, &junctions, live, &votes);
  for (auto& [v, j] : junctions) SortAround(graph, &j);

  // Dart 2c + end; before[d]: the dart before d counter-clockwise at its
  // junction. Leaving by d, a face arrives by d ^ 1 and leaves by the dart
  // before that one (the next clockwise), keeping the face on its left.
  Rotation rot;
  rot.before.assign(2 * graph.curves.size(), -1);
  std::map<int32_t, int32_t> ring_of;  // junction vertex -> ring
  for (auto& [v, j] : junctions) {
    ring_of[v] = static_cast<int32_t>(rot.rings.size());
    std::vector<int32_t> ring;
    for (const Dart& d : j.darts) ring.push_back(2 * d.curve + d.end);
    rot.rings.push_back(ring);
    for (size_t k = 0; k < ring.size(); ++k) {
      rot.before[ring[k]] = ring[(k + ring.size() - 1) % ring.size()];
    }
  }
  if (graph.normals.empty()) {
    // The spanning forest in preorder: a junction's subtree is a range of
    // it. Subtree flips retrace every face each: only where that stays
    // affordable (junctions x darts < 2e8).
    std::vector<int32_t> order;
    std::vector<std::pair<size_t, size_t>> subtrees;
    if (static_cast<double>(rot.rings.size()) *
            static_cast<double>(rot.before.size()) <
        2e8) {
      std::map<int32_t, std::vector<int32_t>> children;
      for (auto& [v, j] : junctions) {
        if (j.parent >= 0) children[j.parent].push_back(v);
      }
      for (auto& [root, jr] : junctions) {
        if (jr.parent >= 0) continue;
        // Iterative: (junction, where its range starts), closed on the way
        // back up.
        std::vector<std::pair<int32_t, size_t>> stack = {{root, SIZE_MAX}};
        while (!stack.empty()) {
          auto [x, start] = stack.back();
          stack.pop_back();
          if (start != SIZE_MAX) {  // all of x's subtree is in order now
            if (junctions[x].parent >= 0) {
              subtrees.emplace_back(start, order.size());
            }
            continue;
          }
          stack.push_back({x, order.size()});
          order.push_back(ring_of[x]);
          for (int32_t c : children[x]) stack.push_back({c, SIZE_MAX});
        }
      }
    }
    rot.sign.assign(rot.rings.size(), 1);
    Status s = ImproveSigns(&rot, order, subtrees, MoreSimple, &ticker);
    if (!s.ok()) return s;
    std::vector<CurveRings> curves;
    for (size_t c = 0; c < graph.curves.size(); ++c) {
      if (!live[c]) continue;
      const auto& vs = graph.curves[c].vertices;
      curves.push_back({ring_of[vs.front()], ring_of[vs.back()], votes[c]});
    }
    // Points to price: moves are tried only where curve votes disagree, so
    // the cut meshes measured price at most 7,000 (12 a network vertex);
    // the cap bounds a network built to disagree everywhere (about 1,250
    // faces of kMaxPoints, a few seconds).
    FaceCosts costs(graph, control, kPricedPoints);
    s = ImproveByCost(&rot, graph, curves, order, subtrees, &costs, &ticker);
    if (!s.ok()) return s;
    if (costs.spent() && notes != nullptr) {
      notes->push_back(
          "the search by the faces' cost stopped early: its points to "
          "price were spent (" +
          std::to_string(costs.priced()) + " faces priced)");
    }
    const FaceCount count = AllFaces(rot);
    if (count.simple + count.seams < count.faces) {
      s = ImproveSigns(&rot, order, subtrees, MoreSurfaceable, &ticker);
      if (!s.ok()) return s;
    }
  }

  std::vector<char> used(rot.before.size(), 0);
  std::set<std::vector<int32_t>> seen_loops;
  for (const auto& ring : rot.rings) {
    for (int32_t start : ring) {
      if (used[start]) continue;
      std::vector<CurveUse> face;
      for (int32_t d = start; !used[d]; d = rot.Next(d)) {
        if (!ticker.Tick()) return ticker.status();
        used[d] = 1;
        face.push_back({d / 2, (d & 1) == 1});
      }
      if (RunsACurveTwice(face)) {
        // A seam face is surfaced in two pieces (SurfaceNetwork).
        SeamSplit split;
        std::string why;
        if (SplitSeam(graph, face, &split, &why)) {
          std::vector<int32_t> key;
          for (const CurveUse& u : face) key.push_back(u.curve);
          std::sort(key.begin(), key.end());
          if (seen_loops.insert(key).second) cycles->push_back({{face}});
          continue;
        }
        if (notes != nullptr) {
          std::string ids;
          for (const CurveUse& u : face) {
            ids += (ids.empty() ? "" : " ") + std::to_string(u.curve);
          }
          notes->push_back("a face runs along a curve both ways and " + why +
                           "; left out: curves " + ids);
        }
        continue;
      }
      for (auto& loop : SplitAtRepeats(graph, face)) {
        // A cycle alone in its part of the network is the boundary of two
        // faces, one each way: surface it once.
        std::vector<int32_t> key;
        for (const CurveUse& u : loop) key.push_back(u.curve);
        std::sort(key.begin(), key.end());
        if (!seen_loops.insert(key).second) continue;
        cycles->push_back({{std::move(loop)}});
      }
    }
  }
  if (options.walls) {
    // Walls turn where the rotation does not: between darts that are not
    // neighbours at their junction.
    std::set<std::pair<int32_t, int32_t>> corners;
    for (size_t d = 0; d < rot.before.size(); ++d) {
      if (rot.before[d] >= 0) {
        corners.insert(Corner(static_cast<int32_t>(d), rot.before[d]));
      }
    }
    if (!FindWalls(graph, corners, cycles, notes, &ticker)) {
      return ticker.status();
    }
  }
  if (!PairIslands(graph, options.islands, cycles, notes, &ticker)) {
    return ticker.status();
  }
  return OkStatus();
}

Status CyclesFromVertices(
    const NetworkGraph& graph,
    const std::vector<std::vector<std::vector<int32_t>>>& patches,
    std::vector<NetworkCycle>* cycles, const Control& control) {
  cycles->clear();
  RunTicker ticker(control, "the given cycles");
  const size_t n_vertices = graph.vertices.size();
  // Neighbours along the curves, each directed edge's curve use, and how
  // many curve ends each vertex is.
  std::vector<std::vector<int32_t>> next(n_vertices);
  std::unordered_map<uint64_t, CurveUse> edge_use;
  auto key = [](int32_t a, int32_t b) {
    return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) |
           static_cast<uint32_t>(b);
  };
  std::vector<int32_t> curve_ends(n_vertices, 0);
  for (size_t c = 0; c < graph.curves.size(); ++c) {
    const auto& vs = graph.curves[c].vertices;
    for (size_t k = 0; k + 1 < vs.size(); ++k) {
      edge_use[key(vs[k], vs[k + 1])] = {static_cast<int32_t>(c), false};
      edge_use[key(vs[k + 1], vs[k])] = {static_cast<int32_t>(c), true};
      next[vs[k]].push_back(vs[k + 1]);
      next[vs[k + 1]].push_back(vs[k]);
    }
    ++curve_ends[vs.front()];
    ++curve_ends[vs.back()];
  }
  const auto inputs = static_cast<int64_t>(graph.vertex_of_input.size());
  std::vector<char> seen(n_vertices, 0);
  std::map<std::vector<std::pair<int32_t, bool>>, size_t> earlier;
  for (size_t p = 0; p < patches.size(); ++p) {
    NetworkCycle cycle;
    std::set<int32_t> in_patch;
    for (size_t l = 0; l < patches[p].size(); ++l) {
      const auto& listed = patches[p][l];
      const std::string where =
          "cycle " + std::to_string(p) + ", loop " + std::to_string(l) + ": ";
      if (listed.empty()) return InvalidArgument(where + "no vertices");
      if (listed.size() > n_vertices) {
        return InvalidArgument(
            where + "lists " + std::to_string(listed.size()) +
            " vertices; the network has " + std::to_string(n_vertices));
      }
      std::vector<int32_t> ids;
      for (int32_t v : listed) {
        if (v < 0 || v >= inputs || graph.vertex_of_input[v] < 0) {
          return InvalidArgument(where + "vertex " + std::to_string(v) +
                                 " is not on a curve of the network");
        }
        ids.push_back(graph.vertex_of_input[v]);
      }
      const std::set<int32_t> listed_set(ids.begin(), ids.end());
      // Fill in the vertices between listed ones along the one curve that
      // joins them, checking for repeats as the walk grows (a loop visits
      // each vertex once, so the walk never exceeds the network).
      std::vector<int32_t> walk;
      auto release = [&] {
        for (int32_t v : walk) seen[v] = 0;
      };
      for (size_t k = 0; k < ids.size(); ++k) {
        if (!ticker.Tick()) {
          release();
          return ticker.status();
        }
        const int32_t from = ids[k], to = ids[(k + 1) % ids.size()];
        std::vector<std::vector<int32_t>> ways;
        // A way through another listed vertex is not this one.
        auto passes_listed = [&](const std::vector<int32_t>& way) {
          for (size_t j = 1; j + 1 < way.size(); ++j) {
            if (listed_set.count(way[j])) return true;
          }
          return false;
        };
        for (int32_t first : next[from]) {
          std::vector<int32_t> way = {from};
          int32_t prev = from, at = first;
          while (true) {
            way.push_back(at);
            // A curve's inner vertices have two neighbours; the walk stops
            // at the target, a junction, or back where it began.
            if (at == to || at == from || next[at].size() != 2) break;
            const int32_t step =
                next[at][0] == prev ? next[at][1] : next[at][0];
            prev = at;
            at = step;
          }
          if (way.back() == to && !passes_listed(way)) {
            ways.push_back(std::move(way));
          }
        }
        const std::string pair = "vertices " + std::to_string(listed[k]) +
                                 " and " +
                                 std::to_string(listed[(k + 1) % ids.size()]);
        if (ways.empty()) {
          release();
          return InvalidArgument(where + "no curve joins " + pair);
        }
        // An edge between them is the way (a loop with no junction can
        // also be run the long way round).
        for (const auto& way : ways) {
          if (way.size() == 2) {
            ways = {way};
            break;
          }
        }
        if (ways.size() > 1) {
          release();
          return InvalidArgument(where + std::to_string(ways.size()) +
                                 " ways along the curves join " + pair +
                                 ": list a vertex between them");
        }
        for (size_t j = 0; j + 1 < ways[0].size(); ++j) {
          const int32_t v = ways[0][j];
          if (seen[v]) {
            release();
            return InvalidArgument(where +
                                   "passes a vertex twice; a loop of a "
                                   "patch is a simple cycle");
          }
          seen[v] = 1;
          walk.push_back(v);
        }
      }
      release();
      if (walk.size() < 3) {
        return InvalidArgument(where + "runs along " +
                               std::to_string(walk.size()) +
                               " vertices; a loop needs at least 3");
      }
      for (int32_t v : walk) {
        if (!in_patch.insert(v).second) {
          return InvalidArgument(where +
                                 "shares a vertex with another loop "
                                 "of the cycle");
        }
      }
      // Start at a curve end (every loop has one: a closed curve's first
      // vertex is its end) and read off whole curves.
      size_t start = 0;
      while (start < walk.size() && curve_ends[walk[start]] == 0) ++start;
      if (start == walk.size()) start = 0;
      std::vector<CurveUse> loop;
      const size_t n = walk.size();
      for (size_t k = 0; k < n;) {
        const int32_t x = walk[(start + k) % n];
        const CurveUse use = edge_use.at(key(x, walk[(start + k + 1) % n]));
        const auto& vs = graph.curves[use.curve].vertices;
        const int32_t expected = use.reversed ? vs.back() : vs.front();
        if (x != expected) {
          return InvalidArgument(where + "starts or ends inside curve " +
                                 std::to_string(use.curve) +
                                 ": a loop runs along whole curves");
        }
        loop.push_back(use);
        k += vs.size() - 1;
      }
      cycle.loops.push_back(std::move(loop));
    }
    if (cycle.loops.empty()) {
      return InvalidArgument("cycle " + std::to_string(p) + " has no loops");
    }
    std::vector<std::pair<int32_t, bool>> uses;
    for (const auto& loop : cycle.loops) {
      for (const CurveUse& u : loop) uses.push_back({u.curve, u.reversed});
    }
    std::sort(uses.begin(), uses.end());
    const auto [it, added] = earlier.emplace(uses, p);
    if (!added) {
      return InvalidArgument("cycle " + std::to_string(p) + " repeats cycle " +
                             std::to_string(it->second));
    }
    cycles->push_back(std::move(cycle));
  }
  // Patches on a curve they both bound run it once each way, so that the
  // surface is oriented (three or more: a non-manifold network, any way).
  std::vector<std::vector<std::pair<size_t, bool>>> runs(graph.curves.size());
  for (size_t p = 0; p < cycles->size(); ++p) {
    for (const auto& loop : (*cycles)[p].loops) {
      for (const CurveUse& u : loop) runs[u.curve].push_back({p, u.reversed});
    }
  }
  for (size_t c = 0; c < runs.size(); ++c) {
    const auto& r = runs[c];
    if (r.size() == 2 && r[0].second == r[1].second) {
      const auto& vs = graph.curves[c].vertices;
      const int32_t a =
          graph.input_of_vertex[r[0].second ? vs.back() : vs.front()];
      return InvalidArgument(
          "cycles " + std::to_string(r[0].first) + " and " +
          std::to_string(r[1].first) + " both run the curve from vertex " +
          std::to_string(a) +
          " the same way; the patches of one surface run a curve they "
          "share once each way (list one of them the other way round)");
    }
  }
  return OkStatus();
}

}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
// BuildNetworkGraph: from polylines to curves between junctions. Points
// are welded by exact coordinates (sketching tools and Blender's curve
// export repeat a junction's point in every curve through it); what is not
// a network is refused with the polylines and vertices named (numbered
// from 0, as the report's curves and patches and every API's arrays).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>
#include <unordered_map>

#include "dot/network.h"
#include "util/run_control.h"
#include "util/union_find.h"

namespace dot {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

std::string Vertex(int32_t input_id) {
  return "vertex " + std::to_string(input_id);
}
std::string Polyline(size_t p) { return "polyline " + std::to_string(p); }

struct Edge {
  int32_t a, b;      // graph vertices, in the polyline's direction
  int32_t polyline;  // which polyline it came from
  int32_t input_a, input_b;
};

std::string Number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

// Distance checks the weld may make (about a second): a distance that puts
// this many pairs of points side by side is refused, not computed.
constexpr int64_t kMaxWeldChecks = 200'000'000;

// Per used point, the first point of its group: points at equal
// coordinates, and with `distance` > 0 a free end (a stroke's end, as a
// sketch leaves it short of or past where it meets another: a place with
// one edge) and the nearest point within `distance` of it not on its own
// stroke (the polylines it runs on through places of two edges; or the
// stroke's other end: a stroke drawn closed) nor beside the junction the
// stroke starts from, transitively. Points inside
// a stroke never weld to each other, so a stroke sampled finer than the
// distance keeps its shape, also given one polyline per edge. Found
// through a grid of cells `distance` wide.
Status WeldGroups(const CurveNetwork& net, const std::vector<char>& used,
                  double distance, const Control& control,
                  std::vector<int32_t>* first) {
  const std::vector<Vec3>& points = net.vertices;
  const size_t n = points.size();
  UnionFind groups(n);
  RunTicker ticker(control, "the network's weld");
  // Points at equal coordinates (-0 == 0 as doubles compare), found by
  // sorting: a map of a million points took half a second, unpolled.
  auto coordinates = [&](int32_t i) {
    return std::make_tuple(points[i].x, points[i].y, points[i].z);
  };
  std::vector<int32_t> order;
  for (size_t i = 0; i < n; ++i) {
    if (used[i]) order.push_back(static_cast<int32_t>(i));
  }
  if (!ticker.Poll()) return ticker.status();
  std::sort(order.begin(), order.end(), [&](int32_t a, int32_t b) {
    return std::make_pair(coordinates(a), a) <
           std::make_pair(coordinates(b), b);
  });
  for (size_t k = 1; k < order.size(); ++k) {
    if (!ticker.Tick()) return ticker.status();
    if (coordinates(order[k]) == coordinates(order[k - 1])) {
      groups.Join(order[k], order[k - 1]);
    }
  }
  if (distance > 0) {
    using Cell = std::array<int64_t, 3>;
    auto cell_of = [&](const Vec3& p) {
      return Cell{static_cast<int64_t>(std::floor(p.x / distance)),
                  static_cast<int64_t>(std::floor(p.y / distance)),
                  static_cast<int64_t>(std::floor(p.z / distance))};
    };
    // The used points by cell, sorted (a lookup is a binary search).
    std::vector<std::pair<Cell, int32_t>> grid;
    grid.reserve(order.size());
    for (size_t k = 0; k < n; ++k) {  // in input order: names the first
      if (!used[k]) continue;
      if (!ticker.Tick()) return ticker.status();
      const auto i = static_cast<int32_t>(k);
      const Vec3& p = points[i];
      // Cells are indexed by 64-bit integers: at most 1e15 cells across.
      if (std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) / distance >
          1e15) {
        return InvalidArgument(
            "the weld distance " + Number(distance) + " is too small for " +
            Vertex(i) +
            "'s coordinates (at most 1e15 times smaller than them)");
      }
      grid.emplace_back(cell_of(p), i);
    }
    if (!ticker.Poll()) return ticker.status();
    std::sort(grid.begin(), grid.end());
    if (!ticker.Poll()) return ticker.status();
    // The network's edges between places (points at equal coordinates), as
    // adjacency lists: an end whose place has other edges (a junction shared
    // by index or by coordinates, an end on another polyline) already meets
    // and is not free; a free end's stroke runs on through places of two
    // edges (a stroke drawn in pieces, or as OBJ's one 'l a b' per edge).
    // An edge of zero length (a point repeated) is no edge here.
    std::vector<int32_t> place(n, -1), next;
    std::vector<int64_t> start(n + 1, 0);
    for (const int32_t i : order) place[i] = groups.Find(i);
    for (const auto& line : net.polylines) {
      for (size_t k = 0; k + 1 < line.size(); ++k) {
        if (!ticker.Tick()) return ticker.status();
        const int32_t a = place[line[k]], b = place[line[k + 1]];
        if (a == b) continue;
        ++start[a + 1];
        ++start[b + 1];
      }
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    next.resize(static_cast<size_t>(start[n]));
    std::vector<int64_t> fill(start.begin(), start.end() - 1);
    for (const auto& line : net.polylines) {
      for (size_t k = 0; k + 1 < line.size(); ++k) {
        if (!ticker.Tick()) return ticker.status();
        const int32_t a = place[line[k]], b = place[line[k + 1]];
        if (a == b) continue;
        next[fill[a]++] = b;
        next[fill[b]++] = a;
      }
    }
    auto degree = [&](int32_t at) { return start[at + 1] - start[at]; };
    int64_t checks = 0;
    std::vector<int32_t> own;  // the places of a free end's stroke, sorted
    for (const auto& line : net.polylines) {
      for (const int32_t end : {line.front(), line.back()}) {
        if (degree(place[end]) != 1) continue;
        // Its stroke: from its place on through places of two edges.
        own = {place[end]};
        int32_t at = next[start[place[end]]], from = place[end];
        while (at != place[end] && own.size() <= n) {
          if (!ticker.Tick()) return ticker.status();
          own.push_back(at);
          if (degree(at) != 2) break;
          const int32_t to =
              next[start[at]] == from ? next[start[at] + 1] : next[start[at]];
          from = at;
          at = to;
        }
        const int32_t other = own.back();  // its far end
        // A stub from a junction within the distance (an overshoot) stays
        // dangling: welded, it would close a loop beside the junction.
        if (degree(other) >= 3 &&
            Distance(points[end], points[other]) <= distance) {
          continue;
        }
        const bool may_close = own.size() >= 4;
        // Where its next place is a junction, that junction's neighbours
        // too: welded to one, its edge would run along theirs.
        for (int64_t k = start[own[1]]; k < start[own[1] + 1]; ++k) {
          own.push_back(next[k]);
        }
        std::sort(own.begin(), own.end());
        const Cell c = cell_of(points[end]);
        // The nearest point it may weld to (the first of equals).
        double best = distance;
        int32_t nearest = -1;
        for (int64_t dx = -1; dx <= 1; ++dx) {
          for (int64_t dy = -1; dy <= 1; ++dy) {
            for (int64_t dz = -1; dz <= 1; ++dz) {
              const Cell cell = {c[0] + dx, c[1] + dy, c[2] + dz};
              for (auto it = std::lower_bound(
                       grid.begin(), grid.end(),
                       std::make_pair(cell,
                                      std::numeric_limits<int32_t>::min()));
                   it != grid.end() && it->first == cell; ++it) {
                const int32_t q = it->second;
                if (!ticker.Tick()) return ticker.status();
                if (++checks > kMaxWeldChecks) {
                  return InvalidArgument(
                      "the weld distance " + Number(distance) +
                      " puts more than " + std::to_string(kMaxWeldChecks) +
                      " pairs of points side by side: give one nearer the "
                      "gaps between stroke ends");
                }
                const bool closes = place[q] == other && may_close;
                if (!closes &&
                    std::binary_search(own.begin(), own.end(), place[q])) {
                  continue;
                }
                const double d = Distance(points[end], points[q]);
                if (d < best || (d == best && (nearest < 0 || q < nearest))) {
                  best = d;
                  nearest = q;
                }
              }
            }
          }
        }
        if (nearest >= 0) groups.Join(end, nearest);
      }
    }
  }
  first->assign(n, -1);
  std::vector<int32_t> least(n, -1);  // per root, its first point
  for (size_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    int32_t& l = least[groups.Find(static_cast<int32_t>(i))];
    if (l < 0) l = static_cast<int32_t>(i);
    (*first)[i] = l;
  }
  return OkStatus();
}

// Welds points with equal coordinates, and those within `distance` of
// each other (transitively); keeps input order.
Status Weld(const CurveNetwork& net, double distance, const Control& control,
            NetworkGraph* g) {
  const size_t n = net.vertices.size();
  std::vector<char> used(n, 0);
  for (size_t p = 0; p < net.polylines.size(); ++p) {
    const auto& line = net.polylines[p];
    if (line.size() < 2) {
      return InvalidArgument(Polyline(p) + " has " +
                             std::to_string(line.size()) +
                             " point; a curve needs at least two");
    }
    for (int32_t v : line) {
      if (v < 0 || static_cast<size_t>(v) >= n) {
        return InvalidArgument(Polyline(p) + " names vertex " +
                               std::to_string(v) + ", not one of the " +
                               std::to_string(n));
      }
      used[v] = 1;
    }
  }
  if (!net.normals.empty() && net.normals.size() != n) {
    return InvalidArgument(std::to_string(net.normals.size()) +
                           " normals for " + std::to_string(n) +
                           " vertices: give one per vertex or none");
  }
  for (size_t i = 0; i < n; ++i) {  // unused ones too: the output keeps them
    if (!IsFinite(net.vertices[i])) {
      return InvalidArgument(Vertex(static_cast<int32_t>(i)) +
                             " has a coordinate that is not a finite number");
    }
    // Lengths, normals and fairing square coordinates: beyond 1e100 they
    // could overflow (found by network_fuzz).
    const Vec3& v = net.vertices[i];
    if (std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}) > 1e100) {
      return InvalidArgument(Vertex(static_cast<int32_t>(i)) +
                             " has a coordinate beyond 1e100 in magnitude: "
                             "scale the network down");
    }
  }
  g->vertex_of_input.assign(n, -1);
  std::vector<int32_t> first;
  Status s = WeldGroups(net, used, distance, control, &first);
  if (!s.ok()) return s;
  for (size_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    if (first[i] != static_cast<int32_t>(i)) {
      ++g->merged_vertices;
      g->vertex_of_input[i] = g->vertex_of_input[first[i]];
      continue;
    }
    g->vertex_of_input[i] = static_cast<int32_t>(g->vertices.size());
    g->vertices.push_back(net.vertices[i]);
    g->input_of_vertex.push_back(static_cast<int32_t>(i));
    if (!net.normals.empty()) {
      const Vec3& nv = net.normals[i];
      if (!IsFinite(nv) || Norm(nv) == 0) {
        return InvalidArgument(Vertex(static_cast<int32_t>(i)) +
                               " has a normal that is zero or not finite");
      }
      g->normals.push_back(Normalized(nv));
    }
  }
  return OkStatus();
}

Status CollectEdges(const CurveNetwork& net, double weld_distance,
                    const Control& control, NetworkGraph* graph,
                    std::vector<Edge>* edges) {
  const NetworkGraph& g = *graph;
  RunTicker ticker(control, "the network's edges");
  std::unordered_map<uint64_t, int32_t> seen;  // undirected key -> edge
  for (size_t p = 0; p < net.polylines.size(); ++p) {
    const auto& line = net.polylines[p];
    for (size_t k = 0; k + 1 < line.size(); ++k) {
      if (!ticker.Tick()) return ticker.status();
      const Edge e{g.vertex_of_input[line[k]], g.vertex_of_input[line[k + 1]],
                   static_cast<int32_t>(p), line[k], line[k + 1]};
      // An edge whose ends were welded together is gone.
      if (e.a == e.b && e.input_a != e.input_b && weld_distance > 0) {
        ++graph->welded_edges;
        continue;
      }
      if (e.a == e.b) {
        return InvalidArgument(
            Polyline(p) + " joins " + Vertex(e.input_a) + " to " +
            (e.input_a == e.input_b
                 ? std::string("itself")
                 : Vertex(e.input_b) + ", a point at the same place"));
      }
      const uint64_t key = (static_cast<uint64_t>(std::min(e.a, e.b)) << 32) |
                           static_cast<uint32_t>(std::max(e.a, e.b));
      auto [it, added] = seen.emplace(key, static_cast<int32_t>(edges->size()));
      if (!added) {
        const Edge& o = (*edges)[it->second];
        return InvalidArgument(
            (o.polyline == e.polyline
                 ? Polyline(p) + " runs twice"
                 : "polylines " + std::to_string(o.polyline) + " and " +
                       std::to_string(p) + " both run") +
            " along the edge between " + Vertex(e.input_a) + " and " +
            Vertex(e.input_b) + " (duplicate curves)");
      }
      edges->push_back(e);
    }
  }
  return OkStatus();
}

// Two edges that meet other than at a shared end (exact predicates).
Status CheckCrossings(const NetworkGraph& g, const std::vector<Edge>& edges,
                      const Control& control) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int32_t>;
  std::vector<Box> boxes;
  boxes.reserve(edges.size());
  for (size_t i = 0; i < edges.size(); ++i) {
    const Vec3& p = g.vertices[edges[i].a];
    const Vec3& q = g.vertices[edges[i].b];
    double lo[3] = {std::min(p.x, q.x), std::min(p.y, q.y), std::min(p.z, q.z)};
    double hi[3] = {std::max(p.x, q.x), std::max(p.y, q.y), std::max(p.z, q.z)};
    boxes.emplace_back(lo, hi, static_cast<int32_t>(i));
  }
  auto point = [&](int32_t v) {
    const Vec3& p = g.vertices[v];
    return K::Point_3(p.x, p.y, p.z);
  };
  struct Found {
    int32_t i, j;
  };
  RunTicker ticker(control, "the network's crossing check");
  try {
    CGAL::box_self_intersection_d(
        boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
          if (!ticker.Tick()) throw ticker.status();
          const Edge& e = edges[x.info()];
          const Edge& f = edges[y.info()];
          const bool shares_a = e.a == f.a || e.a == f.b;
          const bool shares_b = e.b == f.a || e.b == f.b;
          if (shares_a && shares_b) return;  // cannot: no duplicates
          const K::Segment_3 s(point(e.a), point(e.b));
          const K::Segment_3 t(point(f.a), point(f.b));
          if (shares_a || shares_b) {
            // Sharing one end, they meet elsewhere only when they overlap.
            const int32_t c = shares_a ? e.a : e.b;
            const int32_t u = c == e.a ? e.b : e.a;
            const int32_t w = c == f.a ? f.b : f.a;
            if (!CGAL::collinear(point(c), point(u), point(w))) return;
            if ((point(u) - point(c)) * (point(w) - point(c)) <= 0) return;
          } else if (!CGAL::do_intersect(s, t)) {
            return;
          }
          throw Found{std::min(x.info(), y.info()),
                      std::max(x.info(), y.info())};
        });
  } catch (const Status& stop) {
    return stop;
  } catch (const Found& found) {
    const Edge& e = edges[found.i];
    const Edge& f = edges[found.j];
    return InvalidArgument(
        "curves cross: the edge " + Vertex(e.input_a) + "-" +
        Vertex(e.input_b) + " of " + Polyline(e.polyline) + " and the edge " +
        Vertex(f.input_a) + "-" + Vertex(f.input_b) + " of " +
        Polyline(f.polyline) +
        " meet away from a shared vertex (give the crossing point as a "
        "vertex of both, or move one curve)");
  }
  return OkStatus();
}

// Splits the edges into curves between junctions (degree other than 2).
void TraceCurves(const std::vector<Edge>& edges, NetworkGraph* g) {
  const size_t n = g->vertices.size();
  std::vector<std::vector<int32_t>> incident(n);
  for (size_t i = 0; i < edges.size(); ++i) {
    incident[edges[i].a].push_back(static_cast<int32_t>(i));
    incident[edges[i].b].push_back(static_cast<int32_t>(i));
  }
  std::vector<char> taken(edges.size(), 0);
  struct Traced {
    int32_t first_edge;
    NetworkCurve curve;
  };
  std::vector<Traced> traced;
  auto other = [&](int32_t e, int32_t v) {
    return edges[e].a == v ? edges[e].b : edges[e].a;
  };
  // Walks from v along edge e until a junction or back to `stop`.
  auto walk = [&](int32_t v, int32_t e, int32_t stop) {
    Traced t{e, {{v}}};
    while (true) {
      taken[e] = 1;
      t.first_edge = std::min(t.first_edge, e);
      v = other(e, v);
      t.curve.vertices.push_back(v);
      if (incident[v].size() != 2 || v == stop) break;
      e = incident[v][0] == e ? incident[v][1] : incident[v][0];
    }
    return t;
  };
  for (size_t v = 0; v < n; ++v) {
    if (incident[v].size() == 2) continue;
    for (int32_t e : incident[v]) {
      if (!taken[e]) traced.push_back(walk(static_cast<int32_t>(v), e, -1));
    }
  }
  for (size_t e = 0; e < edges.size(); ++e) {  // loops with no junction
    if (!taken[e]) {
      traced.push_back(walk(edges[e].a, static_cast<int32_t>(e), edges[e].a));
    }
  }
  std::sort(traced.begin(), traced.end(), [](const Traced& x, const Traced& y) {
    return x.first_edge < y.first_edge;
  });
  for (Traced& t : traced) {
    // Run the curve the way its first edge runs in the file.
    auto& vs = t.curve.vertices;
    const Edge& e = edges[t.first_edge];
    for (size_t k = 0; k + 1 < vs.size(); ++k) {
      if (vs[k] == e.b && vs[k + 1] == e.a) {
        std::reverse(vs.begin(), vs.end());
        break;
      }
      if (vs[k] == e.a && vs[k + 1] == e.b) break;
    }
    g->curves.push_back(std::move(t.curve));
  }
}

// Curves with a free end, pruned until none is left: a queue of vertices
// whose count of curve ends dropped to one, each curve pruned once (linear
// in the curves, whatever order the file gives them in).
void PruneDangling(NetworkGraph* g) {
  std::vector<int32_t> ends(g->vertices.size(), 0);
  std::vector<std::vector<int32_t>> curves_at(g->vertices.size());
  for (size_t i = 0; i < g->curves.size(); ++i) {
    const NetworkCurve& c = g->curves[i];
    ++ends[c.vertices.front()];
    ++ends[c.vertices.back()];
    if (c.closed()) continue;
    curves_at[c.vertices.front()].push_back(static_cast<int32_t>(i));
    curves_at[c.vertices.back()].push_back(static_cast<int32_t>(i));
  }
  std::vector<char> gone(g->curves.size(), 0);
  std::vector<int32_t> queue;
  for (size_t v = 0; v < ends.size(); ++v) {
    if (ends[v] == 1) queue.push_back(static_cast<int32_t>(v));
  }
  while (!queue.empty()) {
    const int32_t v = queue.back();
    queue.pop_back();
    if (ends[v] != 1) continue;
    for (int32_t i : curves_at[v]) {
      if (gone[i]) continue;
      gone[i] = 1;
      g->dangling.push_back(i);
      const NetworkCurve& c = g->curves[i];
      for (int32_t end : {c.vertices.front(), c.vertices.back()}) {
        if (--ends[end] == 1) queue.push_back(end);
      }
      break;  // v had one end left: this curve's
    }
  }
  std::sort(g->dangling.begin(), g->dangling.end());
}

}  // namespace

Status CheckWeldDistance(double weld_distance) {
  if (weld_distance >= 0 && std::isfinite(weld_distance)) return OkStatus();
  return InvalidArgument(
      "the weld distance must be a finite number >= 0, not " +
      Number(weld_distance));
}

Status BuildNetworkGraph(const CurveNetwork& network, NetworkGraph* out,
                         const Control& control, double weld_distance) {
  *out = {};
  if (network.polylines.empty()) {
    return InvalidArgument("the network has no polylines");
  }
  Status s = CheckWeldDistance(weld_distance);
  if (!s.ok()) return s;
  s = Weld(network, weld_distance, control, out);
  if (!s.ok()) return s;
  std::vector<Edge> edges;
  s = CollectEdges(network, weld_distance, control, out, &edges);
  if (!s.ok()) return s;
  s = CheckCrossings(*out, edges, control);
  if (!s.ok()) return s;
  TraceCurves(edges, out);
  PruneDangling(out);
  return OkStatus();
}

std::vector<int32_t> LoopVertices(const NetworkGraph& graph,
                                  const std::vector<CurveUse>& loop) {
  std::vector<int32_t> out;
  for (const CurveUse& u : loop) {
    const auto& vs = graph.curves[u.curve].vertices;
    if (u.reversed) {
      out.insert(out.end(), vs.rbegin(), vs.rend() - 1);
    } else {
      out.insert(out.end(), vs.begin(), vs.end() - 1);
    }
  }
  return out;
}

}  // namespace dot

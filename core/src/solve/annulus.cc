// SPDX-License-Identifier: AGPL-3.0-or-later
#include "solve/annulus.h"

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <numeric>
#include <string>

#include "solve/loop_ears.h"
#include "solve/solvers.h"
#include "util/run_control.h"

namespace dot {
namespace {

// Sides per loop so far, each saturating at 3: state c = 4 * on_a + on_b.
constexpr int kCounts = 16;
constexpr int kEnough = 15;  // at least 3 sides on each loop
int Counted(int c, bool on_a) {
  const int ca = c / 4, cb = c % 4;
  return on_a ? std::min(ca + 1, 3) * 4 + cb : ca * 4 + std::min(cb + 1, 3);
}

// A cross triangle used with one of its sides on a loop. A-arcs advance
// along A at a fixed vertex of B, B-arcs along B at a fixed vertex of A.
struct Arc {
  int32_t from, to;  // nodes
  bool on_a;
  int32_t advance;
  Triangle tri;  // oriented
  Vec3 normal;
  double cost;                   // the triangle's weight and its ear
  int32_t chord_from, chord_to;  // positions: the side on the loop
};

// A node: an edge between the loops, as local indices on A and B.
struct Node {
  int32_t x, y;
};

// Lower bounds on what covering an interval of a loop's edges costs: each
// edge gets the least cost per edge of any side covering it, so any set of
// sides covering an interval costs at least the sum over its edges (when no
// term is negative). With the two loops' sums this is an A* bound.
class CoverBound {
 public:
  void Init(int32_t n) {
    per_edge_.assign(n, kInf);
    prefix_.clear();
  }
  void Add(int32_t first_edge, int32_t advance, double cost) {
    const auto n = static_cast<int32_t>(per_edge_.size());
    const double per = cost / advance;
    for (int32_t i = 0; i < advance; ++i) {
      double& e = per_edge_[(first_edge + i) % n];
      e = std::min(e, per);
    }
  }
  void Finish() {
    prefix_.assign(2 * per_edge_.size() + 1, 0);
    for (size_t i = 0; i + 1 < prefix_.size(); ++i) {
      prefix_[i + 1] = prefix_[i] + per_edge_[i % per_edge_.size()];
    }
  }
  // Whether every edge has a side covering it.
  bool Covered() const {
    return std::all_of(per_edge_.begin(), per_edge_.end(),
                       [](double e) { return e < kInf; });
  }
  // Edges first_edge, ..., first_edge + count - 1 (cyclic).
  double Sum(int32_t first_edge, int32_t count) const {
    return prefix_[first_edge + count] - prefix_[first_edge];
  }

 private:
  std::vector<double> per_edge_;
  std::vector<double> prefix_;
};

// Per-start pass over the unrolled graph; see annulus.h. Nodes are taken in
// order of their unrolled coordinates from a heap, so a pass costs what it
// reaches, and with non-negative terms states are pruned by the best cycle
// so far plus the cover bounds of what remains.
class StripPass {
 public:
  StripPass(const std::vector<Node>& nodes, const std::vector<Arc>& arcs,
            const std::vector<int32_t>& out_begin,
            const std::vector<int32_t>& out,
            const std::vector<int32_t>& in_begin,
            const std::vector<int32_t>& in, int32_t na, int32_t nb,
            const CoverBound& bound_a, const CoverBound& bound_b,
            const SurfaceCosts& costs)
      : nodes_(nodes),
        arcs_(arcs),
        out_begin_(out_begin),
        out_(out),
        in_begin_(in_begin),
        in_(in),
        na_(na),
        nb_(nb),
        bound_a_(bound_a),
        bound_b_(bound_b),
        costs_(costs),
        prune_(costs.NonNegative()),
        bi_(costs.bi()) {
    const size_t slots = bi_ ? arcs.size() : nodes.size();
    dist_.assign(slots * kCounts, kInf);
    pred_.resize(slots * kCounts);
    queued_.assign(nodes.size(), 0);
  }

  // What any cycle from a start whose first run of A-sides (to past A's
  // last edge) costs at least `fan` costs at least (0 unless prunable): the
  // run bounds the A edges it covers, so the better of it and A's cover
  // bound, plus B's.
  double StartBound(double fan) const {
    if (!prune_) return 0;
    return std::max(fan, bound_a_.Sum(0, na_)) + bound_b_.Sum(0, nb_);
  }

  // Best cycle from start node `s` (DOT2: whose first arc is `first`) below
  // `*best`; on success replaces *best and *path (arcs in cycle order).
  bool Run(int32_t s, int32_t first, RunTicker* ticker, double* best,
           std::vector<int32_t>* path, int64_t* states, bool* stopped);

 private:
  struct Pred {
    int32_t arc = -1;  // DOT1: arc into the node; DOT2: the arc before
    int8_t count = 0;
  };
  // Unrolled coordinates of node v for start s.
  std::pair<int32_t, int32_t> Coords(int32_t s, int32_t v) const {
    const Node& st = nodes_[s];
    const Node& n = nodes_[v];
    if (v == s) return {0, 0};
    const int32_t ru = n.x == st.x ? na_ : (n.x - st.x + na_) % na_;
    const int32_t rv = n.y == st.y ? 0 : (st.y - n.y + nb_) % nb_;
    return {ru, rv};
  }
  // Lower bound on the rest of a cycle from start s at (ru, rv): A's edges
  // from a + ru on, and B's (walked backwards from q) still to cover.
  double Remaining(int32_t s, int32_t ru, int32_t rv) const {
    const Node& st = nodes_[s];
    return bound_a_.Sum((st.x + ru) % na_, na_ - ru) +
           bound_b_.Sum(st.y, nb_ - rv);
  }
  // Whether arc may leave node (ru, rv) for start s; sets *sink and the
  // coordinates it reaches.
  bool Allowed(int32_t s, const Arc& arc, int32_t ru, int32_t rv, bool* sink,
               int32_t* eu, int32_t* ev) const {
    *sink = arc.to == s;
    if (!arc.on_a && rv == 0 && ru < na_ - nodes_[s].x) {
      return false;  // the first B-side only after A's last edge
    }
    *eu = arc.on_a ? ru + arc.advance : ru;
    *ev = arc.on_a ? rv : rv + arc.advance;
    if (*sink) return !arc.on_a && *eu == na_ && *ev == nb_;
    const auto [tu, tv] = Coords(s, arc.to);
    return tu == *eu && tv == *ev;
  }
  void Queue(int32_t s, int32_t v) {
    if (queued_[v]) return;
    queued_[v] = 1;
    queued_list_.push_back(v);
    const auto [ru, rv] = Coords(s, v);
    heap_.push_back({int64_t{ru} * (nb_ + 1) + rv, v});
    std::push_heap(heap_.begin(), heap_.end(), std::greater<>());
  }
  void Set(size_t slot, double value, Pred pred) {
    if (dist_[slot] == kInf) touched_.push_back(slot);
    dist_[slot] = value;
    pred_[slot] = pred;
  }
  void Reset() {
    for (size_t slot : touched_) dist_[slot] = kInf;
    for (int32_t v : queued_list_) queued_[v] = 0;
    touched_.clear();
    queued_list_.clear();
    heap_.clear();
  }

  const std::vector<Node>& nodes_;
  const std::vector<Arc>& arcs_;
  const std::vector<int32_t>&out_begin_, &out_, &in_begin_, &in_;
  const int32_t na_, nb_;
  const CoverBound &bound_a_, &bound_b_;
  const SurfaceCosts& costs_;
  const bool prune_, bi_;
  std::vector<double> dist_;
  std::vector<Pred> pred_;
  std::vector<size_t> touched_;
  std::vector<char> queued_;
  std::vector<int32_t> queued_list_;
  std::vector<std::pair<int64_t, int32_t>> heap_;
};

bool StripPass::Run(int32_t s, int32_t first, RunTicker* ticker, double* best,
                    std::vector<int32_t>* path, int64_t* states,
                    bool* stopped) {
  Reset();
  double found = *best;
  int32_t last_arc = -1, last_from = -1;  // the arc into the sink
  int last_count = 0;

  if (bi_) {
    const Arc& f = arcs_[first];
    bool sink = false;
    int32_t eu = 0, ev = 0;
    if (f.from != s || !f.on_a || !Allowed(s, f, 0, 0, &sink, &eu, &ev) ||
        sink) {
      return false;
    }
    if (prune_ && f.cost + Remaining(s, eu, ev) >= found) return false;
    Set(static_cast<size_t>(first) * kCounts + Counted(0, true), f.cost, {});
    Queue(s, f.to);
  } else {
    Set(static_cast<size_t>(s) * kCounts, 0, {});
    Queue(s, s);
  }

  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), std::greater<>());
    const int32_t v = heap_.back().second;
    heap_.pop_back();
    if (!ticker->Tick()) {
      *stopped = true;
      return false;
    }
    const auto [ru, rv] = Coords(s, v);
    for (int32_t i = out_begin_[v]; i < out_begin_[v + 1]; ++i) {
      if (!ticker->Tick()) {  // a pop can relax in * out * 16 states
        *stopped = true;
        return false;
      }
      const int32_t b = out_[i];
      const Arc& arc = arcs_[b];
      bool sink = false;
      int32_t eu = 0, ev = 0;
      if (!Allowed(s, arc, ru, rv, &sink, &eu, &ev)) continue;
      const double rest = prune_ && !sink ? Remaining(s, eu, ev) : 0;
      // The states the arc continues: the node's (DOT1), or those of each
      // arc into the node (DOT2, which prices the bend between them).
      const int32_t ib = bi_ ? in_begin_[v] : 0,
                    ie = bi_ ? in_begin_[v + 1] : 1;
      for (int32_t j = ib; j < ie; ++j) {
        if (bi_ && !ticker->Tick()) {
          *stopped = true;
          return false;
        }
        const int32_t a = bi_ ? in_[j] : -1;
        const size_t from_slot = bi_ ? static_cast<size_t>(a) : v;
        if (bi_ && dist_[from_slot * kCounts + kCounts - 1] == kInf) {
          bool any = false;
          for (int c = 0; c < kCounts && !any; ++c) {
            any = dist_[from_slot * kCounts + c] != kInf;
          }
          if (!any) continue;
        }
        const double bend = bi_ ? costs_.Bend(arcs_[a].normal, arc.normal) : 0;
        for (int c = 0; c < kCounts; ++c) {
          const double d = dist_[from_slot * kCounts + c];
          if (d == kInf) continue;
          ++*states;
          double value = d + bend + arc.cost;
          if (prune_ && value + rest >= found) continue;
          const int next = Counted(c, arc.on_a);
          if (sink) {
            if (bi_) value += costs_.Bend(arc.normal, arcs_[first].normal);
            if (next == kEnough && value < found) {
              found = value;
              last_arc = b;
              last_from = bi_ ? a : v;
              last_count = c;
            }
            continue;
          }
          const size_t to =
              (bi_ ? static_cast<size_t>(b) : arc.to) * kCounts + next;
          if (value < dist_[to]) {
            Set(to, value, {bi_ ? a : b, static_cast<int8_t>(c)});
            Queue(s, arc.to);
          }
        }
      }
    }
  }
  if (last_arc < 0) return false;
  *best = found;
  path->assign(1, last_arc);
  if (bi_) {
    // Back through the arcs before the last, to the fixed first arc.
    int32_t a = last_from;
    int c = last_count;
    while (a >= 0) {
      path->push_back(a);
      const Pred p = pred_[static_cast<size_t>(a) * kCounts + c];
      a = p.arc;
      c = p.count;
    }
  } else {
    int32_t v = last_from;
    int c = last_count;
    while (v != s || c != 0) {
      const Pred p = pred_[static_cast<size_t>(v) * kCounts + c];
      path->push_back(p.arc);
      v = arcs_[p.arc].from;
      c = p.count;
    }
  }
  std::reverse(path->begin(), path->end());
  return true;
}

}  // namespace

int64_t EstimateAnnulusBytes(int64_t candidates) {
  // Two arcs per candidate with their DP states (DOT2 keeps them per arc),
  // and ears: chords with their inner lists and candidates.
  // Per state slot: its cost, its predecessor and (once reached) its entry
  // in the list of slots to reset.
  return candidates * 2 *
             static_cast<int64_t>(sizeof(Arc) +
                                  kCounts * (sizeof(double) + 16)) +
         candidates * 3 * 96;
}

Status SolveAnnulus(const std::vector<int32_t>& loop_a,
                    const std::vector<int32_t>& loop_b,
                    const std::vector<Triangle>& candidates,
                    const SurfaceCosts& costs, int64_t memory_budget_bytes,
                    double upper_bound, const Control& control,
                    AnnulusSolution* out) {
  const auto na = static_cast<int32_t>(loop_a.size());
  const auto nb = static_cast<int32_t>(loop_b.size());
  std::vector<int32_t> local(costs.points.size(), -1);
  std::vector<int8_t> side(costs.points.size(), -1);  // 0: A, 1: B
  for (int32_t i = 0; i < na; ++i) {
    local[loop_a[i]] = i;
    side[loop_a[i]] = 0;
  }
  for (int32_t i = 0; i < nb; ++i) {
    local[loop_b[i]] = i;
    side[loop_b[i]] = 1;
  }
  RunTicker ticker(control, Stage::kDynamicProgram);

  // Sort the candidates into ears of A, ears of B, and cross triangles.
  std::vector<Triangle> on_a, on_b, cross;
  for (const Triangle& t : candidates) {
    const int sides = side[t[0]] + side[t[1]] + side[t[2]];
    if (side[t[0]] < 0 || side[t[1]] < 0 || side[t[2]] < 0) continue;
    (sides == 0 ? on_a : sides == 3 ? on_b : cross).push_back(t);
  }
  const int64_t estimate =
      EstimateAnnulusBytes(static_cast<int64_t>(candidates.size()));
  if (estimate > memory_budget_bytes) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "estimated memory " + std::to_string(estimate >> 20) +
                          " MiB for " + std::to_string(candidates.size()) +
                          " candidate triangles exceeds the budget of " +
                          std::to_string(memory_budget_bytes >> 20) + " MiB");
  }
  LoopEars ears_a, ears_b;
  if (Status s = ears_a.Build(loop_a, on_a, costs, control); !s.ok()) return s;
  if (Status s = ears_b.Build(loop_b, on_b, costs, control); !s.ok()) return s;

  // Nodes: the edges between the loops, numbered in (x, y) order.
  std::vector<int64_t> node_keys;
  auto node_key = [&](int32_t pa, int32_t pb) {
    return int64_t{local[pa]} * nb + local[pb];
  };
  for (const Triangle& t : cross) {
    for (int k = 0; k < 3; ++k) {
      const int32_t p = t[k], q = t[(k + 1) % 3];
      if (side[p] != side[q]) {
        node_keys.push_back(side[p] == 0 ? node_key(p, q) : node_key(q, p));
      }
    }
  }
  std::sort(node_keys.begin(), node_keys.end());
  node_keys.erase(std::unique(node_keys.begin(), node_keys.end()),
                  node_keys.end());
  std::vector<Node> nodes;
  nodes.reserve(node_keys.size());
  for (int64_t k : node_keys) {
    nodes.push_back(
        {static_cast<int32_t>(k / nb), static_cast<int32_t>(k % nb)});
  }
  auto node_of = [&](int32_t pa, int32_t pb) {
    return static_cast<int32_t>(
        std::lower_bound(node_keys.begin(), node_keys.end(), node_key(pa, pb)) -
        node_keys.begin());
  };

  // Arcs: each cross triangle with either of its two same-loop corners
  // first, when its ear exists.
  std::vector<Arc> arcs;
  for (const Triangle& t : cross) {
    if (!ticker.Tick()) return ticker.status();
    const bool two_on_a = side[t[0]] + side[t[1]] + side[t[2]] == 1;
    std::array<int32_t, 2> pair{};
    int32_t other = -1, k = 0;
    for (int32_t p : t) {
      if ((side[p] == 0) == two_on_a) {
        pair[k++] = p;
      } else {
        other = p;
      }
    }
    const int32_t n = two_on_a ? na : nb;
    const LoopEars& ears = two_on_a ? ears_a : ears_b;
    for (int flip = 0; flip < 2; ++flip) {
      const int32_t f = pair[flip], g = pair[1 - flip];  // chord f -> g
      const int32_t advance = (local[g] - local[f] + n) % n;
      if (advance < 1 || advance > n - 2) continue;
      Arc arc;
      arc.on_a = two_on_a;
      arc.advance = advance;
      arc.tri = {f, g, other};
      arc.normal = costs.Normal(arc.tri);
      const double ear = ears.Cost(f, g, arc.normal);
      if (ear == kInf) continue;
      arc.cost = costs.Weight(arc.tri) + ear;
      arc.chord_from = f;
      arc.chord_to = g;
      // A-sides move from (f, other) to (g, other); B is walked against
      // its direction, from (other, g) to (other, f).
      arc.from = two_on_a ? node_of(f, other) : node_of(other, g);
      arc.to = two_on_a ? node_of(g, other) : node_of(other, f);
      arcs.push_back(arc);
    }
  }
  const auto node_count = static_cast<int32_t>(nodes.size());
  std::vector<int32_t> out_begin(node_count + 1, 0),
      in_begin(node_count + 1, 0);
  for (const Arc& a : arcs) {
    ++out_begin[a.from + 1];
    ++in_begin[a.to + 1];
  }
  std::partial_sum(out_begin.begin(), out_begin.end(), out_begin.begin());
  std::partial_sum(in_begin.begin(), in_begin.end(), in_begin.begin());
  std::vector<int32_t> out_arcs(arcs.size()), in_arcs(arcs.size());
  {
    std::vector<int32_t> o(out_begin.begin(), out_begin.end() - 1),
        i(in_begin.begin(), in_begin.end() - 1);
    for (int32_t id = 0; id < static_cast<int32_t>(arcs.size()); ++id) {
      out_arcs[o[arcs[id].from]++] = id;
      in_arcs[i[arcs[id].to]++] = id;
    }
  }

  // Cover bounds (see CoverBound).
  CoverBound bound_a, bound_b;
  bound_a.Init(na);
  bound_b.Init(nb);
  for (const Arc& a : arcs) {
    if (a.on_a) {
      bound_a.Add(nodes[a.from].x, a.advance, a.cost);
    } else {
      // From (x, p') to (x, p): B's edges p .. p' - 1.
      bound_b.Add(nodes[a.to].y, a.advance, a.cost);
    }
  }
  bound_a.Finish();
  bound_b.Finish();
  if (!bound_a.Covered() || !bound_b.Covered()) {
    // Some loop edge is on no usable side: no cycle can cover it.
    return MakeStatus(StatusCode::kNoTriangulation, "");
  }
  // Per node (a, q): the least cost of a run of A-sides at q from a to past
  // A's last edge, which every cycle starting there begins with (kInf: no
  // such run, not a start). Runs at q go up in a, so by decreasing a.
  std::vector<double> fan(node_count, kInf);
  {
    std::vector<int32_t> by_row(node_count);
    std::iota(by_row.begin(), by_row.end(), 0);
    std::sort(by_row.begin(), by_row.end(), [&](int32_t u, int32_t v) {
      return nodes[u].y < nodes[v].y ||
             (nodes[u].y == nodes[v].y && nodes[u].x > nodes[v].x);
    });
    for (int32_t v : by_row) {
      for (int32_t i = out_begin[v]; i < out_begin[v + 1]; ++i) {
        const Arc& a = arcs[out_arcs[i]];
        if (!a.on_a) continue;
        const bool crosses = nodes[v].x + a.advance >= na;
        fan[v] = std::min(fan[v], crosses ? a.cost : a.cost + fan[a.to]);
      }
    }
  }
  StripPass pass(nodes, arcs, out_begin, out_arcs, in_begin, in_arcs, na, nb,
                 bound_a, bound_b, costs);
  // Starts: nodes (a, q), a != 0, where q has an A-side across A's last
  // edge; likeliest first, so the best cycle so far prunes the rest.
  std::vector<std::pair<double, int32_t>> starts;
  for (int32_t s = 0; s < node_count; ++s) {
    if (nodes[s].x == 0 || fan[s] == kInf) continue;
    starts.emplace_back(pass.StartBound(fan[s]), s);
  }
  std::sort(starts.begin(), starts.end());
  const bool prune = costs.NonNegative();
  double best = upper_bound;
  std::vector<int32_t> path, candidate_path;
  bool stopped = false;
  for (const auto& [bound, s] : starts) {
    if (prune && bound >= best) break;
    if (costs.bi()) {
      for (int32_t i = out_begin[s]; i < out_begin[s + 1]; ++i) {
        if (pass.Run(s, out_arcs[i], &ticker, &best, &candidate_path,
                     &out->states, &stopped)) {
          path = candidate_path;
        }
        if (stopped) return ticker.status();
      }
    } else {
      if (pass.Run(s, -1, &ticker, &best, &candidate_path, &out->states,
                   &stopped)) {
        path = candidate_path;
      }
      if (stopped) return ticker.status();
    }
  }
  out->table_bytes =
      ears_a.Bytes() + ears_b.Bytes() +
      static_cast<int64_t>(arcs.size() * (sizeof(Arc) + 8)) +
      static_cast<int64_t>((costs.bi() ? arcs.size() : nodes.size()) * kCounts *
                           (sizeof(double) + 8));
  if (path.empty()) return MakeStatus(StatusCode::kNoTriangulation, "");
  out->cost = best;
  out->triangles.clear();
  for (int32_t id : path) {
    const Arc& a = arcs[id];
    out->triangles.push_back(a.tri);
    (a.on_a ? ears_a : ears_b)
        .Collect(a.chord_from, a.chord_to, a.normal, &out->triangles);
  }
  return OkStatus();
}

}  // namespace dot

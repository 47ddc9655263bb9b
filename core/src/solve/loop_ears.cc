// SPDX-License-Identifier: AGPL-3.0-or-later
#include "solve/loop_ears.h"

#include <algorithm>
#include <array>
#include <tuple>
#include <utility>

#include "solve/solvers.h"
#include "util/run_control.h"

namespace dot {

int32_t LoopEars::Span(int32_t from, int32_t to) const {
  const auto n = static_cast<int32_t>(loop_.size());
  const int32_t f = local_.at(from), t = local_.at(to);
  return (t - f + n) % n;
}

int32_t LoopEars::Find(int32_t from, int32_t to) const {
  const auto n = static_cast<int64_t>(loop_.size());
  const auto it = chord_id_.find(from * n + to);
  return it == chord_id_.end() ? -1 : it->second;
}

Status LoopEars::Build(const std::vector<int32_t>& loop,
                       const std::vector<Triangle>& triangles,
                       const SurfaceCosts& costs, const Control& control) {
  costs_ = &costs;
  min_bend_ = costs.MinBend();
  loop_ = loop;
  const auto n = static_cast<int32_t>(loop.size());
  local_.clear();
  for (int32_t i = 0; i < n; ++i) local_[loop[i]] = i;
  RunTicker ticker(control, Stage::kDynamicProgram);

  // Every directed side of every triangle, and the loop edges, is a chord;
  // each triangle is inner to the three chords whose chain holds its apex.
  std::vector<std::tuple<int32_t, int32_t, int32_t>> inner;  // from, to, apex
  std::vector<std::pair<int32_t, int32_t>> directed;
  for (int32_t i = 0; i < n; ++i) directed.emplace_back(i, (i + 1) % n);
  for (const Triangle& t : triangles) {
    if (!ticker.Tick()) return ticker.status();
    std::array<int32_t, 3> c = {local_.at(t[0]), local_.at(t[1]),
                                local_.at(t[2])};
    std::sort(c.begin(), c.end());
    // Chains a->c (apex b), b->a (apex c), c->b (apex a), in loop order.
    inner.emplace_back(c[0], c[2], c[1]);
    inner.emplace_back(c[1], c[0], c[2]);
    inner.emplace_back(c[2], c[1], c[0]);
    for (int k = 0; k < 3; ++k) {
      directed.emplace_back(c[k], c[(k + 1) % 3]);
      directed.emplace_back(c[(k + 1) % 3], c[k]);
    }
  }
  std::sort(directed.begin(), directed.end());
  directed.erase(std::unique(directed.begin(), directed.end()), directed.end());
  std::sort(inner.begin(), inner.end());
  chords_.clear();
  chord_id_.clear();
  inner_apex_.clear();
  inner_apex_.reserve(inner.size());
  size_t k = 0;
  for (const auto& [f, t] : directed) {
    Chord c{f, t, (t - f + n) % n, kInf, -1, 0, 0, 0, 0};
    c.inner_begin = static_cast<int32_t>(inner_apex_.size());
    while (k < inner.size() &&
           std::make_pair(std::get<0>(inner[k]), std::get<1>(inner[k])) <
               std::make_pair(f, t)) {
      ++k;
    }
    for (; k < inner.size() && std::get<0>(inner[k]) == f &&
           std::get<1>(inner[k]) == t;
         ++k) {
      inner_apex_.push_back(std::get<2>(inner[k]));
    }
    c.inner_end = static_cast<int32_t>(inner_apex_.size());
    chord_id_[int64_t{f} * n + t] = static_cast<int32_t>(chords_.size());
    chords_.push_back(c);
  }

  // Solve by increasing span: children are always shorter. Spans of n - 1
  // and more would close the whole loop; a surface with other boundaries
  // never needs them.
  std::vector<int32_t> order(chords_.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int32_t>(i);
  std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) {
    return chords_[a].span < chords_[b].span;
  });
  const bool bi = costs.bi();
  cands_.clear();
  for (int32_t id : order) {
    Chord& c = chords_[id];
    if (c.span == 1) {
      c.best = 0;
      continue;
    }
    if (c.span >= n - 1) continue;
    c.cand_begin = static_cast<int32_t>(cands_.size());
    for (int32_t i = c.inner_begin; i < c.inner_end; ++i) {
      if (!ticker.Tick()) return ticker.status();
      const int32_t z = inner_apex_[i];
      const Triangle u = Oriented(c.from, z, c.to);
      if (bi) {
        const Vec3 nu = costs.Normal(u);
        const double b = costs.Weight(u) + Cost(loop_[c.from], loop_[z], nu) +
                         Cost(loop_[z], loop_[c.to], nu);
        if (b < kInf) cands_.push_back({b, z, nu});
      } else {
        const double b = costs.Weight(u) + chords_[Find(c.from, z)].best +
                         chords_[Find(z, c.to)].best;
        if (b < c.best) {
          c.best = b;
          c.apex = z;
        }
      }
    }
    c.cand_end = static_cast<int32_t>(cands_.size());
    std::sort(cands_.begin() + c.cand_begin, cands_.begin() + c.cand_end,
              [](const Candidate& x, const Candidate& y) {
                return x.b < y.b || (x.b == y.b && x.apex < y.apex);
              });
  }
  return OkStatus();
}

int32_t LoopEars::BestApex(const Chord& c, const Vec3& outer,
                           double* cost) const {
  double best = kInf;
  int32_t apex = -1;
  for (int32_t i = c.cand_begin; i < c.cand_end; ++i) {
    const Candidate& x = cands_[i];
    if (x.b + min_bend_ >= best) break;
    const double v = x.b + costs_->Bend(x.normal, outer);
    if (v < best) {
      best = v;
      apex = x.apex;
    }
  }
  *cost = best;
  return apex;
}

double LoopEars::Cost(int32_t from, int32_t to, const Vec3& outer) const {
  const auto f = local_.find(from), t = local_.find(to);
  if (f == local_.end() || t == local_.end()) return kInf;
  const int32_t id = Find(f->second, t->second);
  if (id < 0) return kInf;
  const Chord& c = chords_[id];
  if (c.span == 1) return costs_->BoundaryBend(from, outer);
  if (!costs_->bi()) return c.best;
  double cost = kInf;
  BestApex(c, outer, &cost);
  return cost;
}

void LoopEars::Collect(int32_t from, int32_t to, const Vec3& outer,
                       std::vector<Triangle>* out) const {
  struct Item {
    int32_t chord;
    Vec3 outer;
  };
  std::vector<Item> stack = {{Find(local_.at(from), local_.at(to)), outer}};
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const Chord& c = chords_[item.chord];
    if (c.span == 1) continue;
    double cost = 0;
    const int32_t z = costs_->bi() ? BestApex(c, item.outer, &cost) : c.apex;
    const Triangle u = Oriented(c.from, z, c.to);
    out->push_back(u);
    const Vec3 nu = costs_->bi() ? costs_->Normal(u) : Vec3{};
    stack.push_back({Find(c.from, z), nu});
    stack.push_back({Find(z, c.to), nu});
  }
}

int64_t LoopEars::Bytes() const {
  return static_cast<int64_t>(chords_.size() * (sizeof(Chord) + 32) +
                              inner_apex_.size() * sizeof(int32_t) +
                              cands_.size() * sizeof(Candidate) +
                              loop_.size() * 24);
}

}  // namespace dot

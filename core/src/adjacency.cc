// SPDX-License-Identifier: AGPL-3.0-or-later
#include "adjacency.h"

#include <limits>

#include "run_control.h"

namespace dot {
namespace {

// Sort key of an edge incidence: span, then low end, then slot. Fits 64 bits
// for n < 2^24.
constexpr int kSlotBits = 2, kLoBits = 24;

struct Incidence {
  uint64_t key;
  int32_t triangle;
};

uint64_t IncidenceKey(int32_t lo, int32_t hi, int slot) {
  return (uint64_t(hi - lo) << (kLoBits + kSlotBits)) |
         (uint64_t(lo) << kSlotBits) | uint64_t(slot);
}

// Insertion sort of a short list (a few entries per edge on average).
template <typename Key>
void SortShort(int32_t* begin, int32_t* end, Key key) {
  for (int32_t* i = begin + 1; i < end; ++i) {
    const int32_t v = *i;
    const int32_t k = key(v);
    int32_t* j = i;
    for (; j > begin && key(j[-1]) > k; --j) *j = j[-1];
    *j = v;
  }
}

// Orders every edge's lists by the triangles' third vertex, so the dynamic
// programs (and their tie-breaking) depend only on the candidate set, not on
// the order a Delaunay backend happened to list it in.
void CanonicalOrder(const std::vector<Triangle>& triangles, Adjacency* adj) {
  for (int32_t e = 0; e < adj->edge_count(); ++e) {
    SortShort(adj->inner.data() + adj->inner_begin[e],
              adj->inner.data() + adj->inner_begin[e + 1],
              [&](int32_t t) { return triangles[t][1]; });
    SortShort(adj->outer.data() + adj->outer_begin[e],
              adj->outer.data() + adj->outer_begin[e + 1], [&](int32_t slot) {
                const Triangle& t = triangles[slot >> 1];
                return (slot & 1) == 0 ? t[2] : t[0];
              });
  }
}

}  // namespace

int64_t Adjacency::Bytes() const {
  auto bytes = [](const auto& v) {
    return static_cast<int64_t>(v.capacity() * sizeof(v[0]));
  };
  return bytes(edge_lo) + bytes(edge_hi) + bytes(inner_begin) + bytes(inner) +
         bytes(outer_begin) + bytes(outer) + bytes(tri_edges);
}

Status BuildAdjacency(int32_t n, const std::vector<Triangle>& triangles,
                      const Control& control, Adjacency* out) {
  if (n >= (1 << kLoBits)) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "polygon has " + std::to_string(n) +
                          " vertices; the limit is 16777215");
  }
  if (triangles.size() * 3 >=
      static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
    return MakeStatus(
        StatusCode::kResourceExhausted,
        "too many candidate triangles: " + std::to_string(triangles.size()));
  }
  RunTicker ticker(control, Stage::kAdjacency);
  const auto tcount = static_cast<int32_t>(triangles.size());
  // Incidences sorted by (span, lo), stable in (triangle, slot): two counting
  // passes, linear in the input and interruptible, instead of a comparison
  // sort.
  FlatVector<Incidence> inc(3 * triangles.size()), tmp;
  tmp.reserve(inc.size());
  for (int32_t t = 0; t < tcount; ++t) {
    const auto& [a, b, c] = triangles[t];
    tmp.push_back({IncidenceKey(a, b, 0), t});
    tmp.push_back({IncidenceKey(b, c, 1), t});
    tmp.push_back({IncidenceKey(a, c, 2), t});
    if (!ticker.Tick()) return ticker.status();
  }
  auto lo_of = [](const Incidence& x) {
    return static_cast<int32_t>((x.key >> kSlotBits) & ((1u << kLoBits) - 1));
  };
  auto span_of = [](const Incidence& x) {
    return static_cast<int32_t>(x.key >> (kLoBits + kSlotBits));
  };
  auto counting_pass = [&](const FlatVector<Incidence>& from,
                           FlatVector<Incidence>* to, auto digit) {
    std::vector<int32_t> start(n + 1, 0);
    for (const Incidence& x : from) ++start[digit(x) + 1];
    for (int32_t d = 0; d < n; ++d) start[d + 1] += start[d];
    for (const Incidence& x : from) {
      (*to)[start[digit(x)]++] = x;
      if (!ticker.Tick()) return false;
    }
    return true;
  };
  if (!counting_pass(tmp, &inc, lo_of) || !counting_pass(inc, &tmp, span_of)) {
    return ticker.status();
  }
  inc.swap(tmp);
  tmp = {};

  Adjacency& adj = *out;
  adj = Adjacency{};
  adj.n = n;
  adj.tri_edges.resize(3 * triangles.size());
  adj.inner.reserve(triangles.size());
  adj.outer.reserve(2 * triangles.size());
  std::vector<bool> has_polygon_edge(n, false);
  uint64_t prev_edge = ~uint64_t{0};
  for (const Incidence& x : inc) {
    const uint64_t edge = x.key >> kSlotBits;
    if (edge != prev_edge) {
      prev_edge = edge;
      const auto lo = static_cast<int32_t>(edge & ((1u << kLoBits) - 1));
      const auto hi = lo + static_cast<int32_t>(edge >> kLoBits);
      adj.edge_lo.push_back(lo);
      adj.edge_hi.push_back(hi);
      adj.inner_begin.push_back(static_cast<int32_t>(adj.inner.size()));
      adj.outer_begin.push_back(static_cast<int32_t>(adj.outer.size()));
      if (hi - lo == 1) has_polygon_edge[lo] = true;
      if (lo == 0 && hi == n - 1) {
        adj.root = static_cast<int32_t>(adj.edge_lo.size()) - 1;
        has_polygon_edge[n - 1] = true;
      }
    }
    const int slot = static_cast<int>(x.key & 3);
    adj.tri_edges[3 * x.triangle + slot] =
        static_cast<int32_t>(adj.edge_lo.size()) - 1;
    if (slot == 2) {
      adj.inner.push_back(x.triangle);
    } else {
      adj.outer.push_back(2 * x.triangle + slot);
    }
  }
  adj.inner_begin.push_back(static_cast<int32_t>(adj.inner.size()));
  adj.outer_begin.push_back(static_cast<int32_t>(adj.outer.size()));
  CanonicalOrder(triangles, &adj);
  for (int32_t i = 0; i < n; ++i) {
    if (!has_polygon_edge[i]) adj.missing_polygon_edges.push_back(i);
  }
  return OkStatus();
}

}  // namespace dot

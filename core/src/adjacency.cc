// SPDX-License-Identifier: AGPL-3.0-or-later
#include "adjacency.h"

#include <algorithm>
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
    return MakeStatus(StatusCode::kResourceExhausted,
                      "too many candidate triangles: " +
                          std::to_string(triangles.size()));
  }
  RunTicker ticker(control, Stage::kAdjacency);
  const auto tcount = static_cast<int32_t>(triangles.size());
  std::vector<Incidence> inc;
  inc.reserve(3 * triangles.size());
  for (int32_t t = 0; t < tcount; ++t) {
    const auto& [a, b, c] = triangles[t];
    inc.push_back({IncidenceKey(a, b, 0), t});
    inc.push_back({IncidenceKey(b, c, 1), t});
    inc.push_back({IncidenceKey(a, c, 2), t});
  }
  std::sort(inc.begin(), inc.end(), [](const Incidence& x, const Incidence& y) {
    return x.key < y.key || (x.key == y.key && x.triangle < y.triangle);
  });
  if (!ticker.Poll()) return ticker.status();

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
  for (int32_t i = 0; i < n; ++i) {
    if (!has_polygon_edge[i]) adj.missing_polygon_edges.push_back(i);
  }
  return OkStatus();
}

}  // namespace dot

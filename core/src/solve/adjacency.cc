// SPDX-License-Identifier: AGPL-3.0-or-later
#include "solve/adjacency.h"

#include <algorithm>
#include <limits>

#include "util/run_control.h"
#include "util/short_sort.h"

namespace dot {
namespace {

// An edge incidence is a 4-byte record 4 * triangle + slot; its edge is
// looked up in the triangle: slot 0 is [a, b], 1 is [b, c], 2 is [a, c].
struct EdgeOf {
  const std::vector<Triangle>& triangles;
  std::pair<int32_t, int32_t> operator()(uint32_t record) const {
    const Triangle& t = triangles[record >> 2];
    switch (record & 3) {
      case 0:
        return {t[0], t[1]};
      case 1:
        return {t[1], t[2]};
      default:
        return {t[0], t[2]};
    }
  }
};

// Orders every edge's lists by the triangles' third vertex, so the dynamic
// programs (and their tie-breaking) depend only on the candidate set, not on
// the order a Delaunay backend happened to list it in.
Status CanonicalOrder(const std::vector<Triangle>& triangles, RunTicker& ticker,
                      Adjacency* adj) {
  for (int32_t e = 0; e < adj->edge_count(); ++e) {
    if (!ticker.Tick()) return ticker.status();
    // Keys are distinct within a list: the third vertices of distinct
    // triangles on one edge.
    SortShortList(adj->inner.data() + adj->inner_begin[e],
                  adj->inner.data() + adj->inner_begin[e + 1],
                  [&](int32_t a, int32_t b) {
                    return triangles[a][1] < triangles[b][1];
                  });
    auto outer_third = [&](int32_t slot) {
      const Triangle& t = triangles[slot >> 1];
      return (slot & 1) == 0 ? t[2] : t[0];
    };
    SortShortList(
        adj->outer.data() + adj->outer_begin[e],
        adj->outer.data() + adj->outer_begin[e + 1],
        [&](int32_t a, int32_t b) { return outer_third(a) < outer_third(b); });
  }
  return OkStatus();
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
  if (n > kMaxVertices) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "polygon has " + std::to_string(n) +
                          " vertices; the limit is " +
                          std::to_string(kMaxVertices));
  }
  if (triangles.size() >= (size_t{1} << 29)) {
    return MakeStatus(
        StatusCode::kResourceExhausted,
        "too many candidate triangles: " + std::to_string(triangles.size()));
  }
  RunTicker ticker(control, Stage::kAdjacency);
  const EdgeOf edge_of{triangles};
  // Incidences sorted by (span, lo), stable in (triangle, slot): two
  // counting passes, linear and interruptible, over 4-byte records (the
  // edge is looked up, not stored, to keep the buffers small: page faults
  // dominate here).
  const size_t records = 3 * triangles.size();
  std::vector<int32_t> start(n + 1);
  // Every pass ticks: the all-triangles space brings millions of records.
  for (const Triangle& t : triangles) {
    if (!ticker.Tick()) return ticker.status();
    ++start[t[0] + 1];
    ++start[t[1] + 1];
    ++start[t[0] + 1];
  }
  for (int32_t d = 0; d < n; ++d) start[d + 1] += start[d];
  FlatVector<uint32_t> by_lo(records), by_span(records);
  for (uint32_t t = 0; t < triangles.size(); ++t) {
    if (!ticker.Tick()) return ticker.status();
    const Triangle& tri = triangles[t];
    by_lo[start[tri[0]]++] = 4 * t;
    by_lo[start[tri[1]]++] = 4 * t + 1;
    by_lo[start[tri[0]]++] = 4 * t + 2;
  }
  std::fill(start.begin(), start.end(), 0);
  for (uint32_t r : by_lo) {
    if (!ticker.Tick()) return ticker.status();
    const auto [lo, hi] = edge_of(r);
    ++start[hi - lo + 1];
  }
  for (int32_t d = 0; d < n; ++d) start[d + 1] += start[d];
  for (uint32_t r : by_lo) {
    if (!ticker.Tick()) return ticker.status();
    const auto [lo, hi] = edge_of(r);
    by_span[start[hi - lo]++] = r;
  }
  by_lo = {};

  Adjacency& adj = *out;
  adj = Adjacency{};
  adj.n = n;
  adj.tri_edges.resize(3 * triangles.size());
  adj.inner.reserve(triangles.size());
  adj.outer.reserve(2 * triangles.size());
  std::vector<bool> has_polygon_edge(n, false);
  std::pair<int32_t, int32_t> prev_edge{-1, -1};
  for (uint32_t r : by_span) {
    if (!ticker.Tick()) return ticker.status();
    const std::pair<int32_t, int32_t> edge = edge_of(r);
    if (edge != prev_edge) {
      prev_edge = edge;
      const auto [lo, hi] = edge;
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
    const auto t = static_cast<int32_t>(r >> 2);
    const int slot = static_cast<int>(r & 3);
    adj.tri_edges[3 * t + slot] = static_cast<int32_t>(adj.edge_lo.size()) - 1;
    if (slot == 2) {
      adj.inner.push_back(t);
    } else {
      adj.outer.push_back(2 * t + slot);
    }
  }
  adj.inner_begin.push_back(static_cast<int32_t>(adj.inner.size()));
  adj.outer_begin.push_back(static_cast<int32_t>(adj.outer.size()));
  const Status ordered = CanonicalOrder(triangles, ticker, &adj);
  if (!ordered.ok()) return ordered;
  for (int32_t i = 0; i < n; ++i) {
    if (!has_polygon_edge[i]) adj.missing_polygon_edges.push_back(i);
  }
  return OkStatus();
}

int64_t EstimateTableBytes(int64_t triangles, bool bi_triangle) {
  // Per candidate: the triangle, its weight, three edge ids, the sort
  // records (3 x 16 bytes, transient), adjacency lists; per edge (at most
  // 1.5 per triangle in practice, 3 at worst) offsets, ends and DP entries.
  int64_t per_triangle = 12 + 8 + 12 + 48 + 12 + 3 * (4 * 4 + 12);
  if (bi_triangle) per_triangle += 24 + 2 * (8 + 4) + 36;
  return triangles * per_triangle;
}

}  // namespace dot

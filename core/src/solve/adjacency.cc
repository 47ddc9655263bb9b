// SPDX-License-Identifier: AGPL-3.0-or-later
#include "solve/adjacency.h"

#include <algorithm>
#include <string>

#include "util/run_control.h"

namespace dot {
namespace {

// Checks that every candidate is three ascending positions below n, and
// finds whether the list is already in lexicographic order.
Status CheckCandidates(int32_t n, const std::vector<Triangle>& triangles,
                       RunTicker& ticker, bool* sorted) {
  *sorted = true;
  size_t bad = triangles.size();
  if (!ForEachPolled(ticker, triangles.size(), [&](size_t t) {
        const Triangle& tri = triangles[t];
        if (!(0 <= tri[0] && tri[0] < tri[1] && tri[1] < tri[2] &&
              tri[2] < n)) {
          bad = t;
          return false;
        }
        if (t > 0 && tri < triangles[t - 1]) *sorted = false;
        return true;
      })) {
    if (bad == triangles.size()) return ticker.status();
    const Triangle& tri = triangles[bad];
    return MakeStatus(
        StatusCode::kInternal,
        "candidate triangle " + std::to_string(bad) + " (" +
            std::to_string(tri[0]) + ", " + std::to_string(tri[1]) + ", " +
            std::to_string(tri[2]) +
            ") is not three ascending positions below " + std::to_string(n));
  }
  return OkStatus();
}

// Sorts the candidates lexicographically: a least-significant-digit radix
// sort, one stable counting pass per corner, linear in triangles + n.
Status SortLexicographically(int32_t n, RunTicker& ticker,
                             std::vector<Triangle>* triangles) {
  std::vector<Triangle>& tris = *triangles;
  FlatVector<Triangle> other(tris.size());
  std::vector<int32_t> start(n + 1);
  auto pass = [&](int corner, const Triangle* from, Triangle* to) {
    std::fill(start.begin(), start.end(), 0);
    if (!ForEachPolled(ticker, tris.size(), [&](size_t t) {
          ++start[from[t][corner] + 1];
          return true;
        })) {
      return false;
    }
    for (int32_t v = 0; v < n; ++v) start[v + 1] += start[v];
    return ForEachPolled(ticker, tris.size(), [&](size_t t) {
      to[start[from[t][corner]]++] = from[t];
      return true;
    });
  };
  if (!pass(2, tris.data(), other.data()) ||
      !pass(1, other.data(), tris.data()) ||
      !pass(0, tris.data(), other.data())) {
    return ticker.status();
  }
  if (!ForEachPolled(ticker, tris.size(), [&](size_t t) {
        tris[t] = other[t];
        return true;
      })) {
    return ticker.status();
  }
  return OkStatus();
}

// One incidence of an edge [lo, hi] in a candidate: its far end (lo is the
// bucket it sits in) and 4 * triangle + slot (0: [a, b], 1: [b, c],
// 2: [a, c]).
struct Incidence {
  int32_t hi;
  uint32_t ref;
};

}  // namespace

int64_t Adjacency::Bytes() const {
  auto bytes = [](const auto& v) {
    return static_cast<int64_t>(TableFootprint(v.capacity() * sizeof(v[0])));
  };
  return bytes(edge_lo) + bytes(edge_hi) + bytes(inner_begin) + bytes(inner) +
         bytes(outer_begin) + bytes(outer) + bytes(tri_edges);
}

Status BuildAdjacency(int32_t n, std::vector<Triangle>* candidates,
                      const Control& control, Adjacency* out) {
  if (n > kMaxVertices) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "polygon has " + std::to_string(n) +
                          " vertices; the limit is " +
                          std::to_string(kMaxVertices));
  }
  std::vector<Triangle>& triangles = *candidates;
  if (triangles.size() >= (size_t{1} << 29)) {
    return MakeStatus(
        StatusCode::kResourceExhausted,
        "too many candidate triangles: " + std::to_string(triangles.size()));
  }
  RunTicker ticker(control, Stage::kAdjacency);
  bool sorted = false;
  Status s = CheckCandidates(n, triangles, ticker, &sorted);
  if (s.ok() && !sorted) s = SortLexicographically(n, ticker, &triangles);
  if (!s.ok()) return s;

  // Every incidence into the bucket of its edge's low end, in triangle
  // order: lexicographic order makes each edge's lists canonical below.
  const auto count = static_cast<uint32_t>(triangles.size());
  std::vector<int32_t> start(n + 1);
  if (!ForEachPolled(ticker, triangles.size(), [&](size_t i) {
        start[triangles[i][0] + 1] += 2;
        ++start[triangles[i][1] + 1];
        return true;
      })) {
    return ticker.status();
  }
  for (int32_t v = 0; v < n; ++v) start[v + 1] += start[v];
  FlatVector<Incidence> by_lo(3 * size_t{count});
  {
    std::vector<int32_t> next(start.begin(), start.end() - 1);
    if (!ForEachPolled(ticker, count, [&](size_t i) {
          const auto t = static_cast<uint32_t>(i);
          const Triangle& tri = triangles[t];
          by_lo[next[tri[0]]++] = {tri[1], 4 * t};
          by_lo[next[tri[1]]++] = {tri[2], 4 * t + 1};
          by_lo[next[tri[0]]++] = {tri[2], 4 * t + 2};
          return true;
        })) {
      return ticker.status();
    }
  }

  Adjacency& adj = *out;
  adj = Adjacency{};
  adj.n = n;
  adj.tri_edges.resize(3 * size_t{count});
  adj.inner.resize(count);
  adj.outer.resize(2 * size_t{count});
  // Euler's formula bounds a tetrahedralization's edges by
  // faces / 2 + 1.5 vertices; no space has more than n (n - 1) / 2.
  const size_t edges_guess =
      std::min(count / 2 + 2 * static_cast<size_t>(n),
               static_cast<size_t>(n) * static_cast<size_t>(n - 1) / 2);
  adj.edge_lo.reserve(edges_guess);
  adj.edge_hi.reserve(edges_guess);
  adj.inner_begin.reserve(edges_guess + 1);
  adj.outer_begin.reserve(edges_guess + 1);
  std::vector<bool> has_polygon_edge(n, false);
  // Per far end hi of the current bucket: its index among the bucket's
  // distinct ends (-1: none yet), then its edge's write cursors.
  std::vector<int32_t> end_index(n, -1);
  std::vector<int32_t> ends, inner_next, outer_next, edge_of_end;
  int32_t inner_size = 0, outer_size = 0;
  int64_t work = 0;  // since the last poll (RunTicker::Advance)
  // Buckets from the highest low end down, ends ascending within: every
  // edge [i, j] comes after its children [i, k] and [k, j], i < k < j.
  for (int32_t lo = n - 1; lo >= 0; --lo) {
    const Incidence* first = by_lo.data() + start[lo];
    const Incidence* last = by_lo.data() + start[lo + 1];
    ends.clear();
    // Counted per bucket, before its three passes: a poll is at most one
    // bucket late (a bucket holds a vertex's incidences: a few in a
    // Delaunay space, about n^2 / 2 in the space of all triangles, a few
    // ms at the n that space allows).
    if (!ticker.Advance(work, 3 * (last - first) + 1)) return ticker.status();
    for (const Incidence* r = first; r != last; ++r) {
      if (end_index[r->hi] < 0) {
        end_index[r->hi] = 0;
        ends.push_back(r->hi);
      }
    }
    std::sort(ends.begin(), ends.end());
    const size_t m = ends.size();
    inner_next.assign(m, 0);
    outer_next.assign(m, 0);
    edge_of_end.resize(m);
    for (size_t k = 0; k < m; ++k) end_index[ends[k]] = static_cast<int32_t>(k);
    for (const Incidence* r = first; r != last; ++r) {
      ++((r->ref & 3) == 2 ? inner_next : outer_next)[end_index[r->hi]];
    }
    for (size_t k = 0; k < m; ++k) {
      const int32_t hi = ends[k];
      const auto e = static_cast<int32_t>(adj.edge_lo.size());
      edge_of_end[k] = e;
      adj.edge_lo.push_back(lo);
      adj.edge_hi.push_back(hi);
      adj.inner_begin.push_back(inner_size);
      adj.outer_begin.push_back(outer_size);
      // The counts become the lists' write cursors.
      const int32_t inner_count = inner_next[k], outer_count = outer_next[k];
      inner_next[k] = inner_size;
      outer_next[k] = outer_size;
      inner_size += inner_count;
      outer_size += outer_count;
      if (hi - lo == 1) has_polygon_edge[lo] = true;
      if (lo == 0 && hi == n - 1) {
        adj.root = e;
        has_polygon_edge[n - 1] = true;
      }
    }
    // Stable: each list keeps triangle order, which is the order of the
    // triangles' third vertices (inner: b of (lo, b, hi); outer: a of
    // (a, lo, hi) before c of (lo, hi, c)).
    for (const Incidence* r = first; r != last; ++r) {
      const int32_t k = end_index[r->hi];
      const uint32_t t = r->ref >> 2, slot = r->ref & 3;
      adj.tri_edges[3 * t + slot] = edge_of_end[k];
      if (slot == 2) {
        adj.inner[inner_next[k]++] = static_cast<int32_t>(t);
      } else {
        adj.outer[outer_next[k]++] = static_cast<int32_t>(2 * t + slot);
      }
    }
    for (int32_t hi : ends) end_index[hi] = -1;
  }
  adj.inner_begin.push_back(inner_size);
  adj.outer_begin.push_back(outer_size);
  for (int32_t i = 0; i < n; ++i) {
    if (!has_polygon_edge[i]) adj.missing_polygon_edges.push_back(i);
  }
  return OkStatus();
}

int64_t EstimateTableBytes(int64_t triangles, bool bi_triangle) {
  // Per candidate: the triangle, its weight, three edge ids, the transient
  // sort copy and incidence records (12 + 3 x 8 bytes; 48 counted),
  // adjacency lists; per edge (at most 1.5 per triangle in practice, 3 at
  // worst) offsets, ends and DP entries.
  int64_t per_triangle = 12 + 8 + 12 + 48 + 12 + 3 * (4 * 4 + 12);
  if (bi_triangle) per_triangle += 24 + 2 * (8 + 4) + 36;
  return triangles * per_triangle;
}

}  // namespace dot

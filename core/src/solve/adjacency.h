// SPDX-License-Identifier: AGPL-3.0-or-later
// Flat edge-triangle adjacency (the paper's table Pi) over polygon positions.
//
// Vertices are polygon positions 0..n-1. Fixing the polygon edge (n-1, 0) as
// the root, every sub-polygon the dynamic programs visit is a chain i..j
// (i < j) closed by the edge [i, j], so each candidate edge needs only one
// side: its "inner" triangles (i, k, j) with i < k < j. A triangle (a, b, c),
// a < b < c, is inner to its long edge [a, c] and "outer" to its two short
// edges [a, b] (slot 0) and [b, c] (slot 1). Edges are numbered by
// decreasing low end, then increasing high end, so every edge [i, j] comes
// after its children [i, k] and [k, j]: one forward pass solves children
// before parents, and the root [0, n-1] is the last edge.
//
// Each edge's lists are in a canonical order, by the triangles' third
// vertex, so the dynamic programs (and their tie-breaking) depend only on
// the candidate set, not on the order a Delaunay backend listed it in.
#ifndef DOT_CORE_SOLVE_ADJACENCY_H_
#define DOT_CORE_SOLVE_ADJACENCY_H_

#include <cstdint>
#include <vector>

#include "dot/control.h"
#include "dot/geometry.h"
#include "dot/problem.h"
#include "dot/status.h"
#include "util/flat_vector.h"

namespace dot {

// The largest polygon the adjacency (and so every solver) accepts. It was
// the reach of 24-bit positions in packed sort keys; the records that
// replaced them need no such bound, but the limit is kept as the library's
// stated maximum (the default memory budget refuses polygons far smaller).
inline constexpr int32_t kMaxVertices = (1 << 24) - 1;

struct Adjacency {
  int32_t n = 0;
  Table<int32_t> edge_lo, edge_hi;  // per edge, lo < hi
  Table<int32_t> inner_begin;       // CSR offsets into inner, E + 1
  Table<int32_t> inner;             // triangle ids with long edge e
  Table<int32_t> outer_begin;       // CSR offsets into outer, E + 1
  Table<int32_t> outer;             // slots 2 * t + s with short edge e
  FlatVector<int32_t> tri_edges;    // per triangle: [a,b], [b,c], [a,c]
  int32_t root = -1;                // edge [0, n-1]
  std::vector<int32_t> missing_polygon_edges;  // i: edge (i, i+1 mod n) absent

  int32_t edge_count() const { return static_cast<int32_t>(edge_lo.size()); }
  bool IsPolygonEdge(int32_t e) const { return edge_hi[e] - edge_lo[e] == 1; }
  int64_t Bytes() const;
};

// Sorts `candidates` (position triples, ascending within each) into
// lexicographic order in place (a radix sort) and builds their adjacency:
// the triangle ids of `out` index the sorted list, so per-triangle weights
// and normals are computed after. The incidences are bucketed by their
// edge's low end, each bucket grouped by high end; no record is looked up
// and no list sorted: lexicographic order is what makes each list
// canonical. kResourceExhausted above kMaxVertices or 2^29 triangles;
// kInternal for a triple that is not three ascending positions below n.
// On any error (also a cancel) `*candidates` and `*out` are unspecified.
Status BuildAdjacency(int32_t n, std::vector<Triangle>* candidates,
                      const Control& control, Adjacency* out);

}  // namespace dot

#endif  // DOT_CORE_SOLVE_ADJACENCY_H_

// SPDX-License-Identifier: AGPL-3.0-or-later
// The two dynamic programs over an Adjacency (paper, section 3), written as
// single forward passes over edges by increasing span: no recursion, tables
// in flat arrays.
//  - Dot1: per-triangle weights only. One state per edge.
//  - Dot2: per-triangle weights plus bending-angle terms between adjacent
//    triangles. One state per (short edge, outer triangle) slot.
// The same code runs GK1/GK2 when the adjacency holds every triangle.
#ifndef DOT_CORE_SOLVE_SOLVERS_H_
#define DOT_CORE_SOLVE_SOLVERS_H_

#include <cstdint>
#include <limits>
#include <vector>

#include "dot/control.h"
#include "dot/metrics.h"
#include "dot/problem.h"
#include "dot/status.h"
#include "solve/adjacency.h"
#include "util/flat_vector.h"

namespace dot {

// The cost of a sub-polygon no candidate triangulates.
inline constexpr double kInf = std::numeric_limits<double>::infinity();

struct DpSolution {
  double cost = 0;
  std::vector<int32_t> triangles;  // candidate triangle ids
  int64_t states = 0;
  int64_t table_bytes = 0;
  double dp_ms = 0, tiling_ms = 0;
};

// The weighted cost of each candidate triangle, by candidate id: a table
// (huge pages when large; filled by the caller, element by element).
using CandidateWeights = FlatVector<double>;

// kNoTriangulation when no triangulation exists in the candidate set.
Status SolveDot1(const Adjacency& adj, const CandidateWeights& weight,
                 const Control& control, DpSolution* out);

struct BendingWeights {
  double dihedral = 0;          // weight of theta
  double squared_dihedral = 0;  // weight of theta^2
};
// Smallest value of dihedral * theta + squared_dihedral * theta^2 over theta
// in [0, pi]: a lower bound on any bending term, for pruning.
double MinBending(BendingWeights w);
// The candidates' unit normals: kept (a space prepared for re-solves keeps
// them), or computed from the points whenever one is needed (three times
// per candidate; a solve that keeps nothing saves 24 bytes per candidate,
// a quarter of DOT2's peak memory). The same values either way.
class CandidateNormals {
 public:
  explicit CandidateNormals(const std::vector<Vec3>& kept) : kept_(&kept) {}
  CandidateNormals(const std::vector<Vec3>& points,
                   const std::vector<Triangle>& triangles)
      : points_(&points), triangles_(&triangles) {}
  // It keeps pointers: no temporaries.
  explicit CandidateNormals(std::vector<Vec3>&&) = delete;
  CandidateNormals(std::vector<Vec3>&&, const std::vector<Triangle>&) = delete;
  CandidateNormals(const std::vector<Vec3>&, std::vector<Triangle>&&) = delete;
  Vec3 operator[](int32_t t) const {
    return kept_ != nullptr ? (*kept_)[t]
                            : UnitNormal(*points_, (*triangles_)[t]);
  }

 private:
  const std::vector<Vec3>* kept_ = nullptr;
  const std::vector<Vec3>* points_ = nullptr;
  const std::vector<Triangle>* triangles_ = nullptr;
};

// `edge_normals`: empty, or per polygon position i the unit normal of the
// surface face across the polygon edge i -> i+1 (zero: none); the bending
// between it and the patch triangle on that edge is priced too.
Status SolveDot2(const Adjacency& adj, const CandidateWeights& weight,
                 const CandidateNormals& unit_normals,
                 const std::vector<Vec3>& edge_normals, BendingWeights bending,
                 const Control& control, DpSolution* out);

}  // namespace dot

#endif  // DOT_CORE_SOLVE_SOLVERS_H_

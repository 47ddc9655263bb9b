// SPDX-License-Identifier: AGPL-3.0-or-later
// Ears of one loop of a surface with several boundaries: for every directed
// chord from -> to of the loop, the optimal triangulation of the chain from,
// next(from), ..., to closed by the chord, over the candidate triangles whose
// three corners are on that loop. Unlike the single-loop Adjacency (rooted at
// the edge n-1 -> 0), a chain may pass the loop's end: in a surface with
// several boundaries an ear can hang on either side of a chord.
//
// DOT1 keeps one value per chord. With bending weights (DOT2) the value also
// depends on the triangle across the chord: each chord keeps its inner
// candidates sorted by their own cost, and Cost() scans them with the
// least bending as a bound, as SolveDot2 does.
#ifndef DOT_CORE_SOLVE_LOOP_EARS_H_
#define DOT_CORE_SOLVE_LOOP_EARS_H_

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "dot/control.h"
#include "dot/geometry.h"
#include "dot/status.h"
#include "solve/surface_costs.h"

namespace dot {

class LoopEars {
 public:
  // `loop`: the loop's positions in the direction it runs along the surface;
  // `triangles`: candidates with all three corners on it (any corner order).
  // Triangles are oriented along the loop (chain order).
  Status Build(const std::vector<int32_t>& loop,
               const std::vector<Triangle>& triangles,
               const SurfaceCosts& costs, const Control& control);

  // The ear on chord from -> to (positions on the loop) given the unit normal
  // of the triangle across the chord (ignored by DOT1). A loop edge (`to`
  // follows `from`) costs its bending against the surrounding face. kInf
  // when the chain has no triangulation or would span the whole loop.
  double Cost(int32_t from, int32_t to, const Vec3& outer) const;
  // Appends that ear's triangles (positions, oriented).
  void Collect(int32_t from, int32_t to, const Vec3& outer,
               std::vector<Triangle>* out) const;
  // Chain length of from -> to in loop steps.
  int32_t Span(int32_t from, int32_t to) const;
  int64_t Bytes() const;

 private:
  struct Chord {
    int32_t from, to;  // local indices
    int32_t span;
    double best;                     // DOT1
    int32_t apex;                    // DOT1: chosen apex, -1 none
    int32_t inner_begin, inner_end;  // into inner_apex_
    int32_t cand_begin, cand_end;    // DOT2: into cands_
  };
  struct Candidate {  // DOT2: an inner triangle and its cost below
    double b;
    int32_t apex;
    Vec3 normal;
  };
  int32_t Find(int32_t from, int32_t to) const;  // chord id or -1
  // Best inner candidate of chord c against `outer`: its apex, or -1.
  int32_t BestApex(const Chord& c, const Vec3& outer, double* cost) const;
  Triangle Oriented(int32_t from, int32_t apex, int32_t to) const {
    return {loop_[from], loop_[apex], loop_[to]};
  }

  const SurfaceCosts* costs_ = nullptr;
  double min_bend_ = 0;
  std::vector<int32_t> loop_;                   // local -> position
  std::unordered_map<int32_t, int32_t> local_;  // position -> local
  std::unordered_map<int64_t, int32_t> chord_id_;
  std::vector<Chord> chords_;
  std::vector<int32_t> inner_apex_;
  std::vector<Candidate> cands_;
};

}  // namespace dot

#endif  // DOT_CORE_SOLVE_LOOP_EARS_H_

// SPDX-License-Identifier: AGPL-3.0-or-later
// A rotation system over a network's curves (the order of the curves around
// each junction) and the faces it traces: leaving each junction by the next
// curve clockwise from the one arrived by keeps the face on the left. A
// junction's normal taken the other way round reverses its ring; the
// searches here flip rings while the faces get better.
#ifndef DOT_NETWORK_ROTATION_H_
#define DOT_NETWORK_ROTATION_H_

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "dot/network.h"
#include "dot/status.h"
#include "util/run_control.h"

namespace dot {

// Darts are 2 curve + end (0: leaves from the curve's first vertex).
struct Rotation {
  int32_t Next(int32_t leave) const { return before[leave ^ 1]; }
  // `before` from ring r's order.
  void SetRing(int32_t r);
  // The junction's normal the other way round: its ring reversed.
  void Flip(int32_t r);

  std::vector<int32_t> before;              // per dart: the one before it
  std::vector<std::vector<int32_t>> rings;  // per junction, counter-clockwise
  std::vector<signed char> sign;  // per ring, when kept: -1 once flipped
};

// The faces counted: how many run no curve twice, how many run only a seam
// one way and back (which SurfaceNetwork surfaces too), and all.
struct FaceCount {
  int simple = 0, seams = 0, faces = 0;
  void Add(const std::vector<CurveUse>& face);
};

// First more simple faces, then more faces (a lower genus): a wrong sign
// merges faces. Counting seams here too would trade true faces for merged
// ones (measured on a genus-3 network).
bool MoreSimple(const FaceCount& a, const FaceCount& b);
// Then, from there, faces made surfaceable, none lost (three rims and two
// seams: two tubes rather than a disk inside and one face with both).
bool MoreSurfaceable(const FaceCount& a, const FaceCount& b);

FaceCount AllFaces(const Rotation& rot);

// The faces through the darts arriving at `rings`, each once: every face a
// flip of those rings changes. False when the ticker says stop.
bool FacesThrough(const Rotation& rot, const std::vector<int32_t>& rings,
                  std::vector<std::vector<CurveUse>>* faces, RunTicker* ticker);

// Splits a face at junctions it passes more than once into simple loops.
std::vector<std::vector<CurveUse>> SplitAtRepeats(
    const NetworkGraph& g, const std::vector<CurveUse>& face);

// The normals' signs are a guess where the network bends: a wrong sign at
// one junction merges the faces around it (an embedding of higher genus),
// and a wrong link of the spanning tree flips a whole subtree. So flip
// single junctions (and swap neighbours where four or more curves meet),
// then subtrees (`order`: ring indices in the spanning forest's preorder;
// `subtrees`: each non-root junction's range of it), while `better` says
// the faces they change are better.
Status ImproveSigns(Rotation* rot, const std::vector<int32_t>& order,
                    const std::vector<std::pair<size_t, size_t>>& subtrees,
                    bool (*better)(const FaceCount&, const FaceCount&),
                    RunTicker* ticker);

}  // namespace dot

#endif  // DOT_NETWORK_ROTATION_H_

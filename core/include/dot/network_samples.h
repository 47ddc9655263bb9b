// SPDX-License-Identifier: AGPL-3.0-or-later
// Test and benchmark data for SurfaceNetwork: curve networks with known
// surfaces. Hand-made ones (a cube's edges, a cylinder's rims), the edges of
// a polygon mesh, and the rims of disk-shaped patches cut from a closed
// mesh (the surface they came from is the reference).
#ifndef DOT_NETWORK_SAMPLES_H_
#define DOT_NETWORK_SAMPLES_H_

#include <cstdint>
#include <vector>

#include "dot/mesh.h"
#include "dot/network.h"
#include "dot/status.h"

namespace dot {

// The 12 edges of the unit cube [0,1]^3, each split into `segments` (>= 1)
// equal pieces: 8 junctions of three curves, 6 square cycles.
CurveNetwork CubeNetwork(int segments);

// Two circular rims of `n` (>= 3) points, radius 1, at heights 0 and 2,
// and, when `seam`, a straight seam of `n / 4` pieces (at least 1) joining
// them at angle 0.
CurveNetwork CylinderNetwork(int n, bool seam);

// CubeNetwork(segments) and a circle of `n` (>= 3) points, radius 0.3,
// centred on the top face (z = 1): a lone loop in a face, the face's island
// (SurfaceOptions::islands).
CurveNetwork LidNetwork(int segments, int n);

// The edges of two unit cubes side by side, [0,2] x [0,1] x [0,1], each
// split into `segments` (>= 1) pieces: the square at x = 1 is a partition
// (SurfaceOptions::walls) or, without walls, a belt around one box.
CurveNetwork PartitionNetwork(int segments);

// The edges of a polygon mesh's faces as curves, each split into
// `segments` (>= 1) equal pieces (the faces of CGAL's 3torus.off give a
// network of genus 3).
CurveNetwork FaceEdgeNetwork(const PolygonSoup& soup, int segments);

// A closed mesh cut into disk-shaped patches: `patches` seeds far apart
// (farthest-point sampling from a face `seed` picks, distances along the
// faces), each face given to its nearest seed, rims smoothed; while a patch
// is not a disk with a simple rim (it wraps a limb or a handle), one more
// seed at its farthest face (CutNetwork::patches says how many in all; at
// most 2 patches + 16). The network is the patch rims, with only the
// junctions and every `keep_every`-th (>= 1) other rim vertex (at least one
// inside each curve). `face_patch` gives each mesh face its patch, and
// `rims` each patch its rim: the network's vertex ids on it, sorted (the
// answer a cycle search should find).
struct CutNetwork {
  CurveNetwork network;
  std::vector<int32_t> face_patch;
  int32_t patches = 0;
  std::vector<std::vector<int32_t>> rims;
};
Status CutIntoPatches(const MeshData& mesh, int patches, int keep_every,
                      uint64_t seed, CutNetwork* out);

// How many of the cut's patches have their rim among `cycles` (each a
// cycle's vertex ids, its loops together, in any order).
int32_t CountRimsFound(const CutNetwork& cut,
                       const std::vector<std::vector<int32_t>>& cycles);

}  // namespace dot

#endif  // DOT_NETWORK_SAMPLES_H_

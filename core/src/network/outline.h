// SPDX-License-Identifier: AGPL-3.0-or-later
#ifndef DOT_CORE_NETWORK_OUTLINE_H_
#define DOT_CORE_NETWORK_OUTLINE_H_

#include <vector>

#include "dot/network.h"

namespace dot {

// A loop of network vertices seen along its normal (the Newell normal of
// its vector area): whether other points lie in the face it bounds, by a
// projection on its plane. Islands and walls use it.
struct Outline {
  std::vector<int32_t> vertices;
  Vec3 vector_area;  // half the sum of p_i x p_i+1
  Vec3 centre, normal, u, v;
  double area = 0;           // |vector_area|; 0: degenerate, nothing inside
  double radius = 0;         // sqrt(area / pi)
  double off_plane = 0;      // the loop's farthest vertex from its plane
  double reach = 0;          // how far from the plane a point may lie inside
  Vec3 lo, hi;               // bounding box, grown by reach
  std::vector<double> x, y;  // the loop in the plane's (u, v) coordinates
  // Long loops: edge k (x[k], y[k]) -> (x[k+1], y[k+1]) listed in every band
  // of v its span meets, so that a point or a short segment meets a few
  // edges, not all (1,500 circles in a face of 20,000 points).
  double band_v0 = 0, band_height = 0;
  std::vector<std::vector<int32_t>> bands;
};

// `reach_fraction`: a point lies in the face up to off_plane plus this
// fraction of the radius from its plane.
Outline MakeOutline(const NetworkGraph& g, std::vector<int32_t> vertices,
                    double reach_fraction);

// Whether p lies in the face: within reach of the plane and inside the
// loop seen along the normal (winding number).
bool Inside(const Outline& o, const Vec3& p);

// Whether the segment p q, seen along the normal, crosses the loop (an
// edge of it between the segment's sides, the segment between its ends).
bool CrossesOutline(const Outline& o, const Vec3& p, const Vec3& q);

}  // namespace dot

#endif  // DOT_CORE_NETWORK_OUTLINE_H_

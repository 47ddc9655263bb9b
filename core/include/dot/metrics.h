// SPDX-License-Identifier: AGPL-3.0-or-later
// The metrics a triangulation can minimize, and their exact definitions.
//
// Per-triangle metrics of a triangle t = (a, b, c), oriented by index order,
// with unit normal n_t = normalize((b - a) x (c - a)):
//   kArea             area of t.
//   kPerimeter        |ab| + |bc| + |ca|.
//   kNormalDeviation  sum over the three vertices v of t of the angle in
//                     radians, in [0, pi], between n_t and the prescribed
//                     boundary normal N_v (normalized). Triangles of a
//                     triangulation are oriented so that the polygon runs
//                     counter-clockwise around n_t (right-hand rule), so N_v
//                     must point to that side.
//   kShape            1 - 4*sqrt(3)*area / (|ab|^2 + |bc|^2 + |ca|^2), in
//                     [0, 1]: 0 for an equilateral triangle, 1 for a
//                     degenerate one (a bounded aspect-ratio measure).
// Bi-triangle metrics of two triangles sharing an edge, consistently
// oriented (the shared edge runs in opposite directions in the two):
//   kDihedral         the bending angle theta in [0, pi] between their unit
//                     normals (0 when they are coplanar and unfolded).
//   kSquaredDihedral  theta^2.
#ifndef DOT_METRICS_H_
#define DOT_METRICS_H_

#include <array>
#include <string_view>
#include <vector>

#include "dot/geometry.h"

namespace dot {

enum class Metric : int {
  kArea = 0,
  kPerimeter,
  kNormalDeviation,
  kShape,
  kDihedral,
  kSquaredDihedral,
};
inline constexpr int kMetricCount = 6;
inline constexpr std::array<Metric, kMetricCount> kAllMetrics = {
    Metric::kArea,  Metric::kPerimeter, Metric::kNormalDeviation,
    Metric::kShape, Metric::kDihedral,  Metric::kSquaredDihedral};

// Stable lower-case names ("area", "perimeter", "normal_deviation", "shape",
// "dihedral", "squared_dihedral"), used by the CLI, logs and reports.
std::string_view MetricName(Metric m);

// A value per metric: weights of a metric spec, or per-metric costs.
struct MetricValues {
  std::array<double, kMetricCount> v{};
  double& operator[](Metric m) { return v[static_cast<int>(m)]; }
  double operator[](Metric m) const { return v[static_cast<int>(m)]; }
};
using MetricWeights = MetricValues;

bool HasBiTriangleWeight(const MetricWeights& w);
bool HasNonZeroWeight(const MetricWeights& w);

// Values of the per-triangle metrics of one triangle (normals may be empty
// when the normal-deviation metric is not needed; it is then 0).
MetricValues PerTriangleMetrics(const std::vector<Vec3>& vertices,
                                const std::vector<Vec3>& normals,
                                const Triangle& t);
// Bending angle between two unit normals, in [0, pi].
double BendingAngle(const Vec3& n1, const Vec3& n2);
Vec3 UnitNormal(const std::vector<Vec3>& vertices, const Triangle& t);

// Unweighted sum of every metric over a triangle set (bi-triangle metrics
// over each edge shared by exactly two triangles), computed directly from the
// triangles: the reference the solvers are checked against. With
// `edge_face_normals` (per vertex id v: the normal of the surface face
// across the boundary edge that leaves v, as Problem::edge_face_normals;
// zero: none), each boundary edge also adds the bending between that face
// and the triangle on the edge.
MetricValues EvaluateMetrics(const std::vector<Vec3>& vertices,
                             const std::vector<Vec3>& normals,
                             const std::vector<Triangle>& triangles,
                             const std::vector<Vec3>& edge_face_normals = {});
double WeightedTotal(const MetricWeights& w, const MetricValues& costs);
// WeightedTotal(w, PerTriangleMetrics(vertices, normals, t)), bit for bit,
// evaluating only the metrics `w` weighs: the solvers' per-candidate cost.
double WeightedTriangleCost(const MetricWeights& w,
                            const std::vector<Vec3>& vertices,
                            const std::vector<Vec3>& normals,
                            const Triangle& t);

}  // namespace dot

#endif  // DOT_METRICS_H_

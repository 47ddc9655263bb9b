// SPDX-License-Identifier: AGPL-3.0-or-later
#include "dot/metrics.h"

#include <algorithm>
#include <cmath>

#include "mesh/edge_index.h"

namespace dot {

bool HasBiTriangleWeight(const MetricWeights& w) {
  return w[Metric::kDihedral] != 0 || w[Metric::kSquaredDihedral] != 0;
}

bool HasNonZeroWeight(const MetricWeights& w) {
  return std::any_of(w.v.begin(), w.v.end(), [](double x) { return x != 0; });
}

Vec3 UnitNormal(const std::vector<Vec3>& vertices, const Triangle& t) {
  const Vec3& a = vertices[t[0]];
  return Normalized(Cross(vertices[t[1]] - a, vertices[t[2]] - a));
}

double BendingAngle(const Vec3& n1, const Vec3& n2) {
  return std::acos(std::clamp(Dot(n1, n2), -1.0, 1.0));
}

namespace {

// The per-triangle metrics; perimeter and shape (three square roots) only
// when `lengths`, normal deviation only with normals.
MetricValues TriangleMetrics(const std::vector<Vec3>& vertices,
                             const std::vector<Vec3>& normals,
                             const Triangle& t, bool lengths) {
  const Vec3& a = vertices[t[0]];
  const Vec3& b = vertices[t[1]];
  const Vec3& c = vertices[t[2]];
  const Vec3 cross = Cross(b - a, c - a);
  const double twice_area = Norm(cross);
  MetricValues m;
  m[Metric::kArea] = 0.5 * twice_area;
  if (lengths) {
    const double ab = Distance(a, b), bc = Distance(b, c), ca = Distance(c, a);
    m[Metric::kPerimeter] = ab + bc + ca;
    const double sq = ab * ab + bc * bc + ca * ca;
    m[Metric::kShape] =
        sq > 0 ? std::max(0.0, 1.0 - 2.0 * std::sqrt(3.0) * twice_area / sq)
               : 1.0;
  }
  if (!normals.empty()) {
    const Vec3 n = twice_area > 0 ? (1.0 / twice_area) * cross : Vec3{};
    double dev = 0;
    for (int32_t v : t) dev += BendingAngle(n, Normalized(normals[v]));
    m[Metric::kNormalDeviation] = dev;
  }
  return m;
}

}  // namespace

MetricValues PerTriangleMetrics(const std::vector<Vec3>& vertices,
                                const std::vector<Vec3>& normals,
                                const Triangle& t) {
  return TriangleMetrics(vertices, normals, t, /*lengths=*/true);
}

double WeightedTriangleCost(const MetricWeights& w,
                            const std::vector<Vec3>& vertices,
                            const std::vector<Vec3>& normals,
                            const Triangle& t) {
  static const std::vector<Vec3> kNoNormals;
  const bool lengths = w[Metric::kPerimeter] != 0 || w[Metric::kShape] != 0;
  return WeightedTotal(
      w, TriangleMetrics(
             vertices, w[Metric::kNormalDeviation] != 0 ? normals : kNoNormals,
             t, lengths));
}

MetricValues EvaluateMetrics(const std::vector<Vec3>& vertices,
                             const std::vector<Vec3>& normals,
                             const std::vector<Triangle>& triangles,
                             const std::vector<Vec3>& edge_face_normals) {
  MetricValues sum;
  std::vector<Vec3> unit(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    const MetricValues m = PerTriangleMetrics(vertices, normals, triangles[i]);
    for (Metric k : kAllMetrics) sum[k] += m[k];
    unit[i] = UnitNormal(vertices, triangles[i]);
  }
  auto add_bend = [&](const Vec3& a, const Vec3& b) {
    const double theta = BendingAngle(a, b);
    sum[Metric::kDihedral] += theta;
    sum[Metric::kSquaredDihedral] += theta * theta;
  };
  ForEachEdge(BuildEdgeIndex(triangles), [&](const EdgeUses& edge) {
    // Only manifold edges (exactly two triangles) have a dihedral angle; a
    // boundary edge has one against the surface face across it, if given.
    if (edge.size() == 2) {
      add_bend(unit[edge[0].triangle], unit[edge[1].triangle]);
    } else if (edge.size() == 1 && !edge_face_normals.empty()) {
      const Vec3& face = edge_face_normals[edge[0].from()];
      if (Norm(face) > 0) add_bend(face, unit[edge[0].triangle]);
    }
  });
  return sum;
}

double WeightedTotal(const MetricWeights& w, const MetricValues& costs) {
  double total = 0;
  for (Metric m : kAllMetrics) {
    if (w[m] != 0) total += w[m] * costs[m];
  }
  return total;
}

std::string_view MetricName(Metric m) {
  switch (m) {
    case Metric::kArea:
      return "area";
    case Metric::kPerimeter:
      return "perimeter";
    case Metric::kNormalDeviation:
      return "normal_deviation";
    case Metric::kShape:
      return "shape";
    case Metric::kDihedral:
      return "dihedral";
    case Metric::kSquaredDihedral:
      return "squared_dihedral";
  }
  return "?";
}

}  // namespace dot

// SPDX-License-Identifier: AGPL-3.0-or-later
#include "polygon/plane_fit.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace dot {
namespace {

using Mat3 = double[3][3];

// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations:
// columns of `vec` are eigenvectors of `a` (destroyed), `val` eigenvalues.
void SymmetricEigen(Mat3 a, double val[3], Mat3 vec) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) vec[i][j] = i == j;
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off =
        a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diag =
        a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (off <= 1e-30 * diag || off == 0) break;
    for (int p = 0; p < 2; ++p) {
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const double t = (theta >= 0 ? 1.0 : -1.0) /
                         (std::fabs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {  // A <- A J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // A <- J^T A
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {  // V <- V J
          const double vkp = vec[k][p], vkq = vec[k][q];
          vec[k][p] = c * vkp - s * vkq;
          vec[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  for (int i = 0; i < 3; ++i) val[i] = a[i][i];
}

}  // namespace

PlaneFit FitPlane(const std::vector<Vec3>& points) {
  PlaneFit fit;
  if (points.empty()) return fit;
  Vec3 lo = points[0], hi = points[0], sum;
  for (const Vec3& p : points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    sum = sum + p;
  }
  fit.diagonal = Distance(lo, hi);
  fit.centroid = (1.0 / points.size()) * sum;
  Mat3 cov = {};
  for (const Vec3& p : points) {
    const Vec3 d = p - fit.centroid;
    const double v[3] = {d.x, d.y, d.z};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) cov[i][j] += v[i] * v[j];
  }
  double val[3];
  Mat3 vec;
  SymmetricEigen(cov, val, vec);
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int i, int j) { return val[i] > val[j]; });
  auto column = [&](int k) {
    return Vec3{vec[0][order[k]], vec[1][order[k]], vec[2][order[k]]};
  };
  fit.direction = Normalized(column(0));
  fit.normal = Normalized(column(2));
  const double n[3] = {std::fabs(fit.normal.x), std::fabs(fit.normal.y),
                       std::fabs(fit.normal.z)};
  fit.dominant_axis = static_cast<int>(std::max_element(n, n + 3) - n);
  for (const Vec3& p : points) {
    const Vec3 d = p - fit.centroid;
    fit.max_plane_distance =
        std::max(fit.max_plane_distance, std::fabs(Dot(d, fit.normal)));
    fit.max_line_distance =
        std::max(fit.max_line_distance, Norm(Cross(d, fit.direction)));
  }
  return fit;
}

}  // namespace dot

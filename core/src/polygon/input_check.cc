// SPDX-License-Identifier: AGPL-3.0-or-later
#include "polygon/input_check.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <tuple>
#include <vector>

namespace dot {

std::string FormatVec(const Vec3& v) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

Status CheckProblem(const Problem& problem, const Options& options) {
  const auto& v = problem.vertices;
  const int n = static_cast<int>(v.size());
  if (n < 3) {
    return InvalidArgument("polygon has " + std::to_string(n) +
                           (n == 1 ? " vertex" : " vertices") +
                           "; at least 3 are needed");
  }
  // The next vertex along each loop.
  std::vector<int> next(n);
  if (!problem.loop_sizes.empty()) {
    int64_t sum = 0;
    for (size_t l = 0; l < problem.loop_sizes.size(); ++l) {
      const int32_t size = problem.loop_sizes[l];
      if (size < 3) {
        return InvalidArgument(
            "loop " + std::to_string(l) + " has " + std::to_string(size) +
            (size == 1 ? " vertex" : " vertices") + "; at least 3 are needed");
      }
      sum += size;
    }
    if (sum != n) {
      return InvalidArgument("the loop sizes sum to " + std::to_string(sum) +
                             ", but there are " + std::to_string(n) +
                             " vertices");
    }
  }
  for (int begin = 0, l = 0; begin < n; ++l) {
    const int size = problem.loop_sizes.empty() ? n : problem.loop_sizes[l];
    for (int i = 0; i < size; ++i) next[begin + i] = begin + (i + 1) % size;
    begin += size;
  }
  for (int i = 0; i < n; ++i) {
    if (!IsFinite(v[i])) {
      return InvalidArgument("vertex " + std::to_string(i) +
                             " has a non-finite coordinate " + FormatVec(v[i]));
    }
  }
  for (Metric m : kAllMetrics) {
    if (!std::isfinite(problem.weights[m])) {
      return InvalidArgument("weight of metric " + std::string(MetricName(m)) +
                             " is not finite");
    }
  }
  if (!problem.normals.empty()) {
    if (problem.normals.size() != v.size()) {
      return InvalidArgument(std::to_string(problem.normals.size()) +
                             " boundary normals given for " +
                             std::to_string(n) +
                             " vertices; give one per vertex or none");
    }
    for (int i = 0; i < n; ++i) {
      const Vec3& nv = problem.normals[i];
      if (!IsFinite(nv) || Norm(nv) == 0) {
        return InvalidArgument("boundary normal " + std::to_string(i) + " " +
                               FormatVec(nv) + " is zero or not finite");
      }
    }
  } else if (problem.weights[Metric::kNormalDeviation] != 0) {
    return InvalidArgument(
        "metric normal_deviation has a weight but no boundary normals were "
        "given");
  }
  if (!problem.edge_face_normals.empty()) {
    if (problem.edge_face_normals.size() != v.size()) {
      return InvalidArgument(std::to_string(problem.edge_face_normals.size()) +
                             " edge face normals given for " +
                             std::to_string(n) +
                             " vertices; give one per polygon edge or none");
    }
    for (int i = 0; i < n; ++i) {
      if (!IsFinite(problem.edge_face_normals[i])) {
        return InvalidArgument("edge face normal " + std::to_string(i) + " " +
                               FormatVec(problem.edge_face_normals[i]) +
                               " is not finite");
      }
    }
  }
  for (const auto& [a, b] : problem.forbidden_edges) {
    const std::string name =
        "forbidden edge " + std::to_string(a) + "-" + std::to_string(b);
    if (a < 0 || b < 0 || a >= n || b >= n || a == b) {
      return InvalidArgument(name +
                             " does not join two distinct vertices of "
                             "the polygon");
    }
    if (next[a] == b || next[b] == a) {
      return InvalidArgument(name +
                             " is a polygon edge; every polygon edge "
                             "is part of the result");
    }
  }
  for (int i = 0; i < n; ++i) {
    const int j = next[i];
    if (v[i] == v[j]) {
      return InvalidArgument("vertices " + std::to_string(i) + " and " +
                             std::to_string(j) +
                             " are consecutive duplicates " + FormatVec(v[i]));
    }
  }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](int i) { return std::tie(v[i].x, v[i].y, v[i].z); };
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return key(a) < key(b) || (key(a) == key(b) && a < b);
  });
  for (int k = 0; k + 1 < n; ++k) {
    if (v[order[k]] == v[order[k + 1]]) {
      return InvalidArgument("vertex " + std::to_string(order[k + 1]) +
                             " repeats vertex " + std::to_string(order[k]) +
                             " " + FormatVec(v[order[k]]));
    }
  }
  if (options.delaunay == DelaunayBackend::kTetgen && !TetgenAvailable()) {
    return InvalidArgument(kNoTetgenMessage);
  }
  if (options.delaunay_threads < 0) {
    return InvalidArgument("delaunay_threads must be >= 0 (0: all cores)");
  }
  if (options.parallel_delaunay_min_points < 0) {
    return InvalidArgument("parallel_delaunay_min_points must be >= 0");
  }
  if (options.planar_tolerance < 0 ||
      !std::isfinite(options.planar_tolerance)) {
    return InvalidArgument("planar tolerance must be a finite number >= 0");
  }
  return OkStatus();
}

Status CheckNotCollinear(const PlaneFit& fit, int n, const Options& options) {
  if (fit.max_line_distance <= options.planar_tolerance * fit.diagonal) {
    std::ostringstream s;
    s << "all " << n << " vertices are collinear (every vertex is within "
      << fit.max_line_distance << " of the line through "
      << FormatVec(fit.centroid) << ")";
    return InvalidArgument(s.str());
  }
  return OkStatus();
}

}  // namespace dot

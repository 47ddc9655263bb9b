// SPDX-License-Identifier: AGPL-3.0-or-later
#include "network/face_cost.h"

#include <algorithm>

#include "dot/triangulate.h"
#include "network/seam.h"

namespace dot {
namespace {

// The face as darts (2 curve + reversed), rotated to start at its least
// dart: the same key whichever dart a trace starts from.
std::vector<int32_t> Canonical(std::vector<int32_t> darts) {
  std::rotate(darts.begin(), std::min_element(darts.begin(), darts.end()),
              darts.end());
  return darts;
}

std::vector<int32_t> Key(const std::vector<CurveUse>& face) {
  std::vector<int32_t> forward, backward;
  for (const CurveUse& u : face) forward.push_back(2 * u.curve + u.reversed);
  for (auto it = face.rbegin(); it != face.rend(); ++it) {
    backward.push_back(2 * it->curve + !it->reversed);
  }
  return std::min(Canonical(forward), Canonical(backward));
}

}  // namespace

std::vector<Vec3> PricedPoints(const NetworkGraph& graph,
                               const std::vector<CurveUse>& face) {
  size_t points = 0;
  for (const CurveUse& u : face) {
    points += graph.curves[u.curve].vertices.size() - 1;
  }
  const double keep =
      std::min(1.0, static_cast<double>(FaceCosts::kMaxPoints) /
                        static_cast<double>(std::max<size_t>(points, 1)));
  std::vector<Vec3> out;
  for (const CurveUse& u : face) {
    std::vector<int32_t> vs = graph.curves[u.curve].vertices;
    if (u.reversed) std::reverse(vs.begin(), vs.end());
    const size_t inner = vs.size() - 2;
    const auto kept = static_cast<size_t>(static_cast<double>(inner) * keep);
    out.push_back(graph.vertices[vs[0]]);
    for (size_t k = 1; k <= kept; ++k) {
      out.push_back(graph.vertices[vs[k * (inner + 1) / (kept + 1)]]);
    }
  }
  return out;
}

double FaceCosts::Cost(const std::vector<CurveUse>& face) {
  std::vector<int32_t> key = Key(face);
  const auto it = cost_.find(key);
  if (it != cost_.end()) return it->second;
  Problem problem;
  problem.vertices = PricedPoints(graph_, face);
  double cost = kUnsurfaceable * static_cast<double>(problem.vertices.size());
  if (!RunsACurveTwice(face) && problem.vertices.size() >= 3) {
    problem.weights[Metric::kSquaredDihedral] = 1;
    Options options;
    options.space = SearchSpace::kDelaunay;
    const Result r = Triangulate(problem, options, control_);
    if (r.status.ok()) cost = r.total_cost;
  }
  cost_.emplace(std::move(key), cost);
  return cost;
}

}  // namespace dot

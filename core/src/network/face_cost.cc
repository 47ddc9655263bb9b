// SPDX-License-Identifier: AGPL-3.0-or-later
#include "network/face_cost.h"

#include <algorithm>
#include <atomic>
#include <chrono>

#include "dot/triangulate.h"
#include "network/seam.h"

namespace dot {
namespace {

// The face as darts (2 curve + reversed), rotated to start at its least
// dart: the same whichever dart a trace starts from.
std::vector<int32_t> Canonical(std::vector<int32_t> darts) {
  std::rotate(darts.begin(), std::min_element(darts.begin(), darts.end()),
              darts.end());
  return darts;
}

std::vector<CurveUse> Reversed(const std::vector<CurveUse>& face) {
  std::vector<CurveUse> out;
  for (auto it = face.rbegin(); it != face.rend(); ++it) {
    out.push_back({it->curve, !it->reversed});
  }
  return out;
}

std::vector<int32_t> Darts(const std::vector<CurveUse>& face) {
  std::vector<int32_t> darts;
  for (const CurveUse& u : face) darts.push_back(2 * u.curve + u.reversed);
  return Canonical(std::move(darts));
}

// A patch's rim passes each junction once: a face that runs a curve twice
// or comes back to a junction is pinched (the rotation makes such faces
// where a sign is wrong), and SurfaceNetwork would cut it apart.
bool Pinched(const NetworkGraph& graph, const std::vector<CurveUse>& face) {
  if (RunsACurveTwice(face)) return true;
  std::vector<int32_t> starts;
  for (const CurveUse& u : face) {
    const auto& vs = graph.curves[u.curve].vertices;
    starts.push_back(u.reversed ? vs.back() : vs.front());
  }
  std::sort(starts.begin(), starts.end());
  return std::adjacent_find(starts.begin(), starts.end()) != starts.end();
}

bool Stopped(const Control& control) {
  return (control.cancel != nullptr && control.cancel->load()) ||
         std::chrono::steady_clock::now() >= control.deadline;
}

}  // namespace

std::vector<Vec3> PricedPoints(const NetworkGraph& graph,
                               const std::vector<CurveUse>& face) {
  std::vector<int32_t> loop;
  for (const CurveUse& u : face) {
    std::vector<int32_t> vs = graph.curves[u.curve].vertices;
    if (u.reversed) std::reverse(vs.begin(), vs.end());
    loop.insert(loop.end(), vs.begin(), vs.end() - 1);
  }
  const size_t limit = FaceCosts::kMaxPoints;
  std::vector<Vec3> out;
  if (loop.size() <= limit || face.size() > limit / 2) {
    const size_t n = std::min(loop.size(), limit);
    for (size_t k = 0; k < n; ++k) {
      out.push_back(graph.vertices[loop[k * loop.size() / n]]);
    }
    return out;
  }
  // Each curve's first point, and its share of the rest.
  const double keep = static_cast<double>(limit - face.size()) /
                      static_cast<double>(loop.size() - face.size());
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

FaceCosts::FaceCosts(const NetworkGraph& graph, const Control& control,
                     int64_t max_points)
    : graph_(graph), max_points_(max_points) {
  control_.cancel = control.cancel;
  control_.deadline = control.deadline;
}

std::optional<double> FaceCosts::Cost(const std::vector<CurveUse>& face) {
  // Priced the way round whose darts come first, so that a face thinned to
  // kMaxPoints keeps the same points either way.
  std::vector<int32_t> forward = Darts(face);
  const std::vector<CurveUse> back = Reversed(face);
  std::vector<int32_t> backward = Darts(back);
  const bool turn = backward < forward;
  std::vector<int32_t> key = turn ? std::move(backward) : std::move(forward);
  const auto it = cost_.find(key);
  if (it != cost_.end()) return it->second;
  if (spent() || Stopped(control_)) return std::nullopt;
  // From its least dart too: a face thinned evenly along its loop keeps
  // the same points whichever dart a trace started from.
  std::vector<CurveUse> priced = turn ? back : face;
  const auto least = std::find_if(
      priced.begin(), priced.end(),
      [&](const CurveUse& u) { return 2 * u.curve + u.reversed == key[0]; });
  std::rotate(priced.begin(), least, priced.end());
  Problem problem;
  problem.vertices = PricedPoints(graph_, priced);
  priced_points_ += static_cast<int64_t>(problem.vertices.size());
  double cost = kUnsurfaceable * static_cast<double>(problem.vertices.size());
  if (!Pinched(graph_, face) && problem.vertices.size() >= 3) {
    problem.weights[Metric::kSquaredDihedral] = 1;
    Options options;
    options.space = SearchSpace::kDelaunay;
    const Result r = Triangulate(problem, options, control_);
    if (r.status.ok()) {
      cost = r.total_cost;
    } else if (r.status.code != StatusCode::kNoTriangulation &&
               r.status.code != StatusCode::kInvalidArgument) {
      return std::nullopt;  // stopped or out of memory: not a price
    }
  }
  cost_.emplace(std::move(key), cost);
  return cost;
}

}  // namespace dot

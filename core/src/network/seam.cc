// SPDX-License-Identifier: AGPL-3.0-or-later
// Seams: a face of the network that runs a path of curves one way and then
// back (a tube's seam, a curve from a hole to its rim) is no simple polygon
// for DOT. Cut along a new path across it, it is two: the new path's points
// are free vertices that fairing moves onto the surface.
#include "network/seam.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace dot {
namespace {

// The graph vertices along consecutive uses, from the first's start to the
// last's end, both included.
std::vector<int32_t> PathVertices(const NetworkGraph& g,
                                  const std::vector<CurveUse>& uses) {
  std::vector<int32_t> out;
  for (const CurveUse& u : uses) {
    const auto& vs = g.curves[u.curve].vertices;
    std::vector<int32_t> run(vs.begin(), vs.end());
    if (u.reversed) std::reverse(run.begin(), run.end());
    out.insert(out.end(), run.begin() + (out.empty() ? 0 : 1), run.end());
  }
  return out;
}

// Arc length from the path's start to each of its vertices.
std::vector<double> ArcLengths(const NetworkGraph& g,
                               const std::vector<int32_t>& path) {
  std::vector<double> out(path.size(), 0);
  for (size_t k = 1; k < path.size(); ++k) {
    out[k] =
        out[k - 1] + Distance(g.vertices[path[k - 1]], g.vertices[path[k]]);
  }
  return out;
}

bool Fail(std::string* why, const std::string& what) {
  if (why != nullptr) *why = what;
  return false;
}

// Where a seam loop's two runs start, and their length; false with why.
bool SeamRuns(const std::vector<CurveUse>& loop, size_t starts[2],
              size_t* length, std::string* why) {
  const size_t n = loop.size();
  std::map<int32_t, std::vector<size_t>> at_of;
  for (size_t i = 0; i < n; ++i) at_of[loop[i].curve].push_back(i);
  std::vector<char> twice(n, 0);
  for (const auto& [curve, at] : at_of) {
    if (at.size() == 1) continue;
    if (at.size() > 2 || loop[at[0]].reversed == loop[at[1]].reversed) {
      return Fail(why, "it runs curve " + std::to_string(curve) +
                           " more than once each way");
    }
    for (size_t i : at) twice[i] = 1;
  }
  // The maximal runs of uses of curves run twice: a seam is two, the
  // second the first backwards.
  std::vector<size_t> found;
  for (size_t i = 0; i < n; ++i) {
    if (twice[i] && !twice[(i + n - 1) % n]) found.push_back(i);
  }
  if (found.size() != 2) {
    return Fail(why, "the curves it runs both ways are not one path");
  }
  size_t k = 0;
  while (twice[(found[0] + k) % n]) ++k;
  for (size_t t = 0; t < k; ++t) {
    const CurveUse& f = loop[(found[0] + t) % n];
    const CurveUse& b = loop[(found[1] + k - 1 - t) % n];
    if (f.curve != b.curve || !twice[(found[1] + t) % n]) {
      return Fail(why, "the curves it runs both ways are not one path");
    }
  }
  starts[0] = found[0];
  starts[1] = found[1];
  *length = k;
  return true;
}

}  // namespace

bool RunsACurveTwice(const std::vector<CurveUse>& loop) {
  std::set<int32_t> curves;
  for (const CurveUse& u : loop) {
    if (!curves.insert(u.curve).second) return true;
  }
  return false;
}

bool IsSeamLoop(const std::vector<CurveUse>& loop, std::string* why) {
  size_t starts[2], k;
  return SeamRuns(loop, starts, &k, why);
}

bool SplitSeam(const NetworkGraph& g, const std::vector<CurveUse>& loop,
               SeamSplit* out, std::string* why) {
  *out = {};
  const size_t n = loop.size();
  size_t starts[2], k;
  if (!SeamRuns(loop, starts, &k, why)) return false;
  // In order: the seam path (a to b), the walk back to b, the seam back,
  // the walk back to a.
  auto run = [&](size_t from, size_t to) {  // uses [from, to), cyclic
    std::vector<CurveUse> uses_in;
    for (size_t i = from; i != to; i = (i + 1) % n) uses_in.push_back(loop[i]);
    return uses_in;
  };
  const std::vector<int32_t> seam =
      PathVertices(g, run(starts[0], (starts[0] + k) % n));
  const std::vector<int32_t> walk_b =
      PathVertices(g, run((starts[0] + k) % n, starts[1]));
  const std::vector<int32_t> walk_a =
      PathVertices(g, run((starts[1] + k) % n, starts[0]));
  if (walk_a.size() < 3 || walk_b.size() < 3) {
    return Fail(why, "a side of its seam is a single curve end");
  }
  // The new path joins the vertex of each walk half way round from the
  // seam (the second the nearest to the first, of those in the middle half
  // of its walk).
  const std::vector<double> len_a = ArcLengths(g, walk_a);
  const std::vector<double> len_b = ArcLengths(g, walk_b);
  size_t i_a = 1;
  for (size_t i = 1; i + 1 < walk_a.size(); ++i) {
    if (std::abs(len_a[i] - len_a.back() / 2) <
        std::abs(len_a[i_a] - len_a.back() / 2)) {
      i_a = i;
    }
  }
  const Vec3& p = g.vertices[walk_a[i_a]];
  size_t i_b = 0;
  for (int pass = 0; pass < 2 && i_b == 0; ++pass) {
    for (size_t i = 1; i + 1 < walk_b.size(); ++i) {
      const double f = len_b[i] / len_b.back();
      if (pass == 0 && (f < 0.25 || f > 0.75)) continue;
      if (i_b == 0 || Distance(p, g.vertices[walk_b[i]]) <
                          Distance(p, g.vertices[walk_b[i_b]])) {
        i_b = i;
      }
    }
  }
  const Vec3& q = g.vertices[walk_b[i_b]];
  // Spaced as the loop's edges, at most as many points as the loop has,
  // and at least one: a path of one edge could be a curve's edge.
  const double mean_edge =
      (len_a.back() + len_b.back() + 2 * ArcLengths(g, seam).back()) /
      static_cast<double>(walk_a.size() + walk_b.size() + 2 * seam.size() - 4);
  double steps = mean_edge > 0 ? std::round(Distance(p, q) / mean_edge) : 1;
  if (!std::isfinite(steps)) steps = 2;
  const auto points = static_cast<int32_t>(std::clamp(
      steps - 1, 1.0, static_cast<double>(walk_a.size() + walk_b.size())));
  const auto first_new = static_cast<int32_t>(g.vertices.size());
  std::vector<int32_t> path;
  for (int32_t t = 1; t <= points; ++t) {
    path.push_back(first_new + t - 1);
    out->new_vertices.push_back(p + (static_cast<double>(t) / (points + 1)) *
                                        (q - p));
  }
  // Piece 0: a to p, the new path, q to b, the seam back to a. Piece 1: p
  // to a, the seam, b to q, the new path back to p.
  std::vector<int32_t> one(walk_a.begin(), walk_a.begin() + i_a + 1);
  one.insert(one.end(), path.begin(), path.end());
  one.insert(one.end(), walk_b.begin() + i_b, walk_b.end());
  one.insert(one.end(), seam.rbegin() + 1, seam.rend() - 1);
  std::vector<int32_t> two(walk_a.begin() + i_a, walk_a.end());
  two.insert(two.end(), seam.begin() + 1, seam.end());
  two.insert(two.end(), walk_b.begin() + 1, walk_b.begin() + i_b + 1);
  two.insert(two.end(), path.rbegin(), path.rend());
  for (const auto* piece : {&one, &two}) {
    std::set<int32_t> seen(piece->begin(), piece->end());
    if (seen.size() != piece->size()) {
      return Fail(why, "a side of its seam runs through a vertex twice");
    }
  }
  out->pieces = {std::move(one), std::move(two)};
  out->seam = seam;
  out->from = walk_a[i_a];
  out->to = walk_b[i_b];
  return true;
}

}  // namespace dot

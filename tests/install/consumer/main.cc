// SPDX-License-Identifier: AGPL-3.0-or-later
// The README's first C++ example, as a user builds it: triangulate a
// curve, fill the holes of a mesh, and print what came back.
#include <cstdio>
#include <string>

#include "dot/dot.h"

int main() {
  dot::Problem problem;
  problem.vertices = dot::MakeCurve(dot::Curve::kMonkey, 60);
  problem.weights[dot::Metric::kSquaredDihedral] = 1;  // DOT2
  const dot::Result r = dot::Triangulate(problem);
  if (!r.status.ok()) {
    std::fprintf(stderr, "triangulate: %s\n", r.status.message.c_str());
    return 1;
  }
  std::printf("%zu triangles, cost %.6g, solver %s\n", r.triangles.size(),
              r.total_cost, std::string(dot::SolverName(r.solver)).c_str());
  return r.triangles.size() == problem.vertices.size() - 2 ? 0 : 1;
}

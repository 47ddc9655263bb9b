// SPDX-License-Identifier: AGPL-3.0-or-later
// Stable names of Triangulate's enums, shared by CLI, logs and the wire.
#include "dot/control.h"
#include "dot/problem.h"

namespace dot {

std::string_view SearchSpaceName(SearchSpace s) {
  switch (s) {
    case SearchSpace::kAuto:
      return "auto";
    case SearchSpace::kDelaunay:
      return "delaunay";
    case SearchSpace::kAll:
      return "all";
    case SearchSpace::kDelaunayFirst:
      return "delaunay_first";
  }
  return "?";
}

std::string_view DelaunayBackendName(DelaunayBackend b) {
  return b == DelaunayBackend::kTetgen ? "tetgen" : "cgal";
}

std::string_view SpaceUsedName(SpaceUsed s) {
  switch (s) {
    case SpaceUsed::kNone:
      return "none";
    case SpaceUsed::kDelaunay3d:
      return "delaunay3d";
    case SpaceUsed::kPlanarDelaunay2d:
      return "planar_cdt2d";
    case SpaceUsed::kAll:
      return "all";
    case SpaceUsed::kAllDelaunayFirst:
      return "all_delaunay_first";
  }
  return "?";
}

std::string_view SolverName(Solver s) {
  switch (s) {
    case Solver::kNone:
      return "none";
    case Solver::kDot1:
      return "DOT1";
    case Solver::kDot2:
      return "DOT2";
    case Solver::kGk1:
      return "GK1";
    case Solver::kGk2:
      return "GK2";
    case Solver::kGk2Greedy:
      return "GK2-greedy";
  }
  return "?";
}

std::optional<DelaunayBackend> DelaunayBackendFromName(std::string_view name) {
  for (DelaunayBackend b : {DelaunayBackend::kCgal, DelaunayBackend::kTetgen}) {
    if (name == DelaunayBackendName(b)) return b;
  }
  return std::nullopt;
}

}  // namespace dot

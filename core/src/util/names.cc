// SPDX-License-Identifier: AGPL-3.0-or-later
// Stable names of the library's enums, shared by CLI, logs and the wire.
#include "dot/curves.h"
#include "dot/metrics.h"
#include "dot/status.h"
#include "dot/triangulate.h"

namespace dot {

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

std::string_view StatusCodeName(StatusCode c) {
  switch (c) {
    case StatusCode::kOk:
      return "ok";
    case StatusCode::kNoTriangulation:
      return "no_triangulation";
    case StatusCode::kInvalidArgument:
      return "invalid_argument";
    case StatusCode::kResourceExhausted:
      return "resource_exhausted";
    case StatusCode::kCancelled:
      return "cancelled";
    case StatusCode::kDeadlineExceeded:
      return "deadline_exceeded";
    case StatusCode::kInternal:
      return "internal";
  }
  return "?";
}

std::string_view SearchSpaceName(SearchSpace s) {
  switch (s) {
    case SearchSpace::kAuto:
      return "auto";
    case SearchSpace::kDelaunay:
      return "delaunay";
    case SearchSpace::kAll:
      return "all";
  }
  return "?";
}

std::string_view DelaunayBackendName(DelaunayBackend b) {
  return b == DelaunayBackend::kTetgen ? "tetgen" : "cgal";
}

bool ParseDelaunayBackend(std::string_view name, DelaunayBackend* backend) {
  for (DelaunayBackend b : {DelaunayBackend::kCgal, DelaunayBackend::kTetgen}) {
    if (name == DelaunayBackendName(b)) {
      *backend = b;
      return true;
    }
  }
  return false;
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
  }
  return "?";
}

std::string_view StageName(Stage s) {
  switch (s) {
    case Stage::kValidate:
      return "validation";
    case Stage::kDelaunay:
      return "the Delaunay step";
    case Stage::kAdjacency:
      return "adjacency";
    case Stage::kDynamicProgram:
      return "the dynamic program";
    case Stage::kTiling:
      return "tiling";
  }
  return "?";
}

std::string_view CurveName(Curve c) {
  switch (c) {
    case Curve::kMonkey:
      return "monkey";
    case Curve::kMobius:
      return "mobius";
    case Curve::kSpiral:
      return "spiral";
    case Curve::kMoment:
      return "moment";
    case Curve::kTwist:
      return "twist";
    case Curve::kTrefoil:
      return "trefoil";
  }
  return "?";
}

std::optional<Curve> CurveFromName(std::string_view name) {
  for (Curve c : {Curve::kMonkey, Curve::kMobius, Curve::kSpiral,
                  Curve::kMoment, Curve::kTwist, Curve::kTrefoil}) {
    if (CurveName(c) == name) return c;
  }
  return std::nullopt;
}

}  // namespace dot

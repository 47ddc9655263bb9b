// SPDX-License-Identifier: AGPL-3.0-or-later
// Rejects malformed problems before any work, naming the offending index and
// value: too few vertices, non-finite or duplicate vertices, bad normals or
// weights, collinear polygons; and options out of range or naming a backend
// this build does not have.
#ifndef DOT_CORE_POLYGON_INPUT_CHECK_H_
#define DOT_CORE_POLYGON_INPUT_CHECK_H_

#include <string>

#include "dot/control.h"
#include "dot/problem.h"
#include "dot/status.h"
#include "polygon/plane_fit.h"

namespace dot {

std::string FormatVec(const Vec3& v);

// Checks everything but collinearity, which needs the plane fit.
Status CheckProblem(const Problem& problem, const Options& options);
Status CheckNotCollinear(const PlaneFit& fit, int n, const Options& options);

}  // namespace dot

#endif  // DOT_CORE_POLYGON_INPUT_CHECK_H_

// SPDX-License-Identifier: AGPL-3.0-or-later
// The CGAL kernel the judge and the CGAL child share.
#ifndef DOT_BENCH_SUITE_FILL_BENCH_CGAL_TYPES_H_
#define DOT_BENCH_SUITE_FILL_BENCH_CGAL_TYPES_H_

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "dot/geometry.h"

namespace dot::bench::fill {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

inline K::Point_3 P(const Vec3& v) { return {v.x, v.y, v.z}; }

}  // namespace dot::bench::fill

#endif  // DOT_BENCH_SUITE_FILL_BENCH_CGAL_TYPES_H_

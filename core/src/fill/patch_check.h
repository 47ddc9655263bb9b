// SPDX-License-Identifier: AGPL-3.0-or-later
// Intersection counts over a few faces of a large mesh, without copying the
// mesh: only the vertices the faces use are gathered.
#ifndef DOT_CORE_FILL_PATCH_CHECK_H_
#define DOT_CORE_FILL_PATCH_CHECK_H_

#include <cstdint>
#include <functional>
#include <vector>

#include "dot/control.h"
#include "dot/geometry.h"
#include "dot/problem.h"
#include "dot/status.h"
#include "mesh/face_tree.h"

namespace dot {

// Pairs of `faces` that intersect (exact predicates, as the validator)
// with at least one of the pair among the first `checked`; `point` gives a
// vertex id's position. Faces are taken by value: they are renumbered.
// Stops when `control` says so (kCancelled, kDeadlineExceeded).
Status CountPairsAmong(const std::function<const Vec3&(int32_t)>& point,
                       std::vector<Triangle> faces, size_t checked,
                       const Control& control, int64_t* pairs);

}  // namespace dot

#endif  // DOT_CORE_FILL_PATCH_CHECK_H_

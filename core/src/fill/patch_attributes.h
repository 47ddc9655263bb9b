// SPDX-License-Identifier: AGPL-3.0-or-later
// The attribute entries of the corners of filled holes' patches, from the
// faces across each patch's rim (see soup_output.h for the method:
// mean-value harmonic fields, seams cut into arcs, normals from the
// patch's own faces).
#ifndef DOT_CORE_FILL_PATCH_ATTRIBUTES_H_
#define DOT_CORE_FILL_PATCH_ATTRIBUTES_H_

#include <cstddef>
#include <utility>
#include <vector>

#include "dot/geometry.h"
#include "dot/mesh.h"
#include "fill/attribute_entries.h"

namespace dot {

// `patches`: (first face, face count) of each patch in `faces`. Every
// other face's corners have their entries in `corners`; each patch's are
// filled in, channel by channel (a patch with no face across its rim is
// left with kNone).
void InterpolatePatches(const std::vector<Vec3>& points,
                        const std::vector<Triangle>& faces,
                        const std::vector<std::pair<size_t, size_t>>& patches,
                        std::vector<AttributeChannel>* channels,
                        CornerEntries* corners);

}  // namespace dot

#endif  // DOT_CORE_FILL_PATCH_ATTRIBUTES_H_

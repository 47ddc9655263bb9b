// SPDX-License-Identifier: AGPL-3.0-or-later
// Faces of a tetrahedralization given as tetrahedra and neighbour lists, as
// TetGen (in-process or in the server's helper processes) returns it.
#ifndef DOT_CORE_SEARCH_SPACE_FACES_OF_TETRAHEDRA_H_
#define DOT_CORE_SEARCH_SPACE_FACES_OF_TETRAHEDRA_H_

#include <vector>

#include "dot/control.h"
#include "dot/geometry.h"
#include "dot/problem.h"
#include "dot/status.h"

namespace dot {

// Distinct faces of a tetrahedralization, each sorted ascending, found
// through the neighbour lists in one linear pass. kInternal when the
// neighbour lists are inconsistent.
Status FacesOfTetrahedra(const Tetrahedralization& t,
                         std::vector<Triangle>* faces);

}  // namespace dot

#endif  // DOT_CORE_SEARCH_SPACE_FACES_OF_TETRAHEDRA_H_

// SPDX-License-Identifier: AGPL-3.0-or-later
// Umbrella header of the dot core library: include this, call
// dot::Triangulate(problem, options) or dot::FillSoup(soup, options). The
// helper process pool (dot/delaunay_helpers.h, POSIX) is included apart.
#ifndef DOT_DOT_H_
#define DOT_DOT_H_

#include "dot/control.h"          // IWYU pragma: export
#include "dot/curves.h"           // IWYU pragma: export
#include "dot/elapsed.h"          // IWYU pragma: export
#include "dot/fill_holes.h"       // IWYU pragma: export
#include "dot/fill_soup.h"        // IWYU pragma: export
#include "dot/geometry.h"         // IWYU pragma: export
#include "dot/hole_generator.h"   // IWYU pragma: export
#include "dot/io.h"               // IWYU pragma: export
#include "dot/mesh.h"             // IWYU pragma: export
#include "dot/mesh_repair.h"      // IWYU pragma: export
#include "dot/metrics.h"          // IWYU pragma: export
#include "dot/network.h"          // IWYU pragma: export
#include "dot/network_samples.h"  // IWYU pragma: export
#include "dot/problem.h"          // IWYU pragma: export
#include "dot/space_cache.h"      // IWYU pragma: export
#include "dot/status.h"           // IWYU pragma: export
#include "dot/table_memory.h"     // IWYU pragma: export
#include "dot/triangulate.h"      // IWYU pragma: export
#include "dot/validate.h"         // IWYU pragma: export

#endif  // DOT_DOT_H_

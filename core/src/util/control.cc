// SPDX-License-Identifier: AGPL-3.0-or-later
// Stage names, for progress messages and logs.
#include "dot/control.h"

namespace dot {

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

}  // namespace dot

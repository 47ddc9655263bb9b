// SPDX-License-Identifier: AGPL-3.0-or-later
#include "search_space/faces_of_tetrahedra.h"

#include <algorithm>
#include <string>

namespace dot {

Status FacesOfTetrahedra(const Tetrahedralization& t,
                         std::vector<Triangle>* faces) {
  const auto count = static_cast<int32_t>(t.tets.size());
  if (t.neighbors.size() != t.tets.size()) {
    return MakeStatus(
        StatusCode::kInternal,
        "tetrahedralization has " + std::to_string(count) + " tetrahedra but " +
            std::to_string(t.neighbors.size()) + " neighbour lists");
  }
  faces->clear();
  faces->reserve(2 * t.tets.size() + 4);
  for (int32_t i = 0; i < count; ++i) {
    const auto& tet = t.tets[i];
    int hull_faces = 0;
    for (int32_t nb : t.neighbors[i]) {
      if (nb < 0 || nb >= count) {
        ++hull_faces;
        continue;
      }
      if (nb < i) continue;  // emitted when visiting nb
      // The shared face: the corners of `tet` that `nb` also has.
      Triangle f;
      int k = 0;
      for (int32_t v : tet) {
        const auto& other = t.tets[nb];
        if (std::find(other.begin(), other.end(), v) != other.end() && k < 3) {
          f[k++] = v;
        }
      }
      if (k != 3) {
        return MakeStatus(StatusCode::kInternal,
                          "tetrahedra " + std::to_string(i) + " and " +
                              std::to_string(nb) +
                              " are listed as neighbours "
                              "but share no face");
      }
      std::sort(f.begin(), f.end());
      faces->push_back(f);
    }
    if (hull_faces == 0) continue;
    // Hull faces: those of the four faces not shared with a neighbour.
    for (int skip = 0; skip < 4; ++skip) {
      Triangle f;
      int k = 0;
      for (int c = 0; c < 4; ++c) {
        if (c != skip) f[k++] = tet[c];
      }
      bool shared = false;
      for (int32_t nb : t.neighbors[i]) {
        if (nb < 0 || nb >= count) continue;
        const auto& other = t.tets[nb];
        shared |=
            std::find(other.begin(), other.end(), tet[skip]) == other.end();
      }
      if (shared) continue;
      std::sort(f.begin(), f.end());
      faces->push_back(f);
    }
  }
  return OkStatus();
}

}  // namespace dot

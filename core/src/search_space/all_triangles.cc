// SPDX-License-Identifier: AGPL-3.0-or-later
#include "search_space/all_triangles.h"

#include "util/run_control.h"

namespace dot {

Status AllTriangles(const std::vector<Vec3>& loop, const Control& control,
                    std::vector<Triangle>* triangles) {
  const auto n = static_cast<int32_t>(loop.size());
  RunTicker ticker(control, Stage::kDelaunay);
  triangles->clear();
  triangles->reserve(static_cast<size_t>(n) * (n - 1) * (n - 2) / 6);
  for (int32_t a = 0; a < n; ++a) {
    for (int32_t b = a + 1; b < n; ++b) {
      const Vec3 ab = loop[b] - loop[a];
      for (int32_t c = b + 1; c < n; ++c) {
        const Vec3 cross = Cross(ab, loop[c] - loop[a]);
        if (cross.x == 0 && cross.y == 0 && cross.z == 0) continue;
        triangles->push_back({a, b, c});
      }
      if (!ticker.Tick(double(a) / n)) return ticker.status();
    }
  }
  return OkStatus();
}

}  // namespace dot

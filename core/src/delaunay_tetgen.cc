// SPDX-License-Identifier: AGPL-3.0-or-later
#include <algorithm>
#include <mutex>

#include "delaunay.h"
#include "tetgen.h"  // needs TETLIBRARY (set by TetGen::TetGen) to throw

namespace dot {

Status TetgenTetrahedralize(const std::vector<Vec3>& points,
                            std::vector<std::array<int32_t, 4>>* tets) {
  // The one piece of process-wide state in the library, forced by TetGen's.
  static std::mutex tetgen_mutex;
  std::vector<REAL> coords;
  coords.reserve(3 * points.size());
  for (const Vec3& p : points) coords.insert(coords.end(), {p.x, p.y, p.z});

  std::lock_guard<std::mutex> lock(tetgen_mutex);
  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(points.size());
  in.pointlist = coords.data();
  // tetgenio frees its arrays with delete[]; ours belongs to `coords`.
  struct Release {
    tetgenio& io;
    ~Release() { io.pointlist = nullptr; }
  } release{in};
  tetgenbehavior b;
  char switches[] = "Q";  // quiet: plain Delaunay tetrahedralization
  if (!b.parse_commandline(switches)) {
    return MakeStatus(StatusCode::kInternal, "TetGen rejected its switches");
  }
  try {
    tetrahedralize(&b, &in, &out);
  } catch (int code) {
    return MakeStatus(StatusCode::kInternal,
                      "TetGen failed with error code " + std::to_string(code));
  } catch (...) {
    return MakeStatus(StatusCode::kInternal, "TetGen failed");
  }
  if (out.numberofcorners != 4 || out.tetrahedronlist == nullptr) {
    return MakeStatus(StatusCode::kInternal, "TetGen returned no tetrahedra");
  }
  tets->resize(out.numberoftetrahedra);
  std::vector<bool> used(points.size(), false);
  for (int t = 0; t < out.numberoftetrahedra; ++t) {
    for (int k = 0; k < 4; ++k) {
      const int v = out.tetrahedronlist[4 * t + k];
      if (v < 0 || v >= static_cast<int>(points.size())) {
        return MakeStatus(StatusCode::kInternal,
                          "TetGen returned an out-of-range vertex index");
      }
      (*tets)[t][k] = v;
      used[v] = true;
    }
  }
  // TetGen silently drops points it considers duplicates; the search space
  // would then miss polygon edges for no geometric reason.
  const auto missing = std::find(used.begin(), used.end(), false);
  if (missing != used.end()) {
    return MakeStatus(StatusCode::kInvalidArgument,
                      "vertex " + std::to_string(missing - used.begin()) +
                          " is so close to another vertex that TetGen merged "
                          "them");
  }
  return OkStatus();
}

std::vector<Triangle> FacesOfTetrahedra(
    const std::vector<std::array<int32_t, 4>>& tets) {
  std::vector<Triangle> faces;
  faces.reserve(4 * tets.size());
  for (const auto& t : tets) {
    for (int skip = 0; skip < 4; ++skip) {
      Triangle f;
      int k = 0;
      for (int i = 0; i < 4; ++i) {
        if (i != skip) f[k++] = t[i];
      }
      std::sort(f.begin(), f.end());
      faces.push_back(f);
    }
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

}  // namespace dot

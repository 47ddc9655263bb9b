// SPDX-License-Identifier: AGPL-3.0-or-later
// TetGen 1.5, the second 3D Delaunay backend and the library's one AGPL
// dependency: kept in this folder and compiled only with DOT_WITH_TETGEN=ON.
#include <algorithm>
#include <mutex>
#include <new>

#include "dot/control.h"
#include "dot/problem.h"
#include "tetgen.h"  // needs TETLIBRARY (set by TetGen::TetGen) to throw

namespace dot {

Status TetgenTetrahedralize(const std::vector<Vec3>& points,
                            Tetrahedralization* out_tets) {
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
  char switches[] = "Qn";  // quiet Delaunay tetrahedralization, neighbours
  if (!b.parse_commandline(switches)) {
    return MakeStatus(StatusCode::kInternal, "TetGen rejected its switches");
  }
  try {
    tetrahedralize(&b, &in, &out);
  } catch (const std::bad_alloc&) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "TetGen ran out of memory on " +
                          std::to_string(points.size()) + " points");
  } catch (int code) {
    // TetGen's terminatetetgen() codes.
    if (code == 1) {
      return MakeStatus(StatusCode::kResourceExhausted,
                        "TetGen ran out of memory on " +
                            std::to_string(points.size()) + " points");
    }
    return MakeStatus(StatusCode::kInternal,
                      "TetGen failed with error code " + std::to_string(code) +
                          (code == 2 ? " (internal error)" : ""));
  } catch (...) {
    return MakeStatus(StatusCode::kInternal, "TetGen failed");
  }
  if (out.numberofcorners != 4 || out.tetrahedronlist == nullptr ||
      out.neighborlist == nullptr) {
    return MakeStatus(StatusCode::kInternal, "TetGen returned no tetrahedra");
  }
  auto& tets = out_tets->tets;
  auto& neighbors = out_tets->neighbors;
  tets.resize(out.numberoftetrahedra);
  neighbors.resize(out.numberoftetrahedra);
  std::vector<bool> used(points.size(), false);
  for (int t = 0; t < out.numberoftetrahedra; ++t) {
    for (int k = 0; k < 4; ++k) {
      const int v = out.tetrahedronlist[4 * t + k];
      if (v < 0 || v >= static_cast<int>(points.size())) {
        return MakeStatus(StatusCode::kInternal,
                          "TetGen returned an out-of-range vertex index");
      }
      tets[t][k] = v;
      used[v] = true;
      const int nb = out.neighborlist[4 * t + k];
      neighbors[t][k] = nb >= 0 && nb < out.numberoftetrahedra ? nb : -1;
    }
  }
  // TetGen silently drops points it considers duplicates; the search space
  // would then miss polygon edges for no geometric reason.
  const auto missing = std::find(used.begin(), used.end(), false);
  if (missing != used.end()) {
    return InvalidArgument("vertex " + std::to_string(missing - used.begin()) +
                           " is so close to another vertex that TetGen merged "
                           "them");
  }
  return OkStatus();
}

}  // namespace dot

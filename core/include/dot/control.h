// SPDX-License-Identifier: AGPL-3.0-or-later
// Run-time hooks of one call (cancel, deadline, progress, the backends that
// run out of process, the search-space cache), as opposed to its
// configuration (each entry point's Options). Every layer of the core takes
// a Control; nothing here depends on what the call computes.
#ifndef DOT_CONTROL_H_
#define DOT_CONTROL_H_

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

#include "dot/geometry.h"
#include "dot/status.h"

namespace dot {

// The stages of Triangulate, as progress reports them.
enum class Stage { kValidate, kDelaunay, kAdjacency, kDynamicProgram, kTiling };
// "validation", "the Delaunay step", ...: for messages and logs.
std::string_view StageName(Stage s);

class SpaceCache;

// A 3D Delaunay tetrahedralization: vertex-index quadruples, and for each
// tetrahedron the indices of the (up to four) tetrahedra sharing a face with
// it, -1 for faces on the convex hull.
struct Tetrahedralization {
  std::vector<std::array<int32_t, 4>> tets;
  std::vector<std::array<int32_t, 4>> neighbors;
};
// Tetrahedralization backend for `points` (no duplicates, not all coplanar).
// The default is TetGen in-process, serialized by a mutex.
using TetrahedralizeFn = std::function<Status(const std::vector<Vec3>& points,
                                              Tetrahedralization* out)>;

// The default backend: TetGen in this process, serialized by a mutex
// (TetGen keeps file-scope state). It aborts the process on exactly planar
// input, which Triangulate never passes it. In a build without TetGen
// (!TetgenAvailable()) it returns kInvalidArgument.
Status TetgenTetrahedralize(const std::vector<Vec3>& points,
                            Tetrahedralization* out);

// A square sparse system A X = B with `rhs` right-hand sides, as fairing
// solves it: A by its nonzeros, B and X column-major (n * rhs values).
struct SparseSystem {
  int64_t n = 0;
  std::vector<int32_t> rows, cols;
  std::vector<double> values;
  int32_t rhs = 0;
  std::vector<double> b;
};
// Sparse solver backend: X into `x`; kInvalidArgument for a singular A.
using SparseSolveFn =
    std::function<Status(const SparseSystem& system, std::vector<double>* x)>;
// Fairing systems of more unknowns than this go to Control::solve_sparse,
// when set; smaller ones factorize in process in at most ~50 ms.
inline constexpr int64_t kSolveSparseMinUnknowns = 2000;

// The default backend: Eigen's SparseLU (COLAMD ordering, as CGAL's fair())
// in this process. It cannot be interrupted: ~0.1 s for 3,000 unknowns of a
// bi-Laplacian, 0.6 s for 12,000, growing superlinearly.
Status SolveSparseLu(const SparseSystem& system, std::vector<double>* x);

// Run-time hooks of one call, as opposed to its configuration.
struct Control {
  const std::atomic<bool>* cancel = nullptr;  // polled; true stops the run
  std::chrono::steady_clock::time_point deadline =
      std::chrono::steady_clock::time_point::max();
  // Called from the computing thread, at most every few milliseconds.
  std::function<void(Stage, double fraction)> progress;
  // Replaces in-process TetGen for DelaunayBackend::kTetgen (the server runs
  // it in helper processes). Empty: TetGen in-process.
  TetrahedralizeFn tetrahedralize;
  // Replaces in-process SolveSparseLu for fairing systems above
  // kSolveSparseMinUnknowns (the server runs it in the helper processes,
  // where a cancel or deadline kills it at once). Empty: in-process.
  SparseSolveFn solve_sparse;
  // Keeps and reuses weight-independent search spaces across calls; null:
  // no caching. See dot/space_cache.h.
  SpaceCache* space_cache = nullptr;
  // Asked when a run stops after finishing part of its work (a fill with
  // some holes done): whether that part is still wanted, so the run
  // assembles and returns it (FillResult::partial). Null: it is. The
  // server says no once its client has gone.
  std::function<bool()> keep_partial;
};

}  // namespace dot

#endif  // DOT_CONTROL_H_

// SPDX-License-Identifier: AGPL-3.0-or-later
// What a triangulation takes and gives: the problem, the options, the
// result and the names of their enums. The vocabulary every stage of the
// polygon pipeline shares; the entry point is dot/triangulate.h.
#ifndef DOT_PROBLEM_H_
#define DOT_PROBLEM_H_

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "dot/geometry.h"
#include "dot/metrics.h"
#include "dot/status.h"

namespace dot {

enum class SearchSpace { kAuto, kDelaunay, kAll, kDelaunayFirst };
// What actually produced a result.
enum class SpaceUsed {
  kNone,
  kDelaunay3d,
  kPlanarDelaunay2d,
  kAll,
  kAllDelaunayFirst
};
// kGk2Greedy: kDelaunayFirst's cubic program with bending weights, which
// prices each bend against the sub-chain's own optimum (as CGAL does).
enum class Solver { kNone, kDot1, kDot2, kGk1, kGk2, kGk2Greedy };
// Who computes the 3D Delaunay tetrahedralization. Both use exact
// predicates; they can differ only in how they break cospherical ties.
enum class DelaunayBackend { kCgal, kTetgen };
// Whether this build has the TetGen backend (CMake option DOT_WITH_TETGEN,
// also visible to dependents as the compile definition DOT_WITH_TETGEN=1/0).
// Without it, CGAL is the only backend and a request for kTetgen fails with
// kInvalidArgument.
bool TetgenAvailable();
// Why a build without TetGen (DOT_WITH_TETGEN=OFF) refuses kTetgen.
inline constexpr char kNoTetgenMessage[] =
    "this build has no TetGen backend (built with DOT_WITH_TETGEN=OFF); use "
    "cgal";

std::string_view SearchSpaceName(SearchSpace s);
std::string_view SpaceUsedName(SpaceUsed s);
std::string_view SolverName(Solver s);
std::string_view DelaunayBackendName(DelaunayBackend b);  // "cgal", "tetgen"
// The backend a DelaunayBackendName names; nullopt when it names none.
std::optional<DelaunayBackend> DelaunayBackendFromName(std::string_view name);

struct Problem {
  std::vector<Vec3> vertices;  // polygon, closed from last to first
  std::vector<Vec3> normals;   // empty, or one boundary normal per vertex
  MetricWeights weights;       // all zero means area alone
  // Filling a hole of a surface: empty, or one per vertex i, the normal of
  // the surface face across the polygon edge (i, i+1 mod n), oriented like
  // the patch (the face runs i+1 -> i); a zero vector means no face there.
  // The bi-triangle metrics then also price the bending between that face
  // and the patch triangle on the edge (DOT2/GK2 and Result::metric_costs
  // alike), so a patch meets its surroundings smoothly. Ignored by DOT1.
  std::vector<Vec3> edge_face_normals;
  // Chords (vertex index pairs that are not polygon edges) no triangle of
  // the result may use: edges the surrounding mesh already has, which the
  // patch would make non-manifold.
  std::vector<std::pair<int32_t, int32_t>> forbidden_edges;
  // Several loops bounding one surface: empty (the vertices are one loop),
  // or the sizes of consecutive loops, each at least 3, summing to the
  // vertex count (loop i is closed from its last vertex to its first). The
  // result is a surface of genus 0 with exactly these boundaries; each loop
  // runs along it in its given direction (the surface on its left, seen
  // from the side its normal points to), unless Options::reorient_loops
  // lets the solver reverse loops after the first. Two loops are solved
  // exactly; three or more by bridges first (Result::bridges).
  // (A default initializer keeps {vertices, ...} initializations short.)
  std::vector<int32_t> loop_sizes = {};
};

// How Triangulate searches. A default-constructed Options is the
// recommended configuration; every field, its meaning and default:
//
//  space                 Which candidate triangles to search (see above).
//                        Default: SearchSpace::kAuto.
//  delaunay              3D Delaunay backend. Default: DelaunayBackend::kCgal
//                        (faster than TetGen, re-entrant, cancellable
//                        mid-way, and the only one when !TetgenAvailable()).
//  protect_edges         Split polygon edges on no Delaunay triangle at their
//                        midpoints until every polygon edge is on one (paper,
//                        Lemma 4.3). Default: false.
//  max_inserted_vertices Most vertices edge protection may insert; beyond,
//                        kResourceExhausted. Default: 100000.
//  all_space_max_vertices kAuto falls back to kAll (when no Delaunay
//                        triangulation exists) only up to this many vertices.
//                        Default: 40.
//  all_space_hard_limit  An explicit kAll is refused above this many
//                        vertices (its tables grow as n^3). Default: 400.
//  delaunay_first_max_vertices  kDelaunayFirst is refused above this many
//                        vertices (its time grows as n^3: about 2 s at
//                        1,000 on the machines measured). Default: 2000.
//  planar_tolerance      A polygon is planar when every vertex is within this
//                        fraction of its bounding-box diagonal from its
//                        least-squares plane. Default: 1e-6.
//  memory_budget_bytes   Refuse (kResourceExhausted) a request whose memory
//                        would exceed this: the Delaunay step stops when its
//                        cells (with their faces and the tables they imply)
//                        pass it; the tables are estimated before
//                        allocating. Default: 2 GiB (int64_t{2} << 30).
//  validate_output       Count self-intersecting triangle pairs of the output
//                        (Result::intersecting_pairs; always done for kAll
//                        results, which may self-intersect). Default: false.
//  parallel_delaunay_min_points
//                        The CGAL backend inserts points on several threads
//                        (TBB, CGAL's lock grid) from this many polygon
//                        vertices on. The result is the same either way
//                        (CGAL's Delaunay is unique under symbolic
//                        perturbation). Default: off (INT_MAX): on the
//                        2-core machines measured, parallel insertion was
//                        slower on every input (README, Performance); set
//                        it (e.g. 20000) where more cores pay off.
//  delaunay_threads      Threads of that parallel insertion: 0 all cores, 1
//                        sequential always. Default: 0.
//  reorient_loops        Several loops: the solver may reverse loops after
//                        the first when the surface is cheaper that way (it
//                        tries both directions; Result::reversed_loops
//                        names those reversed). false: every loop keeps its
//                        given direction, as filling a hole with an island
//                        of a mesh needs. Default: true.
struct Options {
  SearchSpace space = SearchSpace::kAuto;
  DelaunayBackend delaunay = DelaunayBackend::kCgal;
  bool protect_edges = false;
  int max_inserted_vertices = 100000;
  int all_space_max_vertices = 40;
  int all_space_hard_limit = 400;
  int delaunay_first_max_vertices = 2000;
  double planar_tolerance = 1e-6;
  int64_t memory_budget_bytes = int64_t{2} << 30;
  bool validate_output = false;
  int parallel_delaunay_min_points = std::numeric_limits<int>::max();
  int delaunay_threads = 0;
  bool reorient_loops = true;
};

struct Stats {
  int n = 0;                       // polygon vertices, after edge protection
  int64_t tetrahedra = 0;          // 3D Delaunay tetrahedra
  int64_t delaunay_triangles = 0;  // distinct faces of those (or 2D faces)
  int64_t search_triangles = 0;    // |S|: candidate triangles
  int64_t edges = 0;               // distinct edges of the candidates
  int64_t adjacency_entries = 0;   // |Pi|: edge-triangle incidences
  int64_t dp_states = 0;           // DOT1: edges; DOT2: edge-triangle pairs
  int64_t table_bytes = 0;         // adjacency + DP tables
  int64_t estimated_bytes = 0;     // the estimate checked against the budget
  bool cache_hit = false;          // the search space came from the cache
  // kDelaunayFirst: triangles of the result that are not Delaunay faces.
  int64_t non_delaunay_triangles = 0;
  double validate_ms = 0, delaunay_ms = 0, adjacency_ms = 0, dp_ms = 0,
         tiling_ms = 0, total_ms = 0;
};

struct Result {
  Status status;  // kOk: triangles hold the answer; kNoTriangulation: reason
  std::vector<Vec3> vertices;       // the input's, then any inserted ones
  std::vector<Triangle> triangles;  // oriented: polygon runs i -> i+1
  std::vector<int32_t> polygon;     // the loop (with inserted vertices)
  // Several loops: their sizes in `polygon` (with inserted vertices), which
  // lists each loop in the direction the surface runs along it; empty for
  // one loop.
  std::vector<int32_t> loop_sizes;
  std::vector<int32_t> reversed_loops;  // loops run against their input
  // Three or more loops: the edges that joined the loops into one polygon
  // first (vertex index pairs). The surface is the optimum for these
  // bridges, an approximation of the optimum over every surface (see
  // README "One surface through several loops"); empty otherwise.
  std::vector<std::pair<int32_t, int32_t>> bridges;
  std::vector<int32_t> inserted;  // indices of vertices edge protection added
  std::vector<std::pair<int32_t, int32_t>> non_delaunay_edges;
  double total_cost = 0;
  MetricValues metric_costs;  // unweighted sum of each metric
  SpaceUsed space_used = SpaceUsed::kNone;
  DelaunayBackend delaunay = DelaunayBackend::kCgal;  // for kDelaunay3d
  Solver solver = Solver::kNone;
  bool planar = false;
  int64_t intersecting_pairs = -1;  // -1: not checked
  Stats stats;
};

// The result's loops as ValidateSurface takes them: Result::polygon cut by
// Result::loop_sizes (one loop: the polygon).
std::vector<std::vector<int32_t>> ResultLoops(const Result& r);

// Bytes the solvers' adjacency and DP tables of a search space of `triangles`
// candidates need (DOT2 when `bi_triangle`).
int64_t EstimateTableBytes(int64_t triangles, bool bi_triangle);

}  // namespace dot

#endif  // DOT_PROBLEM_H_

// SPDX-License-Identifier: AGPL-3.0-or-later
// Filling the holes of a triangle mesh (the paper's Figure 10): each hole is
// triangulated by DOT with the surrounding faces in the metric, then refined
// (Liepa) and faired (Laplacian energy), and checked for intersections.
//
// A staircase of entry points, each usable alone:
//   FindHoleLoops     every border cycle, split into simple loops, oriented
//                     so that a fill face agrees with its neighbours;
//   (selection)       which loops to fill: FillOptions::selection;
//   GroupHoleLoops    which loops one patch joins (a hole's rim and the
//                     rims of its islands);
//   TriangulateHole   one hole's loops -> a patch (DOT, escalating to edge
//                     protection, then to all triangles for small holes or
//                     every triangle with the Delaunay ones first for
//                     large single-loop ones);
//   RefineAndFairPatch  Liepa refinement and fairing of one patch (CGAL);
//   FillHoles         all of the above over a whole mesh, holes in parallel;
//   FillSoup          repair a polygon soup, then FillHoles (dot/fill_soup.h:
//                     the use case behind the FillHoles RPC and dotctl).
//
// The contract: input vertices keep their order and exact coordinates; new
// vertices follow them. Input faces are kept, except the faces across a
// boundary edge that edge protection split, which are replaced by their
// pieces. A hole that cannot be filled without an intersection is left open
// and reported, never filled with an intersecting patch.
#ifndef DOT_FILL_HOLES_H_
#define DOT_FILL_HOLES_H_

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "dot/geometry.h"
#include "dot/io.h"
#include "dot/metrics.h"
#include "dot/status.h"
#include "dot/triangulate.h"

namespace dot {

// A simple closed loop of border vertices.
struct HoleLoop {
  int32_t id = 0;                 // position in FindHoleLoops' answer
  std::vector<int32_t> vertices;  // mesh vertex ids, in fill order
  // Per loop edge (vertices[i], vertices[i+1 mod n]): the mesh face across.
  std::vector<int32_t> faces;
  int32_t border = 0;    // the border walk it was split from
  bool pinched = false;  // shares a vertex with another loop
  double diameter = 0;   // bounding-box diagonal of its vertices
};

// Every border cycle of an edge-manifold, consistently oriented mesh, each
// split at repeated vertices into simple loops. Loops run against the
// border half-edges of their faces, so a patch oriented by the loop agrees
// with its neighbours. kInvalidArgument names a non-manifold edge, or a
// vertex that starts more than kMaxBorderEdgesAtVertex border edges.
inline constexpr size_t kMaxBorderEdgesAtVertex = 64;
Status FindHoleLoops(const MeshData& mesh, std::vector<HoleLoop>* loops,
                     const Control& control = {});

// Which loops FillHoles fills. Every field, its meaning and default:
//  max_edges     only loops with at most this many edges; 0: any. Default 0.
//  max_diameter  only loops whose bounding-box diagonal is at most this;
//                0: any. Default 0.
//  skip_longest  leave the border with the most edges open (the outer rim
//                of a terrain or of an open surface). Default false.
//  ids           only these loop ids (HoleLoop::id); empty: every loop.
//  through_vertices  only the loops through one of these vertices (a
//                cursor or a selection in a modeling tool names loops this
//                way); a vertex on no loop is refused. Empty: every loop.
//  through_names how the refusal names through_vertices[k] (the caller's
//                own ids, before a repair renumbered them); empty: by the
//                ids themselves.
// A loop is filled when it passes every criterion given.
struct HoleSelection {
  int max_edges = 0;
  double max_diameter = 0;
  bool skip_longest = false;
  std::vector<int32_t> ids;
  std::vector<int32_t> through_vertices;
  std::vector<int32_t> through_names;
};

// Holes with islands: a hole's border may be several loops, its rim and
// the rims of islands (pieces of surface floating inside it); one patch of
// genus 0 joins them (Triangulate over several loops, each loop keeping its
// direction, so the patch agrees with the faces around every loop).
//  kAuto  loop I is an island of loop R when I is the outer border (the
//         widest loop, by bounding-box diagonal) of a piece of the mesh
//         (faces joined by shared vertices) with fewer faces than R's
//         piece, R is wider than I, R's bounding box grown by a quarter of
//         R's diameter each way holds the centre of I's vertices, and among
//         the 16 narrowest such loops R is the nearest to I (mean distance
//         from I's vertices to R's, sampled, at most R's diameter). A
//         piece's other loops are its
//         own holes (the inner rim of a ring-shaped island), and a loop
//         that is an island is never a rim. Topology and distance rather
//         than a projection: a hole that wraps a limb has a rim far from
//         planar, around its island in no single view.
//  kOff   every loop is a hole of its own.
enum class IslandMode { kAuto, kOff };
std::string_view IslandModeName(IslandMode m);  // "auto", "off"

// Per loop (HoleLoop::id), the id of the loop whose patch fills it: itself
// for a hole's rim, the rim for an island. Groups in `join` (loop ids,
// each group filled by one patch whose widest loop is the rim) come first
// and are never regrouped; then `mode` groups the others. kInvalidArgument
// names a group with an unknown or repeated id, fewer than 2 loops, or
// loops sharing a vertex.
Status GroupHoleLoops(const MeshData& mesh, const std::vector<HoleLoop>& loops,
                      IslandMode mode,
                      const std::vector<std::vector<int32_t>>& join,
                      std::vector<int32_t>* rim, const Control& control = {});

enum class FillStage { kTriangulate, kRefine, kFair };
std::string_view FillStageName(FillStage s);  // "triangulate", ...

// How FillHoles works. Every field, its meaning and default:
//  weights          metric weights of the DOT patch. Default: squared
//                   dihedral 1 (with the faces around the hole: the patch
//                   meets them smoothly) plus area 0.01. When
//                   scale_free_weights, the area weight is per squared mean
//                   boundary edge length and the perimeter weight per mean
//                   boundary edge length of each hole, so one set of
//                   weights suits holes of every size.
//  scale_free_weights  Default true.
//  triangulate      options of each hole's Triangulate (search space,
//                   backend, memory budget, ...). Default: Options{}, with
//                   space kDelaunay (the escalation below replaces kAuto).
//  all_space_max_vertices  last resort for holes of at most this many
//                   vertices: the optimum over all triangles, accepted only
//                   when it intersects nothing. Default 40. Larger holes of
//                   one loop, up to triangulate.delaunay_first_max_vertices
//                   (2,000), end with SearchSpace::kDelaunayFirst instead,
//                   accepted the same way.
//  stage            kTriangulate, kRefine (Liepa refinement) or kFair
//                   (refinement and fairing). Default kFair.
//  density          Liepa's density control factor: refinement stops when
//                   patch triangles are as dense as the surrounding mesh
//                   times this. Default sqrt(2).
//  fairing_continuity  0, 1 or 2: minimizes the Laplacian energy of order
//                   1, 2 or 3 (membrane, thin plate, minimum variation).
//                   Default 1.
//  selection        which holes (above). A hole with islands is selected
//                   by its rim: the islands come with it, whatever their
//                   own sizes.
//  islands          how loops are grouped into holes with islands
//                   (IslandMode above). Default kAuto.
//  join             groups of loop ids, each filled by one patch (joining
//                   two borders of one piece, or islands kAuto misses).
//                   Default none.
//  threads          holes solved at once; 0: all cores. Default 0.
//  repair           FillSoup only: repair the soup first (merge duplicate
//                   vertices, drop degenerate and duplicate faces, orient);
//                   false: only triangulate its polygons. Default true.
//  keep_polygons    FillSoup only: give the result as SoupFillResult::soup,
//                   shaped as the soup was sent: its polygons kept where no
//                   patch split them (fill.mesh is moved there). false: the
//                   triangles of fill.mesh. Either way the soup's attribute
//                   channels (normals, colours, UVs, ...) are carried and
//                   interpolated into every new corner (see fill_soup.h).
//                   Default false.
//  allow_input_intersections  a hole every patch of which meets the mesh
//                   is filled anyway when the input already intersects
//                   itself near it (pairs among the mesh faces whose
//                   boxes meet the patch's) and the patch meets neither
//                   itself nor its own split faces: its report keeps
//                   intersecting_pairs (with the patch) and
//                   input_pairs_near (those the input had), and its
//                   reason says so. For meshes cut where they cross
//                   themselves, where no patch can avoid them. Default
//                   false: such holes stay open.
//  dry_run          find and select the holes, fill none: every selected
//                   hole is reported kListed with its size, the mesh is
//                   returned unchanged. Default false.
struct FillOptions {
  MetricWeights weights = DefaultFillWeights();
  bool scale_free_weights = true;
  Options triangulate = DefaultTriangulateOptions();
  int all_space_max_vertices = 40;
  FillStage stage = FillStage::kFair;
  double density = 1.4142135623730951;
  int fairing_continuity = 1;
  HoleSelection selection;
  IslandMode islands = IslandMode::kAuto;
  std::vector<std::vector<int32_t>> join;
  int threads = 0;
  bool repair = true;
  bool keep_polygons = false;
  bool allow_input_intersections = false;
  bool dry_run = false;

  static MetricWeights DefaultFillWeights();
  static Options DefaultTriangulateOptions();
};

// kListed: selected but not filled, because FillOptions::dry_run.
// kStopped: selected, but the fill stopped (cancel, deadline) before this
// hole was finished; its reason says whether it had started.
enum class HoleStatus {
  kFilled,
  kSkipped,
  kNoTriangulation,
  kFailed,
  kListed,
  kStopped
};
std::string_view HoleStatusName(HoleStatus s);  // "filled", ...

// Which search step produced a hole's patch.
enum class Escalation {
  kNone,
  kDelaunay,
  kProtectedEdges,
  kAllTriangles,
  kDelaunayFirst
};
std::string_view EscalationName(Escalation e);

struct HoleReport {
  int32_t id = 0;
  int32_t boundary_vertices = 0;
  bool pinched = false;
  // Holes with islands: on the rim, the ids of the island loops its patch
  // joins (boundary_vertices counts the rim alone); on an island, the rim's
  // id (its status is the rim's), else -1.
  std::vector<int32_t> joined;
  int32_t joined_to = -1;
  // The loop's size and place, in the mesh's units: its bounding-box
  // diagonal, its length, and the centroid of its edges (length-weighted).
  double diameter = 0, perimeter = 0;
  Vec3 centroid;
  HoleStatus status = HoleStatus::kSkipped;
  std::string reason;  // why skipped / not filled / failed; fairing notes
  Escalation escalation = Escalation::kNone;
  SpaceUsed space = SpaceUsed::kNone;
  Solver solver = Solver::kNone;
  int32_t boundary_inserted = 0;  // vertices edge protection added
  // Escalation::kDelaunayFirst: DOT patch triangles that are not Delaunay.
  int32_t non_delaunay_triangles = 0;
  std::vector<int32_t> split_faces;  // input faces replaced by their pieces
  int32_t patch_triangles = 0;
  int32_t refined_vertices = 0;  // interior vertices refinement added
  bool faired = false;           // fairing ran and was kept
  double cost = 0;               // the DOT patch's weighted cost
  // Of the kept patch with itself and the mesh: 0 when filled, unless
  // FillOptions::allow_input_intersections filled it over an input that
  // already intersects itself, with input_pairs_near such pairs among the
  // mesh faces near the patch.
  int64_t intersecting_pairs = 0;
  int64_t input_pairs_near = 0;
  double triangulate_ms = 0, refine_ms = 0, fair_ms = 0, check_ms = 0;
};

struct FillReport {
  std::vector<HoleReport> holes;  // one per loop, by id
  int32_t loops = 0, filled = 0, skipped = 0, unfilled = 0;
  int32_t listed = 0;   // dry_run: selected, not filled
  int32_t stopped = 0;  // kStopped: the fill stopped before them
  int32_t added_vertices = 0, added_faces = 0;
  bool closed = false;  // no border edge left
  double total_ms = 0;
};

// One filled hole before it is merged into the mesh: faces over mesh ids,
// where ids >= first_new_id index `new_vertices`.
struct HolePatch {
  std::vector<Vec3> new_vertices;
  std::vector<Triangle> faces;
  // Replacement of each split input face (split_faces[k] -> pieces[k]).
  std::vector<int32_t> split_faces;
  std::vector<std::vector<Triangle>> pieces;
};

// A hole as it was merged into FillResult::mesh: its patch in the result's
// ids (new_vertices[k] is mesh vertex first_vertex + k).
struct FilledHole {
  int32_t hole = 0;  // HoleReport::id
  int32_t first_vertex = 0;
  HolePatch patch;
};

// `status` is kOk when every selected hole was tried, even when some stay
// open (see report). When the fill stops early (cancel, deadline, an
// error of one hole) after finishing some holes, nothing done is thrown
// away: `partial` is set, status says why it stopped (a cancel or the
// deadline rather than one hole's error), and mesh, report and patches
// hold every hole finished before the stop, in a valid mesh; the others
// are reported kStopped. Not OK and not partial: nothing to keep (the
// options, the mesh, a stop before any hole was finished, or
// Control::keep_partial said no).
struct FillResult {
  Status status;
  bool partial = false;
  MeshData mesh;  // input vertices first, unchanged; then new ones
  FillReport report;
  // What is new in `mesh`, hole by hole (in merge order, which is id
  // order): for callers that keep their mesh and add only the patches.
  std::vector<FilledHole> patches;
};

// The per-hole stages, for callers that drive them (and for tests). The
// mesh must be the one FindHoleLoops ran on; `topology` is built once.
struct MeshTopology;  // vertex -> faces, vertex -> neighbours
std::shared_ptr<const MeshTopology> BuildMeshTopology(const MeshData& mesh);

// DOT over the loop, with the faces across its edges in the bi-triangle
// metrics and the loop's existing mesh edges forbidden as chords. Fills
// report's escalation, space, solver, cost, boundary_inserted, split_faces.
// Patch ids: mesh ids, then first_new_id + k for patch->new_vertices[k].
Status TriangulateHole(const MeshData& mesh, const MeshTopology& topology,
                       const HoleLoop& loop, const FillOptions& options,
                       const Control& control, int32_t first_new_id,
                       HolePatch* patch, HoleReport* report);
// The same over a hole with islands: one patch of genus 0 bounded by every
// loop of `loops` (the rim first), each run in its direction; `avoid`
// forbids more chords (mesh vertex id pairs; FillHoles passes those of
// patch faces that met the mesh).
Status TriangulateHole(
    const MeshData& mesh, const MeshTopology& topology,
    const std::vector<const HoleLoop*>& loops, const FillOptions& options,
    const Control& control, int32_t first_new_id, HolePatch* patch,
    HoleReport* report,
    const std::vector<std::pair<int32_t, int32_t>>& avoid = {});

// Liepa refinement and, for FillStage::kFair, fairing of the patch's new
// interior vertices (CGAL PMP on the patch and three rings of faces around
// it). Fairing that fails or creates an intersection is undone (report says
// so).
Status RefineAndFairPatch(const MeshData& mesh, const MeshTopology& topology,
                          const FillOptions& options, const Control& control,
                          int32_t first_new_id, HolePatch* patch,
                          HoleReport* report);

// Intersecting pairs of patch faces with each other and with the mesh faces
// near the patch (exact predicates), into `pairs`; stops when `control`
// says so. IntersectingChords: the interior edges between mesh vertices of
// the patch faces in such pairs, each once (`own_only`: in pairs with
// other patch faces or the split faces' pieces alone).
Status PatchIntersections(const MeshData& mesh, const MeshTopology& topology,
                          int32_t first_new_id, const HolePatch& patch,
                          const Control& control, int64_t* pairs);
Status IntersectingChords(const MeshData& mesh, const MeshTopology& topology,
                          int32_t first_new_id, const HolePatch& patch,
                          const Control& control,
                          std::vector<std::pair<int32_t, int32_t>>* chords,
                          bool own_only = false);
// For FillOptions::allow_input_intersections, the crossings of a patch and
// of the mesh faces near it (those whose boxes meet the patch's): the
// patch's with itself and its split faces' pieces (`own_pairs`, never
// allowed), the input's own among those faces (`input_pairs`), the patch's
// with the mesh (`patch_pairs`), and of those the pairs whose mesh face
// lies more than kCrossingRings rings of faces from every face of an input
// pair (`away_pairs`: the patch would cross the mesh where it is sound).
inline constexpr int kCrossingRings = 3;
struct InputCrossings {
  int64_t own_pairs = 0, input_pairs = 0, patch_pairs = 0, away_pairs = 0;
};
Status InputCrossingsNear(const MeshData& mesh, const MeshTopology& topology,
                          int32_t first_new_id, const HolePatch& patch,
                          const Control& control, InputCrossings* out);

// INVALID_ARGUMENT naming the first field out of its range (weights not
// finite or all zero, density outside [0.1, 100], fairing_continuity
// outside 0..2, a negative or non-finite hole size limit, negative
// threads); FillHoles and FillSoup refuse such options with it.
Status CheckFillOptions(const FillOptions& options);

// The phases of a fill, in order, as progress reports them.
enum class FillPhase { kRepair, kLoops, kHoles, kMerge };
std::string_view FillPhaseName(FillPhase p);  // "repair", "loops", ...

// Progress of a fill: called as each phase starts and, in kHoles, after
// each selected hole, with (holes done, holes selected; 0 before kHoles).
// From the computing threads, one call at a time.
using FillProgressFn =
    std::function<void(FillPhase phase, int holes_done, int holes_total)>;

// Control's cancel and deadline are honoured in every stage up to the
// merge, which is bounded by the patches made and always runs, so that a
// stop keeps them (FillResult::partial); its progress callback is not used
// (holes run at once): `on_progress` reports the phases and holes.
FillResult FillHoles(const MeshData& mesh, const FillOptions& options = {},
                     const Control& control = {},
                     const FillProgressFn& on_progress = nullptr);
// The same, taking the mesh's arrays for the result instead of copying
// them (a scan is then held once): `mesh` is left empty.
FillResult FillHoles(MeshData&& mesh, const FillOptions& options = {},
                     const Control& control = {},
                     const FillProgressFn& on_progress = nullptr);

}  // namespace dot

#endif  // DOT_FILL_HOLES_H_

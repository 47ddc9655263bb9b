// SPDX-License-Identifier: AGPL-3.0-or-later
// Curve networks into surfaces (the paper's Figure 10): a network of 3D
// curves is split into the cycles that bound patches, each patch is
// triangulated by DOT (squared dihedral angles, with boundary normals the
// two patches on each curve share), refined (Liepa) and the whole network
// is faired at once with every curve vertex fixed.
//
// A staircase of entry points, each usable alone:
//   ReadNetworkFile    OBJ 'v'/'l' lines or text blocks -> CurveNetwork;
//   BuildNetworkGraph  welds equal points (and stroke ends that nearly
//                      meet, when asked), splits polylines into curves
//                      between junctions, refuses duplicate and crossing
//                      curves, sets dangling curves apart;
//   FindNetworkCycles  the cycles that bound patches, from a rotation
//                      system at the junctions (any genus, no planarity
//                      assumption; manifold networks), or
//   CyclesFromVertices the cycles a user gives as vertex lists;
//   SurfaceNetwork     all of the above, then the surface: one mesh.
//
// The contract: the mesh's first vertices are the network's, every one in
// its order at its exact coordinates (a point welded to an earlier copy is
// left unused: SurfaceResult::vertex_of_input), then the new ones; every
// curve edge of a surfaced patch is a mesh edge; no face crosses another
// (checked with exact predicates after every step), no edge but a curve's
// has more than two faces, and the patches are consistently oriented, so
// the mesh of a manifold network is edge-manifold (given cycles where three
// patches meet on a curve make it non-manifold there, and the report
// counts those curves). A patch that cannot be surfaced without breaking
// that is left out and reported, never included.
#ifndef DOT_NETWORK_H_
#define DOT_NETWORK_H_

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "dot/control.h"
#include "dot/fill_holes.h"
#include "dot/geometry.h"
#include "dot/mesh.h"
#include "dot/problem.h"
#include "dot/status.h"

namespace dot {

// Polylines over shared points, as a file gives them.
struct CurveNetwork {
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;  // empty, or one surface normal per vertex
  std::vector<std::vector<int32_t>> polylines;  // vertex ids, >= 2 each
};

// Network files, by extension:
//  - .obj: 'v' lines and 'l' polylines (1-based, negative from the end;
//    'l a/t b/t' texture indices ignored), one per curve or one per edge
//    ('l a b') as Blender writes them; 'vn' lines, one per 'v', are surface
//    normals. Faces ('f') are refused: the file is a mesh, not a network.
//  - anything else, text: one point a line, "x y z" or "x y z nx ny nz";
//    a blank line ends a polyline; '#' starts a comment.
// Polylines meet where they share a vertex or its exact coordinates; a
// polyline whose last point repeats its first is a closed curve. Errors
// name the file and line.
Status ReadNetworkFile(const std::string& path, CurveNetwork* out);
Status ReadNetworkObj(std::istream& in, CurveNetwork* out);
Status ReadNetworkText(std::istream& in, CurveNetwork* out);
// OBJ 'v' (and 'vn') and 'l' lines, one per polyline.
Status WriteNetworkObj(std::ostream& out, const CurveNetwork& network);

// A curve: a path of edges between two junctions (vertices where other
// than two edges meet), or a closed loop (first == last vertex).
struct NetworkCurve {
  std::vector<int32_t> vertices;  // graph vertex ids, >= 2
  bool closed() const { return vertices.front() == vertices.back(); }
};

// The network as a graph of curves. Vertices are the input's points that
// lie on a polyline, welded (BuildNetworkGraph), in input order.
struct NetworkGraph {
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;             // empty or one per vertex
  std::vector<int32_t> vertex_of_input;  // input id -> vertex id, -1: unused
  std::vector<int32_t> input_of_vertex;  // vertex id -> first input id
  std::vector<NetworkCurve> curves;      // in order of their first edges
  // Curves with an end no other curve meets (and curves only they reach),
  // pruned repeatedly: they bound no patch. Sorted ids.
  std::vector<int32_t> dangling;
  int32_t merged_vertices = 0;  // input points welded to an earlier one
  int32_t welded_edges = 0;     // edges whose two ends were welded: gone
};

// kInvalidArgument names what is not a network: an id out of range, a
// non-finite coordinate or one beyond 1e100 in magnitude, a polyline of fewer
// than 2 points, an edge from a point to itself, two polylines along one edge
// (duplicate curves), or two curves that cross or touch away from a shared
// vertex (exact predicates). Points are welded where their coordinates are
// equal, and with `weld_distance` > 0 a free end (a point with one edge;
// repeated points make none) with the nearest point within that distance
// of it not on its own stroke (the polylines it runs on through points of
// two edges; or the stroke's other end: drawn closed) nor beside the
// junction it starts from, transitively (a stub from a junction within the
// distance stays, dangling): strokes whose ends fall
// short of or past another stroke meet it there, and a stroke's inner
// points never weld to each other. Each group is welded into its first point;
// an edge whose ends are welded together is dropped (welded_edges). A distance
// that puts more than 2e8 pairs side by side is refused.
Status BuildNetworkGraph(const CurveNetwork& network, NetworkGraph* out,
                         const Control& control = {}, double weld_distance = 0);
// kInvalidArgument unless `weld_distance` is a finite number >= 0.
Status CheckWeldDistance(double weld_distance);

// One run of a curve in a cycle: the curve, and whether it is run from its
// last vertex to its first.
struct CurveUse {
  int32_t curve = 0;
  bool reversed = false;
};

// A patch's boundary: one loop of curve uses, or several (a patch with
// islands: the multi-loop solver joins them).
struct NetworkCycle {
  std::vector<std::vector<CurveUse>> loops;
  // Found as a wall (CycleOptions::walls): a third patch on its curves,
  // facing either way, left out of the shared normals and of which way a
  // closed surface faces.
  bool wall = false;
};

// The graph vertices of a loop in order, its first junction once.
std::vector<int32_t> LoopVertices(const NetworkGraph& graph,
                                  const std::vector<CurveUse>& loop);

// What a lone loop (a cycle alone in its part of the network: a closed
// curve drawn on its own) bounds when it lies in a face of another part
// (seen along that face's normal, every point inside the face's outer loop
// and near its plane; nested loops pair inward):
//  kInset  an island of that face (a second loop of its patch: the
//          multi-loop solver) and a patch of its own, facing as the face
//          does: a curve drawn on a face, the surface stays closed.
//  kHole   an island of that face only: a hole in it.
//  kOff    a patch of its own only (it overlaps the face around it: the
//          crossing checks keep the two apart or leave one out).
// A lone loop in no face (a tube's two rims, a loop in space) is a patch of
// its own whatever the mode; give a tube as a cycle of two loops. Ignored
// when the cycles are given.
enum class NetworkIslands { kInset, kHole, kOff };
std::string_view NetworkIslandsName(NetworkIslands m);  // "inset", ...

// How FindNetworkCycles reads what a rotation system leaves open:
//  islands  lone loops in a face (above). Default kInset.
//  walls    also find walls: flat cycles that make a third patch on their
//           curves (a partition inside a box). A ring of curves around a
//           body is either a wall or only the line between two patches (a
//           belt, a sketch's cross-section), and the curves alone cannot
//           tell: walls are found only when asked. A wall turns, at each
//           junction, between two curves no face found turns between (so
//           only at junctions of four curves or more), has at most 8
//           curves, lies flat (within 5 % of its radius of its plane) and
//           holds no other point of the network (vertex or edge
//           midpoint); smallest first, each such corner in one wall.
//           Default false.
struct CycleOptions {
  NetworkIslands islands = NetworkIslands::kInset;
  bool walls = false;
};

// The cycles of a rotation system: at each junction the curves are ordered
// around a normal (given, or fitted to the curves' directions, signs made
// to agree across the network by the normals carried along the curves,
// then by the faces: more simple faces and more faces, and where that
// leaves a choice, faces that cost less as DOT patches), and each face of
// that embedding is a cycle, so every curve that is not dangling bounds two
// patches, one on each side, the cycles consistently oriented. A closed
// curve alone (no junction) bounds one patch. Manifold networks of any
// genus; where three patches meet on one curve, walls (CycleOptions) or
// CyclesFromVertices. A face that runs a path of curves one way and then
// back (a tube's seam, a curve from a hole to its rim) is a cycle too:
// SurfaceNetwork cuts it in two pieces by a new path whose points are new,
// faired vertices. Then walls and islands as `options` say. `notes`
// receives the faces left out (others that run a curve twice), the walls,
// the islands paired, and a search by cost cut short.
Status FindNetworkCycles(const NetworkGraph& graph,
                         std::vector<NetworkCycle>* cycles,
                         std::vector<std::string>* notes = nullptr,
                         const Control& control = {},
                         const CycleOptions& options = {});

// Cycles a user gives: per patch, loops of input vertex ids (as
// CurveNetwork numbers them), each loop listing the vertices in order;
// consecutive listed vertices must be joined by a curve (listing only the
// junctions suffices where one curve joins them). The loops of one patch
// run as its boundary does, the surface on their left (a tube's two rims
// against each other), and two patches that share a curve run it once each
// way. kInvalidArgument names the patch, loop and vertices that do not
// form a cycle, a repeated cycle, or two cycles that run a shared curve the
// same way.
Status CyclesFromVertices(
    const NetworkGraph& graph,
    const std::vector<std::vector<std::vector<int32_t>>>& patches,
    std::vector<NetworkCycle>* cycles, const Control& control = {});

// How SurfaceNetwork works. Every field, its meaning and default:
//  weights          metric weights of each DOT patch. Default: squared
//                   dihedral 1 and normal deviation 0.25 (against the
//                   boundary normals the patches on each curve share), area
//                   0.01. When scale_free_weights, the area weight is per
//                   squared mean edge length and the perimeter weight per
//                   mean edge length of each cycle.
//  scale_free_weights  Default true.
//  triangulate      options of each patch's Triangulate. Default: space
//                   kDelaunay (a patch with no Delaunay triangulation tries
//                   kDelaunayFirst, up to its vertex limit).
//  stage            kTriangulate, kRefine or kFair. Default kFair.
//  density          Liepa's density control factor for refinement, as
//                   FillOptions::density. Default sqrt(2).
//  fairing_continuity  0, 1 or 2 (membrane, thin plate, minimum
//                   variation), over the whole network at once: free
//                   vertices on both sides of a curve are in one system,
//                   so patches meet without a crease unless the curve
//                   bends. Default 1.
//  cycles           patches given by the user (CyclesFromVertices); empty:
//                   FindNetworkCycles.
//  skip_longest     leave out the automatic cycle whose outer loop has the
//                   most vertices (the outer rim of an open sheet; the
//                   first of equals; never an island's own patch). Default
//                   false.
//  islands          lone loops in a face of the automatic cycles (above):
//                   kInset, kHole or kOff. Default kInset.
//  walls            also find walls among the automatic cycles
//                   (CycleOptions). Default false.
//  weld_distance    stroke ends are welded to the nearest point within this
//                   distance (network units; BuildNetworkGraph says
//                   which): for sketched strokes whose ends nearly meet.
//                   Default 0: only points at exactly the same place.
//  threads          patches solved at once; 0: all cores. Default 0.
struct SurfaceOptions {
  MetricWeights weights = DefaultSurfaceWeights();
  bool scale_free_weights = true;
  Options triangulate = FillOptions::DefaultTriangulateOptions();
  FillStage stage = FillStage::kFair;
  double density = 1.4142135623730951;
  int fairing_continuity = 1;
  std::vector<std::vector<std::vector<int32_t>>> cycles;
  bool skip_longest = false;
  NetworkIslands islands = NetworkIslands::kInset;
  bool walls = false;
  double weld_distance = 0;
  int threads = 0;

  static MetricWeights DefaultSurfaceWeights();
};

// kInvalidArgument naming the first field out of range.
Status CheckSurfaceOptions(const SurfaceOptions& options);

// A stop (cancel, deadline) ends the call: no patch is reported stopped.
enum class PatchStatus { kSurfaced, kFailed, kSkipped };
std::string_view PatchStatusName(PatchStatus s);  // "surfaced", ...

struct PatchReport {
  int32_t id = 0;
  std::vector<std::vector<CurveUse>> loops;         // its cycle
  std::vector<std::vector<int32_t>> loop_vertices;  // input ids, per loop
  int32_t boundary_vertices = 0;
  PatchStatus status = PatchStatus::kSkipped;
  std::string reason;  // why failed or skipped; what was undone
  SpaceUsed space = SpaceUsed::kNone;
  Solver solver = Solver::kNone;
  double cost = 0;       // the DOT patch's weighted cost
  int32_t resolves = 0;  // re-solves forbidding chords that met others
  // DOT found nothing that meets the rest only where it should: a fan
  // from a new vertex at the loop's centroid (reason says why).
  bool fan = false;
  int32_t triangles = 0;  // in the output
  int32_t refined_vertices = 0;
  bool faired = false;  // its vertices moved by the network's fairing
  double triangulate_ms = 0, refine_ms = 0;
};

struct SurfaceReport {
  int32_t curves = 0, junctions = 0, merged_vertices = 0;
  // Per curve (as CurveUse numbers them), its vertices in input ids.
  std::vector<std::vector<int32_t>> curve_vertices;
  std::vector<int32_t> dangling;  // curve ids
  std::vector<std::string> notes;
  std::vector<PatchReport> patches;  // one per cycle
  int32_t surfaced = 0, failed = 0;
  // Every curve that is not dangling borders two surfaced patches or more
  // (more: a non-manifold network, whose mesh is then non-manifold along
  // those curves, counted in non_manifold_curves).
  bool closed = false;
  int32_t non_manifold_curves = 0;
  // Fairing: whether it ran over the whole network (false: per patch, or
  // not at all), and the patches whose fairing was undone.
  bool faired_whole = false;
  int64_t intersecting_pairs = 0;  // of the output: 0
  double cycles_ms = 0, triangulate_ms = 0, refine_ms = 0, fair_ms = 0,
         check_ms = 0, total_ms = 0;
};

// Progress: after the cycles (0 of n) and after each patch triangulated.
using SurfaceProgressFn = std::function<void(int patches_done, int total)>;

struct SurfaceResult {
  Status status;
  MeshData mesh;  // the network's vertices first, then new ones
  SurfaceReport report;
  // Per input vertex: the mesh vertex its faces use (itself, or the
  // earlier copy it was welded to); -1: on no polyline.
  std::vector<int32_t> vertex_of_input;
};

// Never throws (out of memory is kResourceExhausted). Not OK: the network,
// the options, or a stop (cancel, deadline; nothing kept). OK with patches
// kFailed: the surface without them (report.closed false).
SurfaceResult SurfaceNetwork(const CurveNetwork& network,
                             const SurfaceOptions& options = {},
                             const Control& control = {},
                             const SurfaceProgressFn& on_progress = nullptr);

}  // namespace dot

#endif  // DOT_NETWORK_H_

// SPDX-License-Identifier: AGPL-3.0-or-later
// FillHoles: find loops -> select -> per hole (in parallel) triangulate ->
// refine and fair -> check -> merge into the mesh in hole order.
#include "dot/fill_holes.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <thread>
#include <unordered_map>
#include <unordered_set>

#include "fill/patch_check.h"
#include "mesh/edge_index.h"
#include "mesh/topology.h"
#include "util/run_control.h"

namespace dot {
namespace {

using Clock = std::chrono::steady_clock;

Status CheckMesh(const MeshData& mesh, RunTicker* ticker) {
  if (mesh.triangles.empty()) return InvalidArgument("the mesh has no faces");
  for (size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (!ticker->Tick()) return ticker->status();
    if (!IsFinite(mesh.vertices[v])) {
      return InvalidArgument("vertex " + std::to_string(v) +
                             " has a non-finite coordinate");
    }
  }
  const auto nv = static_cast<int64_t>(mesh.vertices.size());
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (!ticker->Tick()) return ticker->status();
    const Triangle& t = mesh.triangles[f];
    for (int32_t v : t) {
      if (v < 0 || v >= nv) {
        return InvalidArgument("face " + std::to_string(f) +
                               " has vertex index " + std::to_string(v) +
                               ", outside 0.." + std::to_string(nv - 1));
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      return InvalidArgument("face " + std::to_string(f) +
                             " repeats a vertex (" + std::to_string(t[0]) +
                             ", " + std::to_string(t[1]) + ", " +
                             std::to_string(t[2]) + ")");
    }
  }
  return OkStatus();
}

// Why a loop is not filled, or "" when it is selected; `ids` that name no
// loop are refused (a typo must not pass as "nothing to fill").
Status Select(const std::vector<HoleLoop>& loops, const HoleSelection& sel,
              std::vector<std::string>* reasons) {
  std::vector<std::string>& why = *reasons;
  why.assign(loops.size(), "");
  // Membership by flag, not by search: ids may be repeated millions of
  // times.
  std::vector<bool> wanted(sel.ids.empty() ? 0 : loops.size(), false);
  for (int32_t id : sel.ids) {
    if (id < 0 || static_cast<size_t>(id) >= loops.size()) {
      return InvalidArgument(
          "there is no hole " + std::to_string(id) + ": the mesh has " +
          std::to_string(loops.size()) + " holes" +
          (loops.empty() ? std::string()
                         : ", ids 0.." + std::to_string(loops.size() - 1)));
    }
    wanted[id] = true;
  }
  // A loop passes through a named vertex: flags by vertex, then by loop.
  std::vector<bool> through(sel.through_vertices.empty() ? 0 : loops.size(),
                            false);
  if (!sel.through_vertices.empty()) {
    std::unordered_map<int32_t, std::vector<int32_t>> loops_at;
    for (const HoleLoop& l : loops) {
      for (int32_t v : l.vertices) loops_at[v].push_back(l.id);
    }
    for (size_t k = 0; k < sel.through_vertices.size(); ++k) {
      const int32_t v = sel.through_vertices[k];
      auto it = loops_at.find(v);
      if (it == loops_at.end()) {
        const int32_t name =
            k < sel.through_names.size() ? sel.through_names[k] : v;
        return InvalidArgument("loops_through: vertex " + std::to_string(name) +
                               " is on no border loop of the mesh");
      }
      for (int32_t id : it->second) through[id] = true;
    }
  }
  int32_t longest = -1;
  if (sel.skip_longest) {
    std::map<int32_t, size_t> edges;
    for (const HoleLoop& l : loops) edges[l.border] += l.vertices.size();
    size_t most = 0;
    for (const auto& [border, count] : edges) {
      if (count > most) most = count, longest = border;
    }
  }
  for (size_t i = 0; i < loops.size(); ++i) {
    const HoleLoop& l = loops[i];
    const auto n = static_cast<int>(l.vertices.size());
    if (!sel.ids.empty() && !wanted[l.id]) {
      why[i] = "not among the requested holes";
    } else if (!through.empty() && !through[l.id]) {
      why[i] = "through none of the requested vertices";
    } else if (l.border == longest) {
      why[i] = "the longest border (skip_longest)";
    } else if (sel.max_edges > 0 && n > sel.max_edges) {
      why[i] = std::to_string(n) + " edges, more than max_edges " +
               std::to_string(sel.max_edges);
    } else if (sel.max_diameter > 0 && l.diameter > sel.max_diameter) {
      why[i] = "diameter " + std::to_string(l.diameter) +
               " exceeds max_diameter " + std::to_string(sel.max_diameter);
    }
  }
  return OkStatus();
}

// The loop's length and the centroid of its edges, each edge weighted by
// its length (a loop's vertices may crowd on one side).
void Measure(const MeshData& mesh, const HoleLoop& loop, HoleReport* r) {
  const size_t n = loop.vertices.size();
  Vec3 sum;
  double length = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec3& a = mesh.vertices[loop.vertices[i]];
    const Vec3& b = mesh.vertices[loop.vertices[(i + 1) % n]];
    const double l = Norm(b - a);
    sum = sum + (0.5 * l) * (a + b);
    length += l;
  }
  r->perimeter = length;
  if (length > 0) {
    r->centroid = (1.0 / length) * sum;
  } else if (n > 0) {
    r->centroid = mesh.vertices[loop.vertices[0]];
  }
}

bool AllFinite(const std::vector<Vec3>& points) {
  return std::all_of(points.begin(), points.end(),
                     [](const Vec3& p) { return IsFinite(p); });
}

struct HoleWork {
  HolePatch patch;
  HoleReport report;
  Status status;         // cancel / deadline / resource: stops the fill
  bool started = false;  // the stop came after its work began
};

// Why a hole was stopped, as its reason says it.
std::string StopCause(const Status& s) {
  switch (s.code) {
    case StatusCode::kCancelled:
      return "the fill was cancelled";
    case StatusCode::kDeadlineExceeded:
      return "the fill ran out of time";
    default:
      return s.message;
  }
}

// One attempt at a hole (a rim and its islands, or one loop) with the
// chords `avoid` forbidden: triangulate, refine and fair, check. When every
// patch intersects the mesh, `met` is the DOT patch (else empty).
void FillAttempt(const MeshData& mesh, const MeshTopology& topo,
                 const std::vector<const HoleLoop*>& loops,
                 const FillOptions& options, const Control& control,
                 const std::vector<std::pair<int32_t, int32_t>>& avoid,
                 HoleWork* w, HolePatch* met) {
  *met = {};
  const auto first_new = static_cast<int32_t>(mesh.vertices.size());
  HoleReport& r = w->report;
  RunTicker ticker(control, Stage::kValidate);
  if (!ticker.Poll()) {  // a cancel skips the holes not yet started
    w->status = ticker.status();
    return;
  }
  w->started = true;
  auto t0 = Clock::now();
  Status s = TriangulateHole(mesh, topo, loops, options, control, first_new,
                             &w->patch, &r, avoid);
  r.triangulate_ms = MsSince(t0);
  if (s.code == StatusCode::kCancelled ||
      s.code == StatusCode::kDeadlineExceeded) {
    w->status = s;
    return;
  }
  if (!s.ok()) {
    r.status = s.code == StatusCode::kNoTriangulation
                   ? HoleStatus::kNoTriangulation
                   : HoleStatus::kFailed;
    r.reason = s.message;
    return;
  }
  if (!AllFinite(w->patch.new_vertices)) {  // the promise: never a NaN
    r.status = HoleStatus::kFailed;
    r.reason = "the patch has a non-finite vertex: left open";
    return;
  }
  const HolePatch dot_patch = w->patch;
  // Refinement's vertex cap follows the hole's size: every loop's vertices
  // (the report counts the rim's alone).
  const int32_t rim_vertices = r.boundary_vertices;
  for (size_t k = 1; k < loops.size(); ++k) {
    r.boundary_vertices += static_cast<int32_t>(loops[k]->vertices.size());
  }
  s = RefineAndFairPatch(mesh, topo, options, control, first_new, &w->patch,
                         &r);
  r.boundary_vertices = rim_vertices;
  if (!s.ok()) {
    w->status = s;
    return;
  }
  if (!AllFinite(w->patch.new_vertices)) {
    r.reason =
        "refinement or fairing made a non-finite vertex: kept the "
        "unrefined DOT patch";
    w->patch = dot_patch;
    r.refined_vertices = 0;
    r.faired = false;
    r.patch_triangles = static_cast<int32_t>(dot_patch.faces.size());
  }
  RunTicker ticker_check(control, "the intersection check");
  if (!ticker_check.Poll()) {
    w->status = ticker_check.status();
    return;
  }
  t0 = Clock::now();
  s = PatchIntersections(mesh, topo, first_new, w->patch, control,
                         &r.intersecting_pairs);
  if (!s.ok()) {
    w->status = s;
    return;
  }
  if (r.intersecting_pairs > 0 && options.stage != FillStage::kTriangulate) {
    // Refinement can fold a patch; the DOT patch may still be clean.
    int64_t plain = 0;
    s = PatchIntersections(mesh, topo, first_new, dot_patch, control, &plain);
    if (!s.ok()) {
      w->status = s;
      return;
    }
    if (plain == 0) {
      r.reason = "refined patch intersected the mesh (" +
                 std::to_string(r.intersecting_pairs) +
                 " pairs): kept the unrefined DOT patch";
      w->patch = dot_patch;
      r.intersecting_pairs = 0;
      r.refined_vertices = 0;
      r.faired = false;
      r.patch_triangles = static_cast<int32_t>(dot_patch.faces.size());
    }
  }
  r.check_ms = MsSince(t0);
  if (r.escalation == Escalation::kDelaunayFirst) {
    r.reason =
        "no triangulation over Delaunay triangles: every triangle, "
        "Delaunay ones first (" +
        std::to_string(r.non_delaunay_triangles) + " of " +
        std::to_string(dot_patch.faces.size()) + " not Delaunay)" +
        (r.reason.empty() ? "" : "; " + r.reason);
  }
  if (r.intersecting_pairs > 0) {
    r.status = HoleStatus::kFailed;
    r.reason = (r.escalation == Escalation::kDelaunayFirst ? r.reason + "; but "
                                                           : std::string()) +
               "every patch found intersects the mesh (" +
               std::to_string(r.intersecting_pairs) +
               " pairs of faces): left open";
    *met = dot_patch;
    return;
  }
  r.status = HoleStatus::kFilled;
}

// A hole: attempts, each forbidding the chords of the DOT patch faces that
// met the mesh in the attempts before (the optimum then routes around
// them), up to kAvoidRounds more. `failed`, when given, receives each
// attempt whose patch met the mesh; `own_only` avoids only the chords of
// faces that met the patch itself (allow_input_intersections' second try).
constexpr int kAvoidRounds = 3;

void FillAvoiding(const MeshData& mesh, const MeshTopology& topo,
                  const std::vector<const HoleLoop*>& loops,
                  const FillOptions& options, const Control& control,
                  HoleWork* w, std::vector<HoleWork>* failed,
                  bool own_only = false) {
  const auto first_new = static_cast<int32_t>(mesh.vertices.size());
  const HoleReport initial = w->report;
  std::vector<std::pair<int32_t, int32_t>> avoid;
  HolePatch met;
  FillAttempt(mesh, topo, loops, options, control, avoid, w, &met);
  auto keep_failed = [&](const HoleWork& attempt) {
    if (failed && attempt.status.ok() &&
        attempt.report.status == HoleStatus::kFailed &&
        attempt.report.intersecting_pairs > 0) {
      failed->push_back(attempt);
    }
  };
  keep_failed(*w);
  for (int round = 0;
       round < kAvoidRounds && w->status.ok() &&
       w->report.status == HoleStatus::kFailed && !met.faces.empty();
       ++round) {
    std::vector<std::pair<int32_t, int32_t>> chords;
    Status s = IntersectingChords(mesh, topo, first_new, met, control, &chords,
                                  own_only);
    if (!s.ok()) {
      w->status = s;
      return;
    }
    const size_t before = avoid.size();
    for (const auto& c : chords) {
      if (std::find(avoid.begin(), avoid.end(), c) == avoid.end()) {
        avoid.push_back(c);
      }
    }
    if (avoid.size() == before) return;
    HoleWork retry;
    retry.report = initial;
    retry.started = true;
    const double ms_before = w->report.triangulate_ms + w->report.check_ms;
    FillAttempt(mesh, topo, loops, options, control, avoid, &retry, &met);
    retry.report.triangulate_ms += ms_before;
    if (!retry.status.ok()) {
      w->status = retry.status;
      return;
    }
    if (retry.report.status == HoleStatus::kFilled) {
      const std::string own = retry.report.reason;
      retry.report.reason = "the patch avoids " + std::to_string(avoid.size()) +
                            " chords whose triangles met the mesh" +
                            (own.empty() ? "" : "; ") + own;
      *w = std::move(retry);
      return;
    }
    if (retry.report.status != HoleStatus::kFailed) return;  // keep the first
    keep_failed(retry);
    *w = std::move(retry);
  }
}

// FillOptions::allow_input_intersections: an attempt whose patch met the
// mesh is a fill when the input already intersects itself near it, every
// mesh face the patch crosses is within kCrossingRings rings of faces of
// those crossings, and the patch meets neither itself nor its split faces;
// else `why_not` says why. The check's time counts in check_ms.
bool AllowInputIntersections(const MeshData& mesh, const MeshTopology& topo,
                             const Control& control, HoleWork* w,
                             std::string* why_not) {
  HoleReport& r = w->report;
  InputCrossings c;
  const auto t0 = Clock::now();
  const Status s =
      InputCrossingsNear(mesh, topo, static_cast<int32_t>(mesh.vertices.size()),
                         w->patch, control, &c);
  r.check_ms += MsSince(t0);
  if (!s.ok()) {
    w->status = s;
    return false;
  }
  r.input_pairs_near = c.input_pairs;
  if (c.own_pairs > 0) {
    *why_not = "the patch intersects itself (" + std::to_string(c.own_pairs) +
               " pairs)";
    return false;
  }
  if (c.input_pairs == 0) {
    *why_not = "the mesh does not intersect itself near the hole";
    return false;
  }
  if (c.away_pairs > 0) {
    *why_not = "the patch would cross the mesh where it is sound (" +
               std::to_string(c.away_pairs) + " of " +
               std::to_string(c.patch_pairs) + " pairs more than " +
               std::to_string(kCrossingRings) +
               " rings of faces from the input's own crossings)";
    return false;
  }
  r.status = HoleStatus::kFilled;
  r.reason = "filled although its patch meets the mesh (" +
             std::to_string(c.patch_pairs) + " pairs of faces, each within " +
             std::to_string(kCrossingRings) +
             " rings of faces of where the input already intersects itself: " +
             std::to_string(c.input_pairs) +
             " pairs near the hole); allow_input_intersections is on";
  return true;
}

void FillOne(const MeshData& mesh, const MeshTopology& topo,
             const std::vector<const HoleLoop*>& loops,
             const FillOptions& options, const Control& control, HoleWork* w) {
  const bool allow = options.allow_input_intersections;
  const HoleReport initial = w->report;
  std::vector<HoleWork> failed;
  FillAvoiding(mesh, topo, loops, options, control, w, &failed);
  if (!w->status.ok() || w->report.status != HoleStatus::kFailed ||
      failed.empty()) {
    return;
  }
  if (!allow) {
    // What the user can do: say when the opt-in would fill the hole (a
    // stop here only leaves the hint out: the hole is done).
    HoleWork probe = failed.front();
    std::string why_not;
    const bool would =
        AllowInputIntersections(mesh, topo, control, &probe, &why_not);
    w->report.check_ms +=
        probe.report.check_ms - failed.front().report.check_ms;
    if (would) {
      w->report.reason +=
          "; the mesh already intersects itself near the hole (" +
          std::to_string(probe.report.input_pairs_near) +
          " pairs): allow_input_intersections (--allow-input-intersections) "
          "fills it anyway";
    }
    return;
  }
  // The first attempt that qualifies (a later one avoids more chords but
  // may cross itself where an earlier one did not); when none does, the
  // same rounds again avoiding only the chords where the patch meets
  // itself (the mesh it may meet), which may also find a clean patch.
  std::string why_not;
  double ms = w->report.triangulate_ms, check_ms = w->report.check_ms;
  for (bool own_only : {false, true}) {
    if (own_only) {
      HoleWork again;
      again.report = initial;
      again.started = true;
      failed.clear();
      FillAvoiding(mesh, topo, loops, options, control, &again, &failed, true);
      ms += again.report.triangulate_ms;
      check_ms += again.report.check_ms;
      if (!again.status.ok()) {
        w->status = again.status;
        return;
      }
      if (again.report.status == HoleStatus::kFilled) {
        again.report.triangulate_ms = ms;
        again.report.check_ms = check_ms;
        *w = std::move(again);
        return;
      }
    }
    for (HoleWork& attempt : failed) {
      const double before = attempt.report.check_ms;
      const bool filled =
          AllowInputIntersections(mesh, topo, control, &attempt, &why_not);
      check_ms += attempt.report.check_ms - before;
      if (!attempt.status.ok()) {
        w->status = attempt.status;
        return;
      }
      if (filled) {
        attempt.report.triangulate_ms = ms;  // every attempt's
        attempt.report.check_ms = check_ms;
        *w = std::move(attempt);
        return;
      }
    }
  }
  w->report.triangulate_ms = ms;
  w->report.check_ms = check_ms;
  w->report.reason += "; allow_input_intersections does not apply: " + why_not;
}

// A hole with islands is filled by one patch when one exists; when none
// does (or the solver does not take that many loops), each of its loops is
// filled alone, as without islands, and says why.
void FillGroup(const MeshData& mesh, const MeshTopology& topo,
               const std::vector<HoleLoop>& loops,
               const std::vector<int32_t>& group, const FillOptions& options,
               const Control& control, std::vector<HoleWork>* work) {
  HoleWork& lead = (*work)[group[0]];
  if (group.size() == 1) {
    FillOne(mesh, topo, {&loops[group[0]]}, options, control, &lead);
    return;
  }
  std::vector<const HoleLoop*> hole;
  for (int32_t i : group) hole.push_back(&loops[i]);
  const HoleReport before = lead.report;
  FillOne(mesh, topo, hole, options, control, &lead);
  if (!lead.status.ok() || lead.report.status == HoleStatus::kFilled) return;
  const std::string why =
      "its islands could not be joined to it (" + lead.report.reason + ")";
  lead.report = before;
  lead.patch = {};
  // No loop of the group is joined any more, also those a stop leaves
  // unfilled (they must not take the rim's status).
  for (int32_t i : group) {
    HoleReport& r = (*work)[i].report;
    r.joined.clear();
    r.joined_to = -1;
    r.reason.clear();
  }
  for (int32_t i : group) {
    HoleWork& w = (*work)[i];
    FillOne(mesh, topo, {&loops[i]}, options, control, &w);
    if (!w.status.ok()) return;
    const bool filled = w.report.status == HoleStatus::kFilled;
    const std::string own = w.report.reason;
    w.report.reason =
        (i == group[0] ? why
                       : "the hole of rim " + std::to_string(group[0]) +
                             " could not be joined to this island") +
        (filled ? ": filled alone" : ": tried alone");
    if (!own.empty()) w.report.reason += "; " + own;
  }
}

// The patches merged so far, for the checks between holes (each hole was
// checked against the input mesh alone, in parallel).
struct Merged {
  std::vector<bool> split;             // input faces split so far
  std::unordered_set<uint64_t> edges;  // undirected edges of new faces
  std::vector<Triangle> faces;         // new faces and pieces, mesh ids
  // Per merged hole: the box of its faces, which start at faces[start]. A
  // new patch is checked against the faces of the holes whose box meets
  // its own, not against every face merged so far (thousands of holes).
  std::vector<Box3> boxes;
  std::vector<size_t> starts;
};

// Appends the hole's new vertices and faces; split faces are replaced in
// place by their first piece (so unsplit faces keep their index), the other
// pieces appended. Refused, with the reason in `refused`, when the hole
// would split a face another hole split, reuse an edge of another hole's
// patch (two loops through the same vertices) or intersect another hole's
// patch. Not interrupted: its work is bounded by the patch and the merged
// patches its box meets, and a stopped fill keeps what it merges.
void Merge(int32_t first_new, const HoleWork& w, Merged* merged,
           FillResult* out, std::string* refused) {
  for (int32_t f : w.patch.split_faces) {
    if (merged->split[f]) {
      *refused = "a face it splits was split by another hole";
      return;
    }
  }
  const auto offset =
      static_cast<int32_t>(out->mesh.vertices.size()) - first_new;
  auto remap = [&](Triangle t) {
    for (int32_t& v : t) v = v < first_new ? v : v + offset;
    return t;
  };
  std::vector<Triangle> fresh;  // the patch, then the pieces, in mesh ids
  for (const Triangle& t : w.patch.faces) fresh.push_back(remap(t));
  for (const auto& pieces : w.patch.pieces) {
    for (const Triangle& t : pieces) fresh.push_back(remap(t));
  }
  for (const Triangle& t : fresh) {
    for (int k = 0; k < 3; ++k) {
      if (merged->edges.count(UndirectedEdgeKey(t[k], t[(k + 1) % 3]))) {
        *refused = "its patch would share edge " + std::to_string(t[k]) + "-" +
                   std::to_string(t[(k + 1) % 3]) + " with another hole's";
        return;
      }
    }
  }
  out->mesh.vertices.insert(out->mesh.vertices.end(),
                            w.patch.new_vertices.begin(),
                            w.patch.new_vertices.end());
  auto point = [&](int32_t v) -> const Vec3& { return out->mesh.vertices[v]; };
  Box3 box;
  for (const Triangle& t : fresh) {
    for (int32_t v : t) box.Add(point(v));
  }
  std::vector<Triangle> check = fresh;
  for (size_t k = 0; k < merged->boxes.size(); ++k) {
    if (!merged->boxes[k].Meets(box)) continue;
    const size_t end = k + 1 < merged->starts.size() ? merged->starts[k + 1]
                                                     : merged->faces.size();
    for (size_t f = merged->starts[k]; f < end; ++f) {
      const Triangle& t = merged->faces[f];
      Box3 b;
      for (int32_t v : t) b.Add(point(v));
      if (b.Meets(box)) check.push_back(t);
    }
  }
  if (check.size() > fresh.size()) {
    // Pairs within the hole were checked already: count only the others.
    const Control unbounded;
    int64_t with_others = 0, within = 0;
    CountPairsAmong(point, check, fresh.size(), unbounded, &with_others);
    CountPairsAmong(point, fresh, fresh.size(), unbounded, &within);
    const int64_t pairs = with_others - within;
    if (pairs > 0) {
      out->mesh.vertices.resize(out->mesh.vertices.size() -
                                w.patch.new_vertices.size());
      *refused = "its patch intersects another hole's (" +
                 std::to_string(pairs) + " pairs of faces)";
      return;
    }
  }
  for (size_t k = 0; k < w.patch.split_faces.size(); ++k) {
    const int32_t f = w.patch.split_faces[k];
    merged->split[f] = true;
    const auto& pieces = w.patch.pieces[k];
    out->mesh.triangles[f] = remap(pieces[0]);
    for (size_t p = 1; p < pieces.size(); ++p) {
      out->mesh.triangles.push_back(remap(pieces[p]));
    }
  }
  for (const Triangle& t : w.patch.faces) {
    out->mesh.triangles.push_back(remap(t));
  }
  FilledHole& kept = out->patches.emplace_back();
  kept.hole = w.report.id;
  kept.first_vertex = static_cast<int32_t>(out->mesh.vertices.size() -
                                           w.patch.new_vertices.size());
  kept.patch.new_vertices = w.patch.new_vertices;
  for (const Triangle& t : w.patch.faces) kept.patch.faces.push_back(remap(t));
  kept.patch.split_faces = w.patch.split_faces;
  for (const auto& pieces : w.patch.pieces) {
    auto& mapped = kept.patch.pieces.emplace_back();
    for (const Triangle& t : pieces) mapped.push_back(remap(t));
  }
  merged->boxes.push_back(box);
  merged->starts.push_back(merged->faces.size());
  for (const Triangle& t : fresh) {
    for (int k = 0; k < 3; ++k) {
      merged->edges.insert(UndirectedEdgeKey(t[k], t[(k + 1) % 3]));
    }
    merged->faces.push_back(t);
  }
}

// Whether every edge has exactly two faces: the edges sorted, in runs of
// two (8 bytes a face side, in parallel; an edge index took twice that).
bool Closed(const std::vector<Triangle>& triangles) {
  std::vector<uint64_t> edges(3 * triangles.size());
  tbb::parallel_for(size_t{0}, triangles.size(), [&](size_t f) {
    const Triangle& t = triangles[f];
    for (int k = 0; k < 3; ++k) {
      edges[3 * f + k] = UndirectedEdgeKey(t[k], t[(k + 1) % 3]);
    }
  });
  tbb::parallel_sort(edges.begin(), edges.end());
  for (size_t i = 0; i < edges.size(); i += 2) {
    if (i + 1 == edges.size() || edges[i] != edges[i + 1] ||
        (i + 2 < edges.size() && edges[i + 2] == edges[i])) {
      return false;
    }
  }
  return true;
}

}  // namespace

MetricWeights FillOptions::DefaultFillWeights() {
  MetricWeights w;
  w[Metric::kSquaredDihedral] = 1;
  w[Metric::kArea] = 0.01;
  return w;
}

Options FillOptions::DefaultTriangulateOptions() {
  Options o;
  o.space = SearchSpace::kDelaunay;
  return o;
}

Status CheckFillOptions(const FillOptions& o) {
  for (Metric m : kAllMetrics) {
    if (!std::isfinite(o.weights[m])) {
      return InvalidArgument("weight of metric " + std::string(MetricName(m)) +
                             " is not finite");
    }
  }
  if (!HasNonZeroWeight(o.weights)) {
    return InvalidArgument("every metric weight is zero");
  }
  if (!(o.density >= 0.1 && o.density <= 100)) {
    return InvalidArgument(
        "density must be between 0.1 and 100 (default "
        "sqrt(2))");
  }
  if (o.fairing_continuity < 0 || o.fairing_continuity > 2) {
    return InvalidArgument("fairing_continuity must be 0, 1 or 2");
  }
  if (!(o.selection.max_diameter >= 0) ||
      !std::isfinite(o.selection.max_diameter)) {
    return InvalidArgument("max_hole_diameter must be a finite number >= 0");
  }
  if (o.selection.max_edges < 0) {
    return InvalidArgument("max_hole_edges must be >= 0");
  }
  if (o.threads < 0) return InvalidArgument("threads must be >= 0");
  return OkStatus();
}

namespace {

// FillHoles over `mesh`; when `owned` (== &mesh) is given, the result takes
// its arrays instead of a copy once the holes are done.
FillResult Fill(const MeshData& mesh, MeshData* owned,
                const FillOptions& options, const Control& control,
                const FillProgressFn& on_progress) {
  const auto t_start = Clock::now();
  FillResult out;
  out.status = CheckFillOptions(options);
  if (!out.status.ok()) return out;
  if (on_progress) on_progress(FillPhase::kLoops, 0, 0);
  RunTicker ticker(control, "the check of the mesh");
  out.status = CheckMesh(mesh, &ticker);
  if (!out.status.ok()) return out;
  std::vector<HoleLoop> loops;
  out.status = FindHoleLoops(mesh, &loops, control);
  if (!out.status.ok()) return out;
  std::vector<std::string> skip;
  out.status = Select(loops, options.selection, &skip);
  if (!out.status.ok()) return out;
  std::vector<int32_t> rim;
  out.status =
      GroupHoleLoops(mesh, loops, options.islands, options.join, &rim, control);
  if (!out.status.ok()) return out;
  // Holes, each its rim's index first: an island goes with its rim when
  // the rim is selected, whatever its own size; otherwise it is a hole of
  // its own.
  std::vector<std::vector<int32_t>> groups(loops.size());
  for (size_t i = 0; i < loops.size(); ++i) {
    const auto r = static_cast<size_t>(rim[i]);
    if (r == i || !skip[r].empty()) {
      groups[i].insert(groups[i].begin(), static_cast<int32_t>(i));
    } else {
      groups[r].push_back(static_cast<int32_t>(i));
      skip[i].clear();
    }
  }
  RunTicker between(control, "hole filling");
  std::vector<HoleWork> work(loops.size());
  for (size_t i = 0; i < loops.size(); ++i) {
    HoleReport& r = work[i].report;
    r.id = loops[i].id;
    r.boundary_vertices = static_cast<int32_t>(loops[i].vertices.size());
    r.pinched = loops[i].pinched;
    r.diameter = loops[i].diameter;
    Measure(mesh, loops[i], &r);
    r.reason = skip[i];
    if (options.dry_run && skip[i].empty()) r.status = HoleStatus::kListed;
  }
  for (size_t i = 0; i < loops.size(); ++i) {
    for (size_t k = 1; k < groups[i].size(); ++k) {
      work[i].report.joined.push_back(groups[i][k]);
      HoleReport& island = work[groups[i][k]].report;
      island.joined_to = static_cast<int32_t>(i);
      island.reason = "island of hole " + std::to_string(i);
    }
  }
  if (options.dry_run) {
    out.mesh = owned != nullptr ? std::move(*owned) : mesh;
    for (HoleWork& w : work) {
      (w.report.status == HoleStatus::kSkipped ? out.report.skipped
                                               : out.report.listed)++;
      out.report.holes.push_back(std::move(w.report));
    }
    out.report.loops = static_cast<int32_t>(loops.size());
    out.report.closed = loops.empty();
    out.report.total_ms = MsSince(t_start);
    return out;
  }
  int selected = 0;  // holes: a rim and its islands count once
  for (size_t i = 0; i < loops.size(); ++i) {
    selected += skip[i].empty() && !groups[i].empty();
  }
  // A stop before the holes run leaves every selected hole not started.
  std::shared_ptr<const MeshTopology> topo;
  if (between.Poll()) topo = BuildMeshTopology(mesh);
  if (topo && between.Poll()) {
    if (on_progress) on_progress(FillPhase::kHoles, 0, selected);
    // The per-hole calls report no progress of their own (they run at once).
    Control hole_control = control;
    hole_control.progress = nullptr;
    const int threads =
        options.threads > 0
            ? options.threads
            : static_cast<int>(std::thread::hardware_concurrency());
    std::mutex progress_mu;
    int done = 0;
    tbb::task_arena arena(std::max(1, threads));
    arena.execute([&] {
      tbb::parallel_for(size_t{0}, loops.size(), size_t{1}, [&](size_t i) {
        if (!skip[i].empty() || groups[i].empty()) return;
        FillGroup(mesh, *topo, loops, groups[i], options, hole_control, &work);
        if (on_progress && work[i].status.ok()) {  // stopped ones are not done
          std::lock_guard<std::mutex> lock(progress_mu);
          on_progress(FillPhase::kHoles, ++done, selected);
        }
      });
    });
  } else {
    for (size_t i = 0; i < loops.size(); ++i) {
      if (skip[i].empty()) work[i].status = between.status();
    }
  }
  // Why the fill stopped, if it did: a cancel or the deadline (which stop
  // every hole after it) rather than one hole's own error. The holes
  // finished before it are kept when any is and the caller still wants
  // them.
  int finished = 0;
  for (const HoleWork& w : work) {
    finished += w.status.ok() && w.report.status == HoleStatus::kFilled;
    const bool stop = w.status.code == StatusCode::kCancelled ||
                      w.status.code == StatusCode::kDeadlineExceeded;
    if (!w.status.ok() && (out.status.ok() || stop)) out.status = w.status;
  }
  if (!out.status.ok()) {
    if (finished == 0 || (control.keep_partial && !control.keep_partial())) {
      return out;  // nothing to keep, or nobody to keep it for
    }
    out.partial = true;
  }

  if (on_progress) on_progress(FillPhase::kMerge, finished, selected);
  topo.reset();  // the merge needs the patches, not the index
  const auto input_vertices = static_cast<int32_t>(mesh.vertices.size());
  const auto input_faces = static_cast<int32_t>(mesh.triangles.size());
  Merged merged;
  merged.split.assign(input_faces, false);
  if (owned != nullptr) {
    out.mesh = std::move(*owned);  // `mesh` is not read after this
  } else {
    out.mesh = mesh;
  }
  for (HoleWork& w : work) {
    HoleReport& r = w.report;
    if (!w.status.ok()) {
      r.status = HoleStatus::kStopped;
      r.reason = std::string(w.started ? "stopped: " : "not started: ") +
                 StopCause(w.status);
    } else if (r.status == HoleStatus::kFilled) {
      // Bounded by the patches made, so not interrupted: a stop keeps them.
      std::string refused;
      Merge(input_vertices, w, &merged, &out, &refused);
      if (!refused.empty()) {
        r.status = HoleStatus::kFailed;
        r.reason = refused + ": left open (fill it in a call of its own)";
      }
    }
  }
  // An island shares its rim's fate.
  for (HoleWork& w : work) {
    HoleReport& r = w.report;
    if (r.joined_to < 0) continue;
    const HoleWork& lead = work[r.joined_to];
    r.status = lead.report.status;
    r.reason = "island of hole " + std::to_string(r.joined_to) +
               (lead.report.reason.empty() ? "" : ": " + lead.report.reason);
    r.escalation = lead.report.escalation;
    r.space = lead.report.space;
    r.solver = lead.report.solver;
  }
  for (HoleWork& w : work) {
    HoleReport& r = w.report;
    switch (r.status) {
      case HoleStatus::kFilled:
        ++out.report.filled;
        break;
      case HoleStatus::kSkipped:
        ++out.report.skipped;
        break;
      case HoleStatus::kStopped:
        ++out.report.stopped;
        break;
      default:
        ++out.report.unfilled;
    }
    out.report.holes.push_back(std::move(r));
  }
  out.report.loops = static_cast<int32_t>(loops.size());
  out.report.added_vertices =
      static_cast<int32_t>(out.mesh.vertices.size()) - input_vertices;
  out.report.added_faces =
      static_cast<int32_t>(out.mesh.triangles.size()) - input_faces;
  // A hole left open leaves its border; only a mesh with every loop filled
  // is checked edge by edge (a linear pass, not interrupted either).
  out.report.closed =
      out.report.filled == out.report.loops && Closed(out.mesh.triangles);
  out.report.total_ms = MsSince(t_start);
  return out;
}

}  // namespace

FillResult FillHoles(const MeshData& mesh, const FillOptions& options,
                     const Control& control,
                     const FillProgressFn& on_progress) {
  return Fill(mesh, nullptr, options, control, on_progress);
}

FillResult FillHoles(MeshData&& mesh, const FillOptions& options,
                     const Control& control,
                     const FillProgressFn& on_progress) {
  return Fill(mesh, &mesh, options, control, on_progress);
}

std::string_view FillStageName(FillStage s) {
  switch (s) {
    case FillStage::kTriangulate:
      return "triangulate";
    case FillStage::kRefine:
      return "refine";
    case FillStage::kFair:
      return "fair";
  }
  return "?";
}

std::string_view IslandModeName(IslandMode m) {
  return m == IslandMode::kOff ? "off" : "auto";
}

std::string_view FillPhaseName(FillPhase p) {
  switch (p) {
    case FillPhase::kRepair:
      return "repair";
    case FillPhase::kLoops:
      return "loops";
    case FillPhase::kHoles:
      return "holes";
    case FillPhase::kMerge:
      return "merge";
  }
  return "?";
}

std::string_view HoleStatusName(HoleStatus s) {
  switch (s) {
    case HoleStatus::kFilled:
      return "filled";
    case HoleStatus::kSkipped:
      return "skipped";
    case HoleStatus::kNoTriangulation:
      return "no_triangulation";
    case HoleStatus::kListed:
      return "listed";
    case HoleStatus::kFailed:
      return "failed";
    case HoleStatus::kStopped:
      return "stopped";
  }
  return "?";
}

std::string_view EscalationName(Escalation e) {
  switch (e) {
    case Escalation::kNone:
      return "none";
    case Escalation::kDelaunay:
      return "delaunay";
    case Escalation::kProtectedEdges:
      return "protected_edges";
    case Escalation::kAllTriangles:
      return "all_triangles";
    case Escalation::kDelaunayFirst:
      return "delaunay_first";
  }
  return "?";
}

}  // namespace dot

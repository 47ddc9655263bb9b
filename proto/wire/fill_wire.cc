// SPDX-License-Identifier: AGPL-3.0-or-later
#include "wire/fill_wire.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "wire/wire.h"

namespace dot::wire {

Status FillStageFromWire(v1::FillStage wire, FillStage* stage) {
  switch (wire) {
    case v1::FILL_STAGE_TRIANGULATE:
      *stage = FillStage::kTriangulate;
      return OkStatus();
    case v1::FILL_STAGE_REFINE:
      *stage = FillStage::kRefine;
      return OkStatus();
    case v1::FILL_STAGE_DEFAULT:
    case v1::FILL_STAGE_FAIR:
      *stage = FillStage::kFair;
      return OkStatus();
    default:
      return InvalidArgument("unknown stage " + std::to_string(wire));
  }
}

Status FillOptionsFromWire(const v1::FillOptions& wire, FillOptions* o) {
  *o = {};
  if (wire.has_weights()) o->weights = FromWire(wire.weights());
  o->scale_free_weights = !wire.absolute_weights();
  const Status stage = FillStageFromWire(wire.stage(), &o->stage);
  if (!stage.ok()) return stage;
  o->selection.max_edges =
      static_cast<int>(std::min<uint32_t>(wire.max_hole_edges(), INT32_MAX));
  o->selection.max_diameter = wire.max_hole_diameter();
  o->selection.skip_longest = wire.skip_longest();
  o->selection.ids.assign(wire.holes().begin(), wire.holes().end());
  if (wire.density() != 0) o->density = wire.density();  // 0: the default
  if (wire.has_fairing_continuity()) {
    o->fairing_continuity = wire.fairing_continuity();
  }
  o->repair = !wire.no_repair();
  o->dry_run = wire.dry_run();
  o->allow_input_intersections = wire.allow_input_intersections();
  // Patches are new triangles in the sent mesh's ids: nothing to regroup.
  o->keep_polygons = wire.keep_polygons() &&
                     wire.answer() == v1::FILL_ANSWER_MESH && !wire.dry_run();
  o->selection.through_vertices.reserve(wire.loops_through_size());
  for (uint32_t v : wire.loops_through()) {
    o->selection.through_vertices.push_back(
        static_cast<int32_t>(std::min<uint32_t>(v, INT32_MAX)));
  }
  switch (wire.islands()) {
    case v1::ISLANDS_AUTO:
      o->islands = IslandMode::kAuto;
      break;
    case v1::ISLANDS_OFF:
      o->islands = IslandMode::kOff;
      break;
    default:
      return InvalidArgument("unknown islands mode " +
                             std::to_string(wire.islands()) +
                             " (ISLANDS_AUTO or ISLANDS_OFF)");
  }
  for (const v1::LoopGroup& g : wire.join()) {
    o->join.emplace_back(g.loops().begin(), g.loops().end());
  }
  // The ranges are the core's to check, one place for every caller.
  return CheckFillOptions(*o);
}

Status FillAnswerFromWire(const v1::FillOptions& wire, v1::FillAnswer* answer) {
  if (!v1::FillAnswer_IsValid(wire.answer())) {
    return InvalidArgument("unknown fill answer " +
                           std::to_string(wire.answer()) +
                           " (FILL_ANSWER_MESH or FILL_ANSWER_PATCHES)");
  }
  *answer = wire.answer();
  return OkStatus();
}

v1::HoleStatus HoleStatusToWire(HoleStatus status) {
  switch (status) {
    case HoleStatus::kFilled:
      return v1::HOLE_STATUS_FILLED;
    case HoleStatus::kSkipped:
      return v1::HOLE_STATUS_SKIPPED;
    case HoleStatus::kNoTriangulation:
      return v1::HOLE_STATUS_NO_TRIANGULATION;
    case HoleStatus::kFailed:
      return v1::HOLE_STATUS_FAILED;
    case HoleStatus::kListed:
      return v1::HOLE_STATUS_LISTED;
    case HoleStatus::kStopped:
      return v1::HOLE_STATUS_STOPPED;
  }
  return v1::HOLE_STATUS_UNSPECIFIED;
}

v1::Escalation EscalationToWire(Escalation escalation) {
  switch (escalation) {
    case Escalation::kNone:
      return v1::ESCALATION_NONE;
    case Escalation::kDelaunay:
      return v1::ESCALATION_DELAUNAY;
    case Escalation::kProtectedEdges:
      return v1::ESCALATION_PROTECTED_EDGES;
    case Escalation::kAllTriangles:
      return v1::ESCALATION_ALL_TRIANGLES;
    case Escalation::kDelaunayFirst:
      return v1::ESCALATION_DELAUNAY_FIRST;
  }
  return v1::ESCALATION_NONE;
}

void FillReportToWire(const FillReport& r, const RepairReport& repair,
                      size_t input_vertices, size_t input_faces,
                      v1::FillReport* out) {
  out->Clear();
  out->set_version(2);
  for (const HoleReport& h : r.holes) {
    v1::HoleReport* w = out->add_holes();
    w->set_id(h.id);
    w->set_boundary_vertices(h.boundary_vertices);
    w->set_pinched(h.pinched);
    w->set_status(HoleStatusToWire(h.status));
    w->set_reason(h.reason);
    if (h.escalation != Escalation::kNone) {
      w->set_escalation(EscalationToWire(h.escalation));
      w->set_search_space_used(std::string(SpaceUsedName(h.space)));
      w->set_solver(std::string(SolverName(h.solver)));
    }
    w->set_boundary_inserted(h.boundary_inserted);
    for (int32_t f : h.split_faces) w->add_split_faces(f);
    w->set_patch_triangles(h.patch_triangles);
    w->set_refined_vertices(h.refined_vertices);
    w->set_faired(h.faired);
    w->set_cost(h.cost);
    w->set_intersecting_pairs(h.intersecting_pairs);
    w->set_input_pairs_near(h.input_pairs_near);
    w->set_non_delaunay_triangles(h.non_delaunay_triangles);
    w->set_triangulate_ms(h.triangulate_ms);
    w->set_refine_ms(h.refine_ms);
    w->set_fair_ms(h.fair_ms);
    w->set_check_ms(h.check_ms);
    w->set_diameter(h.diameter);
    w->set_perimeter(h.perimeter);
    for (double c : {h.centroid.x, h.centroid.y, h.centroid.z}) {
      w->add_centroid(c);
    }
    for (int32_t id : h.joined) w->add_joined(id);
    if (h.joined_to >= 0) w->set_joined_to(h.joined_to);
  }
  out->set_loops(r.loops);
  out->set_filled(r.filled);
  out->set_skipped(r.skipped);
  out->set_unfilled(r.unfilled);
  out->set_listed(r.listed);
  out->set_stopped(r.stopped);
  out->set_added_vertices(r.added_vertices);
  out->set_added_faces(r.added_faces);
  out->set_closed(r.closed);
  out->set_total_ms(r.total_ms);
  v1::RepairReport* rr = out->mutable_repair();
  rr->set_merged_vertices(repair.merged_vertices);
  rr->set_degenerate_faces(repair.degenerate_faces);
  rr->set_duplicate_faces(repair.duplicate_faces);
  rr->set_triangulated_polygons(repair.triangulated_polygons);
  rr->set_reoriented_faces(repair.reoriented_faces);
  rr->set_non_manifold_vertices(repair.non_manifold_vertices);
  rr->set_components(repair.components);
  out->set_input_vertices(static_cast<uint32_t>(input_vertices));
  out->set_input_faces(static_cast<uint32_t>(input_faces));
}

v1::FillPhase FillPhaseToWire(FillPhase phase) {
  switch (phase) {
    case FillPhase::kRepair:
      return v1::FILL_PHASE_REPAIR;
    case FillPhase::kLoops:
      return v1::FILL_PHASE_LOOPS;
    case FillPhase::kHoles:
      return v1::FILL_PHASE_HOLES;
    case FillPhase::kMerge:
      return v1::FILL_PHASE_MERGE;
  }
  return v1::FILL_PHASE_UNSPECIFIED;
}

FillPhase FillPhaseFromWire(v1::FillPhase phase) {
  for (FillPhase p :
       {FillPhase::kRepair, FillPhase::kLoops, FillPhase::kMerge}) {
    if (FillPhaseToWire(p) == phase) return p;
  }
  return FillPhase::kHoles;
}

v1::FillProgress FillProgressClock::Report(FillPhase phase, int holes_done,
                                           int holes_total) {
  const auto now = std::chrono::steady_clock::now();
  if (phase == FillPhase::kHoles && !in_holes_) {
    in_holes_ = true;
    holes_start_ = now;
  }
  v1::FillProgress p;
  p.set_phase(FillPhaseToWire(phase));
  p.set_holes_done(holes_done);
  p.set_holes_total(holes_total);
  p.set_elapsed_ms(MsSince(start_));
  if (phase == FillPhase::kHoles && holes_done > 0) {
    const double per_hole = MsSince(holes_start_) / holes_done;
    p.set_eta_ms(per_hole * (holes_total - holes_done));
  }
  return p;
}

HoleStatus HoleStatusFromWire(v1::HoleStatus status) {
  for (HoleStatus s :
       {HoleStatus::kFilled, HoleStatus::kSkipped, HoleStatus::kNoTriangulation,
        HoleStatus::kListed, HoleStatus::kStopped}) {
    if (HoleStatusToWire(s) == status) return s;
  }
  return HoleStatus::kFailed;
}

Escalation EscalationFromWire(v1::Escalation escalation) {
  for (Escalation e : {Escalation::kDelaunay, Escalation::kProtectedEdges,
                       Escalation::kAllTriangles, Escalation::kDelaunayFirst}) {
    if (EscalationToWire(e) == escalation) return e;
  }
  return Escalation::kNone;
}

FillRequestWriter::FillRequestWriter(std::string id, v1::FillOptions options,
                                     const PolygonSoup& mesh, size_t max_bytes)
    : id_(std::move(id)),
      options_(std::move(options)),
      chunks_(mesh, max_bytes) {}

bool FillRequestWriter::Next(v1::FillHolesRequest* m) {
  m->Clear();
  const bool first = first_;
  if (first_) {  // id and options, and the first slice with them
    first_ = false;
    m->set_id(id_);
    *m->mutable_options() = options_;
  }
  return chunks_.Next(m->mutable_mesh()) || first;  // an empty mesh: one
}

bool PatchWriter::Next(v1::HolePatch* m) {
  m->Clear();
  const auto& patches = *patches_;
  if (patch_ >= patches.size()) return false;
  const SentPatch& p = patches[patch_];
  m->set_hole(p.hole);
  m->set_first_vertex(static_cast<uint32_t>(p.first_vertex + vertex_));
  size_t bytes = 0;
  for (; vertex_ < p.new_vertices.size() && bytes < max_bytes_; ++vertex_) {
    m->add_vertices(p.new_vertices[vertex_].x);
    m->add_vertices(p.new_vertices[vertex_].y);
    m->add_vertices(p.new_vertices[vertex_].z);
    bytes += 27;
  }
  // A triangle's corner values, over every channel.
  size_t corner_bytes = 0;
  for (const PatchChannel& c : p.attributes) corner_bytes += 12 * c.dims;
  const size_t first_face = face_, first_piece = piece_;
  for (; face_ < p.faces.size() && bytes < max_bytes_; ++face_) {
    for (int32_t v : p.faces[face_]) m->add_faces(static_cast<uint32_t>(v));
    bytes += 15 + corner_bytes;
  }
  for (; replaced_ < p.replaced_faces.size() && bytes < max_bytes_;
       ++replaced_) {
    v1::ReplacedFace* r = m->add_replaced_faces();
    r->set_face(static_cast<uint32_t>(p.replaced_faces[replaced_]));
    for (const Triangle& t : p.replacements[replaced_]) {
      for (int32_t v : t) r->add_triangles(static_cast<uint32_t>(v));
    }
    piece_ += p.replacements[replaced_].size();
    bytes += 8 + (15 + corner_bytes) * p.replacements[replaced_].size();
  }
  for (const PatchChannel& c : p.attributes) {
    v1::CornerValues* values = m->add_attributes();
    values->set_name(c.name);
    values->set_dims(static_cast<uint32_t>(c.dims));
    const size_t per = 3 * static_cast<size_t>(c.dims);  // a triangle's
    values->mutable_faces()->Add(c.faces.begin() + first_face * per,
                                 c.faces.begin() + face_ * per);
    values->mutable_replaced()->Add(c.replaced.begin() + first_piece * per,
                                    c.replaced.begin() + piece_ * per);
  }
  if (vertex_ == p.new_vertices.size() && face_ == p.faces.size() &&
      replaced_ == p.replaced_faces.size()) {
    ++patch_;
    vertex_ = face_ = replaced_ = piece_ = 0;
  }
  return true;
}

Status PatchReader::Add(const v1::HolePatch& m) {
  if (m.vertices_size() % 3 != 0 || m.faces_size() % 3 != 0) {
    return InvalidArgument("a patch message of hole " +
                           std::to_string(m.hole()) +
                           " has a partial vertex or triangle");
  }
  if (m.first_vertex() != next_vertex_) {
    return InvalidArgument(
        "the patch of hole " + std::to_string(m.hole()) + " starts at vertex " +
        std::to_string(m.first_vertex()) + ", not " +
        std::to_string(next_vertex_) +
        ": it does not continue where the last message ended");
  }
  const bool continues = !patches_.empty() && patches_.back().hole == m.hole();
  if (!continues && !patches_.empty() && m.hole() < patches_.back().hole) {
    return InvalidArgument("the patch of hole " + std::to_string(m.hole()) +
                           " comes after hole " +
                           std::to_string(patches_.back().hole) +
                           "'s: patches come in hole order");
  }
  SentPatch* p = continues ? &patches_.back() : &patches_.emplace_back();
  if (!continues) {
    p->hole = m.hole();
    p->first_vertex = static_cast<int32_t>(m.first_vertex());
  }
  next_vertex_ += static_cast<size_t>(m.vertices_size() / 3);
  auto check = [&](const auto& ids) {
    for (uint32_t v : ids) {
      if (v >= next_vertex_) {
        return InvalidArgument("the patch of hole " + std::to_string(m.hole()) +
                               " names vertex " + std::to_string(v) +
                               ", but only " + std::to_string(next_vertex_) +
                               " exist");
      }
    }
    return OkStatus();
  };
  Status ids = check(m.faces());
  for (const v1::ReplacedFace& r : m.replaced_faces()) {
    if (ids.ok()) ids = check(r.triangles());
  }
  if (!ids.ok()) return ids;
  for (int i = 0; i < m.vertices_size(); i += 3) {
    p->new_vertices.push_back(
        {m.vertices(i), m.vertices(i + 1), m.vertices(i + 2)});
  }
  for (int i = 0; i < m.faces_size(); i += 3) {
    p->faces.push_back({static_cast<int32_t>(m.faces(i)),
                        static_cast<int32_t>(m.faces(i + 1)),
                        static_cast<int32_t>(m.faces(i + 2))});
  }
  // Each message gives every channel's values for its own corners.
  size_t replacing = 0;  // triangles in replaced_faces
  for (const v1::ReplacedFace& r : m.replaced_faces())
    replacing += static_cast<size_t>(r.triangles_size()) / 3;
  if (!continues) {
    for (const v1::CornerValues& c : m.attributes()) {
      const auto dims = static_cast<int>(std::min<uint32_t>(c.dims(), 17));
      p->attributes.push_back({c.name(), dims, {}, {}});
    }
  }
  if (static_cast<size_t>(m.attributes_size()) != p->attributes.size()) {
    return InvalidArgument(
        "a patch message of hole " + std::to_string(m.hole()) + " has " +
        std::to_string(m.attributes_size()) + " attribute channels, not " +
        std::to_string(p->attributes.size()));
  }
  for (int i = 0; i < m.attributes_size(); ++i) {
    const v1::CornerValues& c = m.attributes(i);
    PatchChannel& to = p->attributes[static_cast<size_t>(i)];
    const size_t dims = c.dims();
    if (c.name() != to.name || c.dims() != static_cast<uint32_t>(to.dims) ||
        dims == 0 || dims > 16 ||
        static_cast<size_t>(c.faces_size()) !=
            dims * static_cast<size_t>(m.faces_size()) ||
        static_cast<size_t>(c.replaced_size()) != 3 * dims * replacing) {
      return InvalidArgument("a patch message of hole " +
                             std::to_string(m.hole()) + ": attribute '" +
                             c.name() +
                             "' does not match the message's corners");
    }
    to.faces.insert(to.faces.end(), c.faces().begin(), c.faces().end());
    to.replaced.insert(to.replaced.end(), c.replaced().begin(),
                       c.replaced().end());
  }
  for (const v1::ReplacedFace& r : m.replaced_faces()) {
    if (r.triangles_size() % 3 != 0) {
      return InvalidArgument("replaced face " + std::to_string(r.face()) +
                             " has a partial triangle");
    }
    p->replaced_faces.push_back(static_cast<int32_t>(r.face()));
    auto& pieces = p->replacements.emplace_back();
    for (int i = 0; i < r.triangles_size(); i += 3) {
      pieces.push_back({static_cast<int32_t>(r.triangles(i)),
                        static_cast<int32_t>(r.triangles(i + 1)),
                        static_cast<int32_t>(r.triangles(i + 2))});
    }
  }
  return OkStatus();
}

Status FillRequestReader::Add(const v1::FillHolesRequest& m) {
  const std::string where = "message " + std::to_string(messages_);
  if (messages_++ == 0) {
    id_ = m.id();
    options_ = m.options();
  } else if (!m.id().empty() || m.has_options()) {
    return InvalidArgument(where +
                           ": id and options belong in the first message");
  }
  if (!m.GetReflection()->GetUnknownFields(m).empty()) {
    return InvalidArgument(
        where +
        " has fields this server does not know: vertices, faces "
        "and face_sizes moved into `mesh` (a MeshChunk) in dot.v1 "
        "revision 2; update the client");
  }
  return chunks_.Add(m.mesh(), where);
}

Status FillRequestReader::Finish(PolygonSoup* soup) {
  if (messages_ == 0) return InvalidArgument("no mesh was sent");
  if (chunks_.faces() == 0) return InvalidArgument("the mesh has no faces");
  return chunks_.Finish(soup);
}

}  // namespace dot::wire

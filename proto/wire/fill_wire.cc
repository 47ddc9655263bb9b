// SPDX-License-Identifier: AGPL-3.0-or-later
#include "wire/fill_wire.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "wire/wire.h"

namespace dot::wire {

Status FillOptionsFromWire(const v1::FillOptions& wire, FillOptions* o) {
  *o = {};
  if (wire.has_weights()) o->weights = FromWire(wire.weights());
  o->scale_free_weights = !wire.absolute_weights();
  switch (wire.stage()) {
    case v1::FILL_STAGE_TRIANGULATE:
      o->stage = FillStage::kTriangulate;
      break;
    case v1::FILL_STAGE_REFINE:
      o->stage = FillStage::kRefine;
      break;
    case v1::FILL_STAGE_DEFAULT:
    case v1::FILL_STAGE_FAIR:
      o->stage = FillStage::kFair;
      break;
    default:
      return InvalidArgument("unknown fill stage");
  }
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
  o->selection.through_vertices.reserve(wire.loops_through_size());
  for (uint32_t v : wire.loops_through()) {
    o->selection.through_vertices.push_back(
        static_cast<int32_t>(std::min<uint32_t>(v, INT32_MAX)));
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
    w->set_triangulate_ms(h.triangulate_ms);
    w->set_refine_ms(h.refine_ms);
    w->set_fair_ms(h.fair_ms);
    w->set_check_ms(h.check_ms);
    w->set_diameter(h.diameter);
    w->set_perimeter(h.perimeter);
    for (double c : {h.centroid.x, h.centroid.y, h.centroid.z}) {
      w->add_centroid(c);
    }
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
                       Escalation::kAllTriangles}) {
    if (EscalationToWire(e) == escalation) return e;
  }
  return Escalation::kNone;
}

FillRequestWriter::FillRequestWriter(std::string id, v1::FillOptions options,
                                     const PolygonSoup& mesh, size_t max_bytes)
    : id_(std::move(id)),
      options_(std::move(options)),
      mesh_(&mesh),
      vertices_per_(std::max<size_t>(1, max_bytes / 24)),
      indices_per_(std::max<size_t>(3, max_bytes / 5)) {
  for (const auto& f : mesh.faces) all_triangles_ &= f.size() == 3;
}

bool FillRequestWriter::Next(v1::FillHolesRequest* m) {
  m->Clear();
  if (first_) {  // id and options, and the first vertices with them
    first_ = false;
    m->set_id(id_);
    *m->mutable_options() = options_;
  }
  const PolygonSoup& mesh = *mesh_;
  v1::MeshChunk* chunk = m->mutable_mesh();
  if (next_vertex_ < mesh.vertices.size()) {
    const size_t end =
        std::min(mesh.vertices.size(), next_vertex_ + vertices_per_);
    chunk->set_first_vertex(static_cast<uint32_t>(next_vertex_));
    chunk->mutable_vertices()->Reserve(
        static_cast<int>(3 * (end - next_vertex_)));
    for (; next_vertex_ < end; ++next_vertex_) {
      const Vec3& p = mesh.vertices[next_vertex_];
      chunk->add_vertices(p.x);
      chunk->add_vertices(p.y);
      chunk->add_vertices(p.z);
    }
    return true;
  }
  if (next_face_ < mesh.faces.size()) {
    chunk->set_first_vertex(static_cast<uint32_t>(mesh.vertices.size()));
    chunk->set_first_triangle(static_cast<uint32_t>(next_face_));
    size_t indices = 0;
    for (; next_face_ < mesh.faces.size(); ++next_face_) {
      const auto& f = mesh.faces[next_face_];
      if (indices > 0 && indices + f.size() > indices_per_) break;
      for (int32_t v : f) chunk->add_triangles(static_cast<uint32_t>(v));
      if (!all_triangles_) {
        chunk->add_face_sizes(static_cast<uint32_t>(f.size()));
      }
      indices += f.size();
    }
    return true;
  }
  // Only the first message of an empty mesh is still to go.
  return m->has_options();
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
  for (; face_ < p.faces.size() && bytes < max_bytes_; ++face_) {
    for (int32_t v : p.faces[face_]) m->add_faces(static_cast<uint32_t>(v));
    bytes += 15;
  }
  for (; replaced_ < p.replaced_faces.size() && bytes < max_bytes_;
       ++replaced_) {
    v1::ReplacedFace* r = m->add_replaced_faces();
    r->set_face(static_cast<uint32_t>(p.replaced_faces[replaced_]));
    for (const Triangle& t : p.replacements[replaced_]) {
      for (int32_t v : t) r->add_triangles(static_cast<uint32_t>(v));
    }
    bytes += 8 + 15 * p.replacements[replaced_].size();
  }
  if (vertex_ == p.new_vertices.size() && face_ == p.faces.size() &&
      replaced_ == p.replaced_faces.size()) {
    ++patch_;
    vertex_ = face_ = replaced_ = 0;
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
  const v1::MeshChunk& c = m.mesh();  // this slice
  if (c.vertices_size() % 3 != 0) {
    return InvalidArgument(where + " has " + std::to_string(c.vertices_size()) +
                           " coordinates, not a multiple of 3");
  }
  if (!c.vertices().empty() && !soup_.faces.empty()) {
    return InvalidArgument(where + " sends vertices after faces");
  }
  if (!c.vertices().empty() && c.first_vertex() != soup_.vertices.size()) {
    return InvalidArgument(
        where + " starts at vertex " + std::to_string(c.first_vertex()) +
        " but " + std::to_string(soup_.vertices.size()) +
        " vertices have arrived (slices come in order, first_vertex set)");
  }
  if (!c.triangles().empty() && c.first_triangle() != soup_.faces.size()) {
    return InvalidArgument(
        where + " starts at face " + std::to_string(c.first_triangle()) +
        " but " + std::to_string(soup_.faces.size()) +
        " faces have arrived (slices come in order, first_triangle set)");
  }
  if (soup_.vertices.size() + c.vertices_size() / 3 > max_vertices_) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "the mesh has more than " +
                          std::to_string(max_vertices_) +
                          " vertices, the server's limit");
  }
  for (int i = 0; i < c.vertices_size(); i += 3) {
    soup_.vertices.push_back(
        {c.vertices(i), c.vertices(i + 1), c.vertices(i + 2)});
  }
  if (c.face_sizes().empty()) {
    if (c.triangles_size() % 3 != 0) {
      return InvalidArgument(where + " has " +
                             std::to_string(c.triangles_size()) +
                             " face indices, not a multiple of 3 (give "
                             "face_sizes for polygons)");
    }
  } else {
    size_t total = 0;
    for (uint32_t k : c.face_sizes()) {
      if (k < 3) {
        return InvalidArgument(where + " has a face of " + std::to_string(k) +
                               " corners; a face needs at least 3");
      }
      total += k;
    }
    if (total != static_cast<size_t>(c.triangles_size())) {
      return InvalidArgument(
          where + ": face_sizes add up to " + std::to_string(total) + " but " +
          std::to_string(c.triangles_size()) + " face indices were sent");
    }
  }
  const size_t faces = c.face_sizes().empty()
                           ? static_cast<size_t>(c.triangles_size()) / 3
                           : static_cast<size_t>(c.face_sizes_size());
  if (soup_.faces.size() + faces > max_faces_) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "the mesh has more than " + std::to_string(max_faces_) +
                          " faces, the server's limit");
  }
  // Corners, not faces, are what polygons cost (each is triangulated).
  corners_ += static_cast<size_t>(c.triangles_size());
  if (corners_ > 3 * max_faces_) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "the mesh's faces have more than " +
                          std::to_string(3 * max_faces_) +
                          " corners in all, the server's limit");
  }
  for (uint32_t k : c.face_sizes()) {
    if (k > kMaxPolygonCorners) {
      return InvalidArgument(
          where + " has a face of " + std::to_string(k) + " corners; at most " +
          std::to_string(kMaxPolygonCorners) + " are accepted");
    }
  }
  int next = 0;
  for (size_t f = 0; f < faces; ++f) {
    const int k =
        c.face_sizes().empty() ? 3 : static_cast<int>(c.face_sizes(f));
    std::vector<int32_t> face;
    for (int corner = 0; corner < k; ++corner) {
      const uint32_t v = c.triangles(next++);
      if (v >= soup_.vertices.size()) {
        return InvalidArgument(
            "face " + std::to_string(soup_.faces.size()) +
            " has vertex index " + std::to_string(v) + ", but only " +
            std::to_string(soup_.vertices.size()) + " vertices were sent");
      }
      face.push_back(static_cast<int32_t>(v));
    }
    soup_.faces.push_back(std::move(face));
  }
  return OkStatus();
}

Status FillRequestReader::Finish(PolygonSoup* soup) {
  if (messages_ == 0) return InvalidArgument("no mesh was sent");
  if (soup_.faces.empty()) return InvalidArgument("the mesh has no faces");
  for (size_t v = 0; v < soup_.vertices.size(); ++v) {
    if (!IsFinite(soup_.vertices[v])) {
      return InvalidArgument("vertex " + std::to_string(v) +
                             " has a non-finite coordinate");
    }
  }
  *soup = std::move(soup_);
  return OkStatus();
}

}  // namespace dot::wire

// SPDX-License-Identifier: AGPL-3.0-or-later
#include "wire/fill_wire.h"

#include <cmath>

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
  // The ranges are the core's to check, one place for every caller.
  return CheckFillOptions(*o);
}

void FillReportToWire(const FillReport& r, const RepairReport& repair,
                      size_t input_vertices, size_t input_faces,
                      v1::FillReport* out) {
  out->Clear();
  out->set_version(1);
  for (const HoleReport& h : r.holes) {
    v1::HoleReport* w = out->add_holes();
    w->set_id(h.id);
    w->set_boundary_vertices(h.boundary_vertices);
    w->set_pinched(h.pinched);
    w->set_status(std::string(HoleStatusName(h.status)));
    w->set_reason(h.reason);
    if (h.escalation != Escalation::kNone) {
      w->set_escalation(std::string(EscalationName(h.escalation)));
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
  }
  out->set_loops(r.loops);
  out->set_filled(r.filled);
  out->set_skipped(r.skipped);
  out->set_unfilled(r.unfilled);
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

std::vector<v1::FillHolesRequest> MakeFillRequests(
    const std::string& id, const v1::FillOptions& options,
    const PolygonSoup& mesh, size_t max_bytes) {
  std::vector<v1::FillHolesRequest> out(1);
  out[0].set_id(id);
  *out[0].mutable_options() = options;
  const size_t vertices_per = std::max<size_t>(1, max_bytes / 24);
  const size_t indices_per = std::max<size_t>(3, max_bytes / 5);
  size_t in_message = 0;
  for (const Vec3& p : mesh.vertices) {
    if (in_message == vertices_per) {
      out.emplace_back();
      in_message = 0;
    }
    v1::FillHolesRequest& m = out.back();
    m.add_vertices(p.x);
    m.add_vertices(p.y);
    m.add_vertices(p.z);
    ++in_message;
  }
  bool all_triangles = true;
  for (const auto& f : mesh.faces) all_triangles &= f.size() == 3;
  in_message = indices_per;  // faces start in a message of their own
  for (const auto& f : mesh.faces) {
    if (in_message + f.size() > indices_per) {
      out.emplace_back();
      in_message = 0;
    }
    v1::FillHolesRequest& m = out.back();
    for (int32_t v : f) m.add_faces(static_cast<uint32_t>(v));
    if (!all_triangles) m.add_face_sizes(static_cast<uint32_t>(f.size()));
    in_message += f.size();
  }
  return out;
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
  if (m.vertices_size() % 3 != 0) {
    return InvalidArgument(where + " has " + std::to_string(m.vertices_size()) +
                           " coordinates, not a multiple of 3");
  }
  if (!m.vertices().empty() && !soup_.faces.empty()) {
    return InvalidArgument(where + " sends vertices after faces");
  }
  if (soup_.vertices.size() + m.vertices_size() / 3 > max_vertices_) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "the mesh has more than " +
                          std::to_string(max_vertices_) +
                          " vertices, the server's limit");
  }
  for (int i = 0; i < m.vertices_size(); i += 3) {
    soup_.vertices.push_back(
        {m.vertices(i), m.vertices(i + 1), m.vertices(i + 2)});
  }
  if (m.face_sizes().empty()) {
    if (m.faces_size() % 3 != 0) {
      return InvalidArgument(where + " has " + std::to_string(m.faces_size()) +
                             " face indices, not a multiple of 3 (give "
                             "face_sizes for polygons)");
    }
  } else {
    size_t total = 0;
    for (uint32_t k : m.face_sizes()) {
      if (k < 3) {
        return InvalidArgument(where + " has a face of " + std::to_string(k) +
                               " corners; a face needs at least 3");
      }
      total += k;
    }
    if (total != static_cast<size_t>(m.faces_size())) {
      return InvalidArgument(
          where + ": face_sizes add up to " + std::to_string(total) + " but " +
          std::to_string(m.faces_size()) + " face indices were sent");
    }
  }
  const size_t faces = m.face_sizes().empty()
                           ? static_cast<size_t>(m.faces_size()) / 3
                           : static_cast<size_t>(m.face_sizes_size());
  if (soup_.faces.size() + faces > max_faces_) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "the mesh has more than " + std::to_string(max_faces_) +
                          " faces, the server's limit");
  }
  // Corners, not faces, are what polygons cost (each is triangulated).
  corners_ += static_cast<size_t>(m.faces_size());
  if (corners_ > 3 * max_faces_) {
    return MakeStatus(StatusCode::kResourceExhausted,
                      "the mesh's faces have more than " +
                          std::to_string(3 * max_faces_) +
                          " corners in all, the server's limit");
  }
  for (uint32_t k : m.face_sizes()) {
    if (k > kMaxPolygonCorners) {
      return InvalidArgument(
          where + " has a face of " + std::to_string(k) + " corners; at most " +
          std::to_string(kMaxPolygonCorners) + " are accepted");
    }
  }
  int next = 0;
  for (size_t f = 0; f < faces; ++f) {
    const int k =
        m.face_sizes().empty() ? 3 : static_cast<int>(m.face_sizes(f));
    std::vector<int32_t> face;
    for (int c = 0; c < k; ++c) {
      const uint32_t v = m.faces(next++);
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

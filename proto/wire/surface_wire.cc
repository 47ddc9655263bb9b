// SPDX-License-Identifier: AGPL-3.0-or-later
#include "wire/surface_wire.h"

#include <algorithm>

#include "wire/fill_wire.h"
#include "wire/wire.h"

namespace dot::wire {

Status SurfaceOptionsFromWire(const v1::SurfaceOptions& wire,
                              SurfaceOptions* o) {
  *o = {};
  if (wire.has_weights()) o->weights = FromWire(wire.weights());
  o->scale_free_weights = !wire.absolute_weights();
  const Status stage = FillStageFromWire(wire.stage(), &o->stage);
  if (!stage.ok()) return stage;
  if (wire.density() != 0) o->density = wire.density();  // 0: the default
  if (wire.has_fairing_continuity()) {
    o->fairing_continuity = wire.fairing_continuity();
  }
  o->skip_longest = wire.skip_longest();
  o->walls = wire.walls();
  o->weld_distance = wire.weld_distance();
  switch (wire.islands()) {
    case v1::NETWORK_ISLANDS_INSET:
      o->islands = NetworkIslands::kInset;
      break;
    case v1::NETWORK_ISLANDS_HOLE:
      o->islands = NetworkIslands::kHole;
      break;
    case v1::NETWORK_ISLANDS_OFF:
      o->islands = NetworkIslands::kOff;
      break;
    default:
      return InvalidArgument("unknown islands mode " +
                             std::to_string(wire.islands()) +
                             " (NETWORK_ISLANDS_INSET, _HOLE or _OFF)");
  }
  for (const v1::VertexCycle& c : wire.cycles()) {
    std::vector<std::vector<int32_t>> loops;
    for (const v1::VertexLoop& l : c.loops()) {
      std::vector<int32_t> ids;
      for (uint32_t v : l.vertices()) {
        ids.push_back(static_cast<int32_t>(std::min<uint32_t>(v, INT32_MAX)));
      }
      loops.push_back(std::move(ids));
    }
    o->cycles.push_back(std::move(loops));
  }
  return CheckSurfaceOptions(*o);
}

v1::PatchStatus PatchStatusToWire(PatchStatus s) {
  switch (s) {
    case PatchStatus::kSurfaced:
      return v1::PATCH_STATUS_SURFACED;
    case PatchStatus::kFailed:
      return v1::PATCH_STATUS_FAILED;
    case PatchStatus::kSkipped:
      return v1::PATCH_STATUS_SKIPPED;
  }
  return v1::PATCH_STATUS_UNSPECIFIED;
}

PatchStatus PatchStatusFromWire(v1::PatchStatus s) {
  switch (s) {
    case v1::PATCH_STATUS_SURFACED:
      return PatchStatus::kSurfaced;
    case v1::PATCH_STATUS_SKIPPED:
      return PatchStatus::kSkipped;
    default:
      return PatchStatus::kFailed;
  }
}

void SurfaceReportToWire(const SurfaceReport& r, size_t input_vertices,
                         const MeshData& mesh, v1::SurfaceReport* out) {
  out->Clear();
  out->set_version(1);
  for (const auto& curve : r.curve_vertices) {
    out->add_curves()->mutable_vertices()->Add(curve.begin(), curve.end());
  }
  out->set_junctions(static_cast<uint32_t>(r.junctions));
  out->set_merged_vertices(static_cast<uint32_t>(r.merged_vertices));
  out->mutable_dangling()->Add(r.dangling.begin(), r.dangling.end());
  for (const std::string& n : r.notes) out->add_notes(n);
  for (const PatchReport& p : r.patches) {
    v1::PatchReport* w = out->add_patches();
    w->set_id(static_cast<uint32_t>(p.id));
    for (size_t l = 0; l < p.loops.size(); ++l) {
      v1::PatchLoop* loop = w->add_loops();
      for (const CurveUse& u : p.loops[l]) {
        v1::CurveUse* cu = loop->add_curves();
        cu->set_curve(static_cast<uint32_t>(u.curve));
        cu->set_reversed(u.reversed);
      }
      if (l < p.loop_vertices.size()) {
        loop->mutable_vertices()->Add(p.loop_vertices[l].begin(),
                                      p.loop_vertices[l].end());
      }
    }
    w->set_boundary_vertices(static_cast<uint32_t>(p.boundary_vertices));
    w->set_status(PatchStatusToWire(p.status));
    w->set_reason(p.reason);
    if (p.space != SpaceUsed::kNone) {
      w->set_search_space_used(std::string(SpaceUsedName(p.space)));
    }
    if (p.solver != Solver::kNone) {
      w->set_solver(std::string(SolverName(p.solver)));
    }
    w->set_cost(p.cost);
    w->set_resolves(static_cast<uint32_t>(p.resolves));
    w->set_fan(p.fan);
    w->set_triangles(static_cast<uint32_t>(p.triangles));
    w->set_refined_vertices(static_cast<uint32_t>(p.refined_vertices));
    w->set_faired(p.faired);
    w->set_triangulate_ms(p.triangulate_ms);
    w->set_refine_ms(p.refine_ms);
  }
  out->set_surfaced(static_cast<uint32_t>(r.surfaced));
  out->set_failed(static_cast<uint32_t>(r.failed));
  out->set_closed(r.closed);
  out->set_non_manifold_curves(static_cast<uint32_t>(r.non_manifold_curves));
  out->set_faired_whole(r.faired_whole);
  out->set_intersecting_pairs(static_cast<uint32_t>(
      std::min<int64_t>(r.intersecting_pairs, UINT32_MAX)));
  out->set_cycles_ms(r.cycles_ms);
  out->set_triangulate_ms(r.triangulate_ms);
  out->set_refine_ms(r.refine_ms);
  out->set_fair_ms(r.fair_ms);
  out->set_check_ms(r.check_ms);
  out->set_total_ms(r.total_ms);
  out->set_input_vertices(static_cast<uint32_t>(input_vertices));
  out->set_mesh_vertices(static_cast<uint32_t>(mesh.vertices.size()));
  out->set_mesh_faces(static_cast<uint32_t>(mesh.triangles.size()));
}

PolygonSoup SoupFromNetwork(const CurveNetwork& network) {
  PolygonSoup soup;
  soup.vertices = network.vertices;
  for (const auto& line : network.polylines) soup.faces.push_back(line);
  if (!network.normals.empty()) {
    AttributeChannel normal{"normal", 3, {}, {}};
    for (const Vec3& n : network.normals) {
      normal.values.push_back(static_cast<float>(n.x));
      normal.values.push_back(static_cast<float>(n.y));
      normal.values.push_back(static_cast<float>(n.z));
    }
    soup.attributes.push_back(std::move(normal));
  }
  return soup;
}

Status NetworkFromSoup(PolygonSoup soup, CurveNetwork* network) {
  *network = {};
  for (const AttributeChannel& c : soup.attributes) {
    if (c.name != "normal" || c.dims != 3 || c.per_corner()) {
      return InvalidArgument(
          "a network carries one attribute channel, \"normal\" (3 floats "
          "per vertex); got \"" +
          c.name + "\"");
    }
    for (size_t e = 0; e < c.entries(); ++e) {
      const float* v = c.entry(e);
      network->normals.push_back({v[0], v[1], v[2]});
    }
  }
  network->vertices = std::move(soup.vertices);
  for (FaceView f : soup.faces)
    network->polylines.emplace_back(f.begin(), f.end());
  return OkStatus();
}

SurfaceRequestWriter::SurfaceRequestWriter(std::string id,
                                           v1::SurfaceOptions options,
                                           const PolygonSoup& soup,
                                           size_t max_bytes)
    : id_(std::move(id)),
      options_(std::move(options)),
      chunks_(soup, max_bytes) {}

bool SurfaceRequestWriter::Next(v1::SurfaceNetworkRequest* m) {
  m->Clear();
  const bool first = first_;
  if (first_) {
    first_ = false;
    m->set_id(id_);
    *m->mutable_options() = options_;
  }
  return chunks_.Next(m->mutable_network()) || first;
}

Status SurfaceRequestReader::Add(const v1::SurfaceNetworkRequest& m) {
  const std::string where = "message " + std::to_string(messages_);
  if (messages_++ == 0) {
    id_ = m.id();
    options_ = m.options();
  } else if (!m.id().empty() || m.has_options()) {
    return InvalidArgument(where +
                           ": id and options belong in the first message");
  }
  return chunks_.Add(m.network(), where);
}

Status SurfaceRequestReader::Finish(CurveNetwork* network) {
  if (messages_ == 0) return InvalidArgument("no network was sent");
  if (chunks_.faces() == 0) {
    return InvalidArgument("the network has no polylines");
  }
  PolygonSoup soup;
  const Status s = chunks_.Finish(&soup);
  if (!s.ok()) return s;
  return NetworkFromSoup(std::move(soup), network);
}

}  // namespace dot::wire

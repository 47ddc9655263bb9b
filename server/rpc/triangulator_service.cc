// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/triangulator_service.h"

#include <filesystem>

#include "rpc/batch_reactor.h"
#include "rpc/fill_holes_reactor.h"
#include "rpc/raw_message.h"
#include "rpc/source_reactor.h"
#include "rpc/surface_network_reactor.h"
#include "rpc/triangulate_reactor.h"

#ifndef DOT_VERSION
#define DOT_VERSION "unknown"
#endif
#ifndef DOT_BUILD_INFO
#define DOT_BUILD_INFO "unknown"
#endif

namespace dot::server {

TriangulatorService::TriangulatorService(JobRunner* runner,
                                         const SpaceCache* cache,
                                         const DelaunayHelperPool* helpers)
    : runner_(runner), cache_(cache), helpers_(helpers) {}

// Reactors are created with new and delete themselves in OnDone: the
// ownership model of gRPC's callback API.
grpc::ServerWriteReactor<grpc::ByteBuffer>* TriangulatorService::Triangulate(
    grpc::CallbackServerContext* context, const grpc::ByteBuffer* request) {
  return new TriangulateReactor(runner_, context, *request);
}

grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>*
TriangulatorService::TriangulateBatch(grpc::CallbackServerContext* context) {
  return new BatchReactor(runner_, context);
}

grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>*
TriangulatorService::FillHoles(grpc::CallbackServerContext* context) {
  return new FillHolesReactor(runner_, context);
}

grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>*
TriangulatorService::SurfaceNetwork(grpc::CallbackServerContext* context) {
  return new SurfaceNetworkReactor(runner_, context);
}

grpc::ServerWriteReactor<grpc::ByteBuffer>* TriangulatorService::GetSource(
    grpc::CallbackServerContext*, const grpc::ByteBuffer* request) {
  grpc::ByteBuffer bytes = *request;
  v1::GetSourceRequest parsed;
  if (!ParseRaw(&bytes, &parsed)) {
    return new SourceReactor(
        UnparsableRequest("GetSource", "GetSourceRequest"));
  }
  return new SourceReactor(runner_->options());
}

grpc::ServerUnaryReactor* TriangulatorService::GetServerInfo(
    grpc::CallbackServerContext* context, const grpc::ByteBuffer* request,
    grpc::ByteBuffer* response) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  grpc::ByteBuffer bytes = *request;
  v1::GetServerInfoRequest parsed;
  if (!ParseRaw(&bytes, &parsed)) {
    reactor->Finish(UnparsableRequest("GetServerInfo", "GetServerInfoRequest"));
    return reactor;
  }
  v1::ServerInfo info;
  FillServerInfo(&info);
  SerializeRaw(info, response);
  reactor->Finish(grpc::Status::OK);
  return reactor;
}

void TriangulatorService::FillServerInfo(v1::ServerInfo* info) const {
  const ServiceOptions& o = runner_->options();
  const DelaunayBackend preferred = o.solve.delaunay;
  auto def = [preferred](DelaunayBackend b) {
    return b == preferred ? std::string(" (default)") : std::string();
  };
  info->set_version(DOT_VERSION);
  info->set_build(DOT_BUILD_INFO);
  info->add_backends("cgal-5.5 Delaunay 3D" + def(DelaunayBackend::kCgal));
  if (TetgenAvailable()) {
    info->add_backends(helpers_ ? "tetgen-1.5 (helper processes)" +
                                      def(DelaunayBackend::kTetgen)
                                : std::string("tetgen-1.5: off on this server "
                                              "(--delaunay-helpers 0)"));
  } else {
    info->add_backends("tetgen: not in this build (DOT_WITH_TETGEN=OFF)");
  }
  info->add_backends("cgal-5.5 constrained Delaunay 2D (planar polygons)");
  info->add_backends("all-triangles GK1/GK2");
  v1::Limits* l = info->mutable_limits();
  l->set_fill_max_vertices(static_cast<uint64_t>(o.fill_max_vertices));
  l->set_fill_max_faces(static_cast<uint64_t>(o.fill_max_faces));
  l->set_fill_memory_bytes(static_cast<uint64_t>(o.fill_memory_bytes));
  l->set_max_vertices(o.max_vertices);
  l->set_max_compute_ms(o.max_compute_ms);
  l->set_memory_budget_bytes(o.solve.memory_budget_bytes);
  l->set_compute_threads(runner_->compute_threads());
  l->set_cache_bytes(cache_ ? static_cast<uint64_t>(cache_->max_bytes()) : 0);
  l->set_queue_size(runner_->queue_capacity());
  l->set_all_space_max_vertices(o.solve.all_space_max_vertices);
  l->set_max_message_bytes(o.max_message_bytes);
  info->set_license("AGPL-3.0-or-later");
  info->set_source_url(o.source_url);
  std::error_code ec;
  const bool archive = !o.source_archive.empty() &&
                       std::filesystem::is_regular_file(o.source_archive, ec);
  std::string where;
  if (archive) where = "call GetSource (dotctl source -o dot-source.tar.gz)";
  if (!o.source_url.empty()) {
    where += (where.empty() ? "download it from " : " or download it from ") +
             o.source_url;
  }
  if (where.empty()) where = "ask this server's operator for it";
  info->set_source_note(
      "This service is free software under the GNU AGPL v3 or later (it "
      "links TetGen, AGPL-3.0+). Its complete corresponding source is "
      "available to every user: " +
      where + ".");
}

}  // namespace dot::server

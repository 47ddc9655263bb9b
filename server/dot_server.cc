// SPDX-License-Identifier: AGPL-3.0-or-later
#include "dot_server.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>
#include <spdlog/spdlog.h>

#include <fstream>
#include <sstream>
#include <thread>

namespace dot::server {
namespace {

std::string ReadFile(const std::string& path, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = "cannot read '" + path + "'";
    return "";
  }
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::shared_ptr<grpc::ServerCredentials> Credentials(const ServerConfig& c,
                                                     std::string* error) {
  if (c.tls_cert.empty()) return grpc::InsecureServerCredentials();
  grpc::SslServerCredentialsOptions options(
      c.tls_client_ca.empty()
          ? GRPC_SSL_DONT_REQUEST_CLIENT_CERTIFICATE
          : GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY);
  options.pem_key_cert_pairs.push_back(
      {ReadFile(c.tls_key, error), ReadFile(c.tls_cert, error)});
  if (!c.tls_client_ca.empty()) {
    options.pem_root_certs = ReadFile(c.tls_client_ca, error);
  }
  return error->empty() ? grpc::SslServerCredentials(options) : nullptr;
}

}  // namespace

std::unique_ptr<DotServer> DotServer::Start(ServerConfig config,
                                            std::string* error) {
  *error = FinalizeConfig(&config);
  if (!error->empty()) return nullptr;
  std::unique_ptr<DotServer> s(new DotServer());
  s->config_ = config;
  try {
    s->metrics_ = std::make_unique<ServerMetrics>(config.metrics_bind,
                                                  config.metrics_port);
  } catch (const std::exception& e) {
    *error = "cannot serve metrics on " + config.metrics_bind + ":" +
             std::to_string(config.metrics_port) + ": " + e.what();
    return nullptr;
  }
  if (config.delaunay_helpers > 0) {
    s->helpers_ = std::make_unique<DelaunayHelperPool>(
        HelperConfig{config.helper_path, config.delaunay_helpers,
                     config.helper_memory_mb << 20});
  }
  s->pool_ = std::make_unique<ComputePool>(config.threads, config.queue_size);
  ServiceLimits limits;
  limits.max_vertices = config.max_vertices;
  limits.max_compute_ms = config.max_compute_ms;
  limits.memory_budget_bytes = config.memory_budget_mb << 20;
  limits.all_space_max_vertices = config.all_space_max_vertices;
  limits.chunk_bytes = static_cast<size_t>(config.chunk_kb) * 1024;
  limits.max_message_bytes = config.max_message_mb << 20;
  limits.threads = config.threads;
  limits.queue_size = config.queue_size;
  ParseDelaunayBackend(config.delaunay_backend, &limits.delaunay_backend);
  if (config.cache_mb > 0) {
    s->cache_ = std::make_unique<SpaceCache>(config.cache_mb << 20);
  }
  limits.inline_max_vertices = config.inline_max_vertices;
  limits.source_archive = config.source_archive;
  limits.source_url = config.source_url;
  s->service_ = std::make_unique<TriangulatorService>(
      limits, s->pool_.get(), s->helpers_.get(), s->cache_.get(),
      s->metrics_.get());

  auto credentials = Credentials(config, error);
  if (!credentials) return nullptr;
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  builder.AddListeningPort(config.listen, credentials, &s->port_);
  builder.RegisterService(s->service_.get());
  builder.SetMaxReceiveMessageSize(limits.max_message_bytes);
  builder.SetMaxSendMessageSize(limits.max_message_bytes);
  // Keepalive: notice dead clients; let clients ping idle connections.
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIME_MS, 60 * 1000);
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, 20 * 1000);
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_PERMIT_WITHOUT_CALLS, 1);
  builder.AddChannelArgument(
      GRPC_ARG_HTTP2_MIN_RECV_PING_INTERVAL_WITHOUT_DATA_MS, 10 * 1000);
  if (config.max_connection_age_s > 0) {
    // Long-lived HTTP/2 connections pin clients to replicas; recycling
    // them lets new replicas take load.
    builder.AddChannelArgument(GRPC_ARG_MAX_CONNECTION_AGE_MS,
                               config.max_connection_age_s * 1000);
    builder.AddChannelArgument(GRPC_ARG_MAX_CONNECTION_AGE_GRACE_MS,
                               config.max_compute_ms + 5000);
  }
  s->server_ = builder.BuildAndStart();
  if (!s->server_ || s->port_ == 0) {
    *error = "cannot listen on " + config.listen;
    return nullptr;
  }
  s->server_->GetHealthCheckService()->SetServingStatus(true);
  spdlog::info(
      "dot-server listening on {} (port {}), {} compute threads, queue {}, "
      "{} Delaunay helpers, metrics {}",
      config.listen, s->port_, config.threads, config.queue_size,
      config.delaunay_helpers,
      config.metrics_port > 0
          ? config.metrics_bind + ":" + std::to_string(config.metrics_port)
          : std::string("off"));
  return s;
}

void DotServer::Drain(std::chrono::milliseconds grace) {
  if (drained_) return;
  drained_ = true;
  server_->GetHealthCheckService()->SetServingStatus(false);
  service_->StartDraining();
  const auto until = std::chrono::steady_clock::now() + grace;
  spdlog::info("draining: {} requests in flight, up to {} ms",
               service_->inflight(), grace.count());
  while (service_->inflight() > 0 && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (service_->inflight() > 0) {
    spdlog::warn("cancelling {} requests still in flight",
                 service_->inflight());
    service_->CancelAll();
  }
  server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  spdlog::info("stopped");
}

DotServer::~DotServer() {
  if (server_) Drain(std::chrono::milliseconds(0));
}

}  // namespace dot::server

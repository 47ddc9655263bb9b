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

// The PEM file at `path`, which must hold a block whose BEGIN line ends in
// `label` ("CERTIFICATE", "PRIVATE KEY"); `flag` names it in the error.
std::string ReadPem(const std::string& flag, const std::string& path,
                    const std::string& label, std::string* error) {
  if (!error->empty()) return "";
  std::ifstream in(path);
  std::ostringstream s;
  if (in) s << in.rdbuf();
  const std::string text = s.str();
  if (text.empty()) {
    *error =
        flag + ": cannot read '" + path + "' (missing, empty or not a file)";
    return "";
  }
  const size_t begin = text.find("-----BEGIN ");
  if (begin == std::string::npos ||
      text.find(label + "-----", begin) == std::string::npos) {
    *error = flag + ": '" + path + "' holds no PEM " + label;
  }
  return text;
}

std::shared_ptr<grpc::ServerCredentials> Credentials(const TlsOptions& tls,
                                                     std::string* error) {
  if (tls.cert.empty()) return grpc::InsecureServerCredentials();
  grpc::SslServerCredentialsOptions options(
      tls.client_ca.empty()
          ? GRPC_SSL_DONT_REQUEST_CLIENT_CERTIFICATE
          : GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY);
  options.pem_key_cert_pairs.push_back(
      {ReadPem("--tls-key", tls.key, "PRIVATE KEY", error),
       ReadPem("--tls-cert", tls.cert, "CERTIFICATE", error)});
  if (!tls.client_ca.empty()) {
    options.pem_root_certs =
        ReadPem("--tls-client-ca", tls.client_ca, "CERTIFICATE", error);
  }
  return error->empty() ? grpc::SslServerCredentials(options) : nullptr;
}

}  // namespace

std::unique_ptr<DotServer> DotServer::Start(ServerConfig config,
                                            std::string* error) {
  *error = FinalizeConfig(&config);
  if (!error->empty()) return nullptr;
  std::unique_ptr<DotServer> s(new DotServer());
  s->config_ = std::move(config);
  const ServerConfig& c = s->config_;
  try {
    s->metrics_ = std::make_unique<ServerMetrics>(c.metrics);
  } catch (const std::exception& e) {
    *error = "cannot serve metrics on " + c.metrics.bind + ":" +
             std::to_string(c.metrics.port) + ": " + e.what();
    return nullptr;
  }
  if (c.helpers.count > 0) {
    s->helpers_ = std::make_unique<DelaunayHelperPool>(c.helpers);
  }
  s->pool_ = std::make_unique<ComputePool>(c.pool);
  if (c.cache_bytes > 0)
    s->cache_ = std::make_unique<SpaceCache>(c.cache_bytes);
  s->jobs_ =
      std::make_unique<JobRunner>(c.service, s->pool_.get(), s->helpers_.get(),
                                  s->cache_.get(), s->metrics_.get());
  s->service_ = std::make_unique<TriangulatorService>(
      s->jobs_.get(), s->cache_.get(), s->helpers_.get());

  auto credentials = Credentials(c.tls, error);
  if (!credentials) return nullptr;
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  builder.AddListeningPort(c.listen, credentials, &s->port_);
  builder.RegisterService(s->service_.get());
  // One server per port: without this, gRPC's SO_REUSEPORT lets a second
  // server start on a taken port and silently take half the calls.
  builder.AddChannelArgument(GRPC_ARG_ALLOW_REUSEPORT, 0);
  builder.SetMaxReceiveMessageSize(c.service.max_message_bytes);
  builder.SetMaxSendMessageSize(c.service.max_message_bytes);
  // Keepalive: notice dead clients; let clients ping idle connections.
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIME_MS, 60 * 1000);
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, 20 * 1000);
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_PERMIT_WITHOUT_CALLS, 1);
  builder.AddChannelArgument(
      GRPC_ARG_HTTP2_MIN_RECV_PING_INTERVAL_WITHOUT_DATA_MS, 10 * 1000);
  if (c.max_connection_age_s > 0) {
    // Long-lived HTTP/2 connections pin clients to replicas; recycling
    // them lets new replicas take load.
    builder.AddChannelArgument(GRPC_ARG_MAX_CONNECTION_AGE_MS,
                               c.max_connection_age_s * 1000);
    builder.AddChannelArgument(GRPC_ARG_MAX_CONNECTION_AGE_GRACE_MS,
                               c.service.max_compute_ms + 5000);
  }
  s->server_ = builder.BuildAndStart();
  if (!s->server_ || s->port_ == 0) {
    *error = "cannot listen on " + c.listen;
    if (!c.tls.cert.empty()) {
      // gRPC says which in its own log line; a key that does not match the
      // certificate is the usual cause.
      *error +=
          " (the address is in use or not valid, or gRPC refused the "
          "TLS certificate and key: see its error above)";
    }
    return nullptr;
  }
  if (!c.health_listen.empty()) {
    // Only the default health service is registered here: the API stays
    // behind the main port's credentials.
    grpc::ServerBuilder health;
    health.AddListeningPort(c.health_listen, grpc::InsecureServerCredentials(),
                            &s->health_port_);
    health.AddChannelArgument(GRPC_ARG_ALLOW_REUSEPORT, 0);
    s->health_server_ = health.BuildAndStart();
    if (!s->health_server_ || s->health_port_ == 0) {
      *error = "cannot listen on " + c.health_listen + " (--health-listen)";
      s->server_->Shutdown();
      return nullptr;
    }
  }
  // Health answers for the whole server ("") and by service name.
  for (const std::string& note : c.notes) spdlog::warn("{}", note);
  s->SetServing(true);
  spdlog::info(
      "dot-server listening on {} (port {}), {} compute threads, queue {}, "
      "{} Delaunay helpers, metrics {}",
      c.listen, s->port_, c.pool.threads, c.pool.queue_size, c.helpers.count,
      c.metrics.port > 0 ? c.metrics.bind + ":" + std::to_string(c.metrics.port)
                         : std::string("off"));
  return s;
}

void DotServer::SetServing(bool serving) {
  for (grpc::Server* server : {server_.get(), health_server_.get()}) {
    if (server == nullptr) continue;
    server->GetHealthCheckService()->SetServingStatus(serving);
    server->GetHealthCheckService()->SetServingStatus(
        v1::Triangulator::service_full_name(), serving);
  }
}

void DotServer::Drain(std::chrono::milliseconds grace) {
  if (drained_.exchange(true)) return;
  SetServing(false);
  jobs_->StartDraining();
  // Work still running at 80% of the grace period is stopped; the rest
  // (at least 2 s) lets stopped fills send the holes they finished.
  const auto start = std::chrono::steady_clock::now();
  const auto until = start + grace * 4 / 5;
  spdlog::info("draining: {} requests in flight, up to {} ms",
               jobs_->inflight(), grace.count());
  while (jobs_->inflight() > 0 && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (jobs_->inflight() > 0) {
    spdlog::warn("cancelling {} requests still in flight", jobs_->inflight());
    jobs_->CancelAllForDrain();
  }
  const auto answers = std::max<std::chrono::steady_clock::duration>(
      std::chrono::seconds(2),
      start + grace - std::chrono::steady_clock::now());
  server_->Shutdown(std::chrono::system_clock::now() + answers);
  if (health_server_) health_server_->Shutdown();
  spdlog::info("stopped");
}

DotServer::~DotServer() {
  if (server_) Drain(std::chrono::milliseconds(0));
}

}  // namespace dot::server

// SPDX-License-Identifier: AGPL-3.0-or-later
#include "remote/grpc_calls.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <thread>
#include <utility>

#include "dot/elapsed.h"
#include "wire/fill_wire.h"
#include "wire/soup_wire.h"
#include "wire/surface_wire.h"
#include "wire/wire.h"

namespace dot::client {
namespace {

using Clock = std::chrono::steady_clock;

// Requests stay well under gRPC's default 4 MiB message limit.
constexpr size_t kRequestBytes = 1 << 20;

void SetDeadline(grpc::ClientContext* context, double seconds) {
  context->set_deadline(
      std::chrono::system_clock::now() +
      std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000)));
}

std::string ReadFile(const std::string& path, std::string* error) {
  std::ifstream in(path);
  if (!in) *error = "cannot read '" + path + "'";
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

std::shared_ptr<grpc::Channel> MakeChannel(const ConnectionFlags& f,
                                           std::string* error) {
  std::shared_ptr<grpc::ChannelCredentials> creds;
  if (f.tls_ca.empty()) {
    creds = grpc::InsecureChannelCredentials();
  } else {
    grpc::SslCredentialsOptions o;
    o.pem_root_certs = ReadFile(f.tls_ca, error);
    if (!f.tls_cert.empty()) {
      o.pem_cert_chain = ReadFile(f.tls_cert, error);
      o.pem_private_key = ReadFile(f.tls_key, error);
    }
    if (!error->empty()) return nullptr;
    creds = grpc::SslCredentials(o);
  }
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(64 << 20);
  args.SetMaxSendMessageSize(64 << 20);
  if (!f.tls_server_name.empty()) {
    args.SetSslTargetNameOverride(f.tls_server_name);
  }
  // Retries: UNAVAILABLE (a replica draining or gone) is safe to retry, the
  // call having done nothing. Round robin spreads calls over every address
  // the name resolves to (one per pod behind a headless Service).
  args.SetServiceConfigJSON(R"({
    "loadBalancingConfig": [{"round_robin": {}}],
    "methodConfig": [{
      "name": [{"service": "dot.v1.Triangulator"}],
      "retryPolicy": {
        "maxAttempts": 5,
        "initialBackoff": "0.05s",
        "maxBackoff": "1s",
        "backoffMultiplier": 2,
        "retryableStatusCodes": ["UNAVAILABLE"]
      }
    }]
  })");
  return grpc::CreateCustomChannel(f.server, creds, args);
}

CallOutcome TriangulateRemote(
    v1::Triangulator::Stub& stub, const v1::TriangulateRequest& request,
    const std::vector<Vec3>& input, double timeout_s,
    const std::function<void(const v1::Progress&)>& on_progress) {
  const auto t0 = Clock::now();
  CallOutcome out;
  grpc::ClientContext context;
  SetDeadline(&context, timeout_s);
  auto reader = stub.Triangulate(&context, request);
  v1::TriangulateResponse msg;
  wire::MeshAssembler assembler;
  bool have_summary = false;
  Status assembly = OkStatus();
  while (reader->Read(&msg)) {
    if (msg.has_progress() && on_progress) on_progress(msg.progress());
    if (msg.has_mesh() && assembly.ok()) assembly = assembler.Add(msg.mesh());
    if (msg.has_summary()) {
      out.summary = msg.summary();
      have_summary = true;
    }
  }
  out.status = reader->Finish();
  if (out.status.ok() && !have_summary) {
    out.status = {grpc::StatusCode::DATA_LOSS,
                  "stream ended without a summary"};
  }
  if (out.status.ok() && assembly.ok() &&
      out.summary.status() == v1::RESULT_STATUS_OK) {
    assembly = assembler.Finish(out.summary, input, &out.mesh);
  }
  if (out.status.ok() && !assembly.ok()) {
    out.status = {grpc::StatusCode::DATA_LOSS, assembly.message};
  }
  out.latency_ms = MsSince(t0);
  return out;
}

FillOutcome FillRemote(v1::Triangulator::Stub& stub, const std::string& id,
                       const v1::FillOptions& options, const PolygonSoup& mesh,
                       double timeout_s, const FillProgressFn& on_progress) {
  const auto t0 = Clock::now();
  FillOutcome out;
  grpc::ClientContext context;
  SetDeadline(&context, timeout_s);
  auto stream = stub.FillHoles(&context);
  wire::FillRequestWriter requests(id, options, mesh, kRequestBytes);
  v1::FillHolesRequest request;
  while (requests.Next(&request)) {
    if (!stream->Write(request)) break;  // the server answered early
  }
  stream->WritesDone();
  // Polygons or attributes kept come as a soup; plain triangles as before.
  const bool as_sent = options.answer() == v1::FILL_ANSWER_MESH &&
                       !options.dry_run() &&
                       (!mesh.attributes.empty() || options.keep_polygons());
  wire::MeshAssembler assembler;
  wire::SoupChunkReader soup(UINT32_MAX, UINT32_MAX);
  wire::PatchReader patches(mesh.vertices.size());
  size_t chunk = 0;
  v1::FillHolesResponse response;
  bool have_report = false;
  Status assembled = OkStatus();
  while (stream->Read(&response)) {
    switch (response.payload_case()) {
      case v1::FillHolesResponse::kProgress:
        if (on_progress) on_progress(response.progress());
        break;
      case v1::FillHolesResponse::kMesh:
        if (!assembled.ok()) break;
        assembled = as_sent ? soup.Add(response.mesh(),
                                       "mesh chunk " + std::to_string(chunk++))
                            : assembler.Add(response.mesh());
        break;
      case v1::FillHolesResponse::kPatch:
        if (assembled.ok()) assembled = patches.Add(response.patch());
        break;
      case v1::FillHolesResponse::kReport:
        out.report = response.report();
        have_report = true;
        break;
      default:
        break;
    }
  }
  out.status = stream->Finish();
  out.latency_ms = MsSince(t0);
  // A fill that stopped early still answers whole, then says why it
  // stopped; anything else that is not OK brings nothing to keep.
  out.partial = !out.status.ok() && have_report && out.report.stopped() > 0;
  if (!out.status.ok() && !out.partial) return out;
  if (!have_report) {
    out.status = grpc::Status(grpc::StatusCode::INTERNAL,
                              "the server ended the stream without a report");
    return out;
  }
  const size_t vertices =
      out.report.input_vertices() + out.report.added_vertices();
  const size_t faces = out.report.input_faces() + out.report.added_faces();
  out.notes.assign(out.report.notes().begin(), out.report.notes().end());
  if (assembled.ok() && as_sent) {
    assembled = soup.Finish(&out.soup);
    if (assembled.ok() && out.soup.vertices.size() != vertices) {
      assembled = InvalidArgument(std::to_string(out.soup.vertices.size()) +
                                  " vertices received, the report announced " +
                                  std::to_string(vertices));
    }
    // Polygons kept make fewer faces than the report's triangles.
    if (assembled.ok() && !options.keep_polygons() &&
        out.soup.faces.size() != faces) {
      assembled = InvalidArgument(std::to_string(out.soup.faces.size()) +
                                  " faces received, the report announced " +
                                  std::to_string(faces));
    }
    // A server that could not carry a channel says so in a note; one from
    // before attributes on the wire ignores them.
    for (const AttributeChannel& sent : mesh.attributes) {
      const bool answered = std::any_of(
          out.soup.attributes.begin(), out.soup.attributes.end(),
          [&](const AttributeChannel& a) { return a.name == sent.name; });
      const bool noted = std::any_of(
          out.notes.begin(), out.notes.end(), [&](const std::string& n) {
            return n.find("'" + sent.name + "'") != std::string::npos;
          });
      if (assembled.ok() && !answered && !noted) {
        out.notes.push_back("attribute '" + sent.name +
                            "' was not answered: the server predates "
                            "attributes on the wire (--local carries it)");
      }
    }
    out.as_sent = assembled.ok();
  } else if (assembled.ok() && options.answer() == v1::FILL_ANSWER_MESH &&
             !options.dry_run()) {  // a dry run's answer is the report alone
    assembled = assembler.Finish(vertices, faces, {}, &out.mesh);
  }
  out.patches = std::move(patches.patches());
  if (!assembled.ok()) {
    out.partial = false;
    out.status = grpc::Status(grpc::StatusCode::INTERNAL,
                              "bad mesh from the server: " + assembled.message);
  }
  return out;
}

SurfaceOutcome SurfaceRemote(v1::Triangulator::Stub& stub,
                             const std::string& id,
                             const v1::SurfaceOptions& options,
                             const CurveNetwork& network, double timeout_s,
                             const SurfaceProgressFn& on_progress) {
  const auto t0 = Clock::now();
  SurfaceOutcome out;
  grpc::ClientContext context;
  SetDeadline(&context, timeout_s);
  auto stream = stub.SurfaceNetwork(&context);
  const PolygonSoup soup = wire::SoupFromNetwork(network);
  wire::SurfaceRequestWriter requests(id, options, soup, kRequestBytes);
  v1::SurfaceNetworkRequest request;
  while (requests.Next(&request)) {
    if (!stream->Write(request)) break;  // the server answered early
  }
  stream->WritesDone();
  wire::MeshAssembler assembler;
  Status assembled = OkStatus();
  bool have_report = false;
  v1::SurfaceNetworkResponse response;
  while (stream->Read(&response)) {
    switch (response.payload_case()) {
      case v1::SurfaceNetworkResponse::kProgress:
        if (on_progress) on_progress(response.progress());
        break;
      case v1::SurfaceNetworkResponse::kMesh:
        if (assembled.ok()) assembled = assembler.Add(response.mesh());
        break;
      case v1::SurfaceNetworkResponse::kReport:
        out.report = response.report();
        have_report = true;
        break;
      default:
        break;
    }
  }
  out.status = stream->Finish();
  out.latency_ms = MsSince(t0);
  if (!out.status.ok()) return out;
  if (!have_report) {
    out.status = grpc::Status(grpc::StatusCode::INTERNAL,
                              "the server ended the stream without a report");
    return out;
  }
  if (assembled.ok()) {
    assembled = assembler.Finish(out.report.mesh_vertices(),
                                 out.report.mesh_faces(), {}, &out.mesh);
  }
  if (assembled.ok() && out.mesh.vertices.size() < network.vertices.size()) {
    assembled = InvalidArgument(
        "the surface has fewer vertices than the "
        "network sent");
  }
  if (!assembled.ok()) {
    out.status = grpc::Status(grpc::StatusCode::INTERNAL,
                              "bad mesh from the server: " + assembled.message);
  }
  return out;
}

grpc::Status TriangulateBatchRemote(
    v1::Triangulator::Stub& stub,
    std::chrono::system_clock::time_point deadline,
    const std::function<const v1::TriangulateRequest*()>& next,
    const std::function<void(const v1::TriangulateResponse&)>& on_answer,
    const std::function<void()>& reads_done) {
  grpc::ClientContext context;
  context.set_deadline(deadline);
  auto stream = stub.TriangulateBatch(&context);
  std::thread writer([&] {
    while (const v1::TriangulateRequest* request = next()) {
      if (!stream->Write(*request)) break;
    }
    stream->WritesDone();
  });
  v1::TriangulateResponse msg;
  while (stream->Read(&msg)) on_answer(msg);
  if (reads_done) reads_done();  // a writer waiting in `next` goes on
  writer.join();
  return stream->Finish();
}

grpc::Status CheckHealthRemote(
    grpc::health::v1::Health::Stub& stub, const std::string& service,
    double timeout_s, grpc::health::v1::HealthCheckResponse* response) {
  grpc::ClientContext context;
  SetDeadline(&context, timeout_s);
  grpc::health::v1::HealthCheckRequest request;
  request.set_service(service);
  return stub.Check(&context, request, response);
}

grpc::Status ServerInfoRemote(v1::Triangulator::Stub& stub, double timeout_s,
                              v1::ServerInfo* info) {
  grpc::ClientContext context;
  SetDeadline(&context, timeout_s);
  return stub.GetServerInfo(&context, {}, info);
}

grpc::Status SourceRemote(
    v1::Triangulator::Stub& stub, double timeout_s,
    const std::function<void(const std::string&)>& on_chunk) {
  grpc::ClientContext context;
  SetDeadline(&context, timeout_s);
  auto reader = stub.GetSource(&context, {});
  v1::SourceChunk chunk;
  while (reader->Read(&chunk)) on_chunk(chunk.data());
  return reader->Finish();
}

}  // namespace dot::client

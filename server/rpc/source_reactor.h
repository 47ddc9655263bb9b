// SPDX-License-Identifier: AGPL-3.0-or-later
// GetSource: the server's Corresponding Source (AGPL-3.0 s. 13) streamed
// from its archive in 256 KiB chunks, each read when the last is written.
#ifndef DOT_SERVER_RPC_SOURCE_REACTOR_H_
#define DOT_SERVER_RPC_SOURCE_REACTOR_H_

#include <grpcpp/grpcpp.h>

#include <fstream>
#include <string>

#include "dot/v1/triangulation.pb.h"
#include "rpc/service_options.h"

namespace dot::server {

class SourceReactor final : public grpc::ServerWriteReactor<grpc::ByteBuffer> {
 public:
  explicit SourceReactor(const ServiceOptions& options);
  // Answers `refused` alone (a request that does not parse).
  explicit SourceReactor(const grpc::Status& refused);
  void OnWriteDone(bool ok) override;
  void OnDone() override;

 private:
  void WriteNext();
  std::ifstream in_;
  v1::SourceChunk chunk_;
  grpc::ByteBuffer chunk_bytes_;  // chunk_, serialized, being written
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_SOURCE_REACTOR_H_

// SPDX-License-Identifier: AGPL-3.0-or-later
// Triangulate, the transport: one polygon in, a stream out (progress, mesh
// chunks, summary). The reactor admits the job and starts it; the job's
// completion starts the writes (AnswerStream); OnCancel sets the job's
// cancel flag. No thread waits: every step is a reaction to the job or to
// gRPC.
#ifndef DOT_SERVER_RPC_TRIANGULATE_REACTOR_H_
#define DOT_SERVER_RPC_TRIANGULATE_REACTOR_H_

#include <grpcpp/grpcpp.h>

#include <optional>

#include "dot/v1/triangulation.pb.h"
#include "rpc/answer_stream.h"
#include "rpc/job.h"
#include "rpc/job_response.h"

namespace dot::server {

class TriangulateReactor final
    : public AnswerStream<grpc::ServerWriteReactor<grpc::ByteBuffer>,
                          v1::TriangulateResponse> {
 public:
  // `request` is parsed here: one that does not parse is refused by name.
  TriangulateReactor(JobRunner* runner, grpc::CallbackServerContext* context,
                     grpc::ByteBuffer request);

  void OnCancel() override;

 private:
  grpc::Status NextAnswer(v1::TriangulateResponse* message,
                          bool* last) override;

  std::optional<JobResponse> response_;
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_TRIANGULATE_REACTOR_H_

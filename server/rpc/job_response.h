// SPDX-License-Identifier: AGPL-3.0-or-later
// The answer to one finished job, as the messages of a response stream:
// its mesh in chunks, then its summary; or, when the job failed, the gRPC
// status that replaces them. Messages are made one at a time, so a large
// mesh is never held twice.
#ifndef DOT_SERVER_RPC_JOB_RESPONSE_H_
#define DOT_SERVER_RPC_JOB_RESPONSE_H_

#include <grpcpp/grpcpp.h>

#include <memory>

#include "dot/v1/triangulation.pb.h"
#include "rpc/job.h"
#include "wire/wire.h"

namespace dot::server {

// The gRPC status of a finished job: a drain's cancel is UNAVAILABLE (so
// clients retry elsewhere), the server's time limit is named, other core
// failures map through wire::ToGrpcStatus; OK otherwise (also for "no
// triangulation", which is an answer).
grpc::Status JobStatus(const Job& job, int max_compute_ms);
// The answer to a call stopped for `why`: each reason its own code and
// message (the one place they are worded).
grpc::Status StoppedStatus(StopReason why);

class JobResponse {
 public:
  // `job` must have run (on_done called). `max_compute_ms` is quoted when
  // the server's own time limit stopped the job.
  JobResponse(std::shared_ptr<const Job> job, size_t chunk_bytes,
              int max_compute_ms);

  // OK when the job has an answer to stream (a mesh, or "no
  // triangulation"); otherwise the RPC's (or batch item's) error.
  const grpc::Status& status() const { return status_; }
  // The next message; false once the summary has been given.
  bool Next(v1::TriangulateResponse* message);
  // True once Next has given the summary, the last message.
  bool done() const { return done_; }

 private:
  std::shared_ptr<const Job> job_;
  grpc::Status status_;
  wire::MeshChunker chunks_;
  bool done_ = false;
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_JOB_RESPONSE_H_

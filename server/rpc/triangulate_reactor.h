// SPDX-License-Identifier: AGPL-3.0-or-later
// Triangulate: one polygon in, a stream out (progress, mesh chunks,
// summary). The reactor admits the job and starts it; the job's completion
// starts the writes; OnCancel sets the job's cancel flag. No thread waits:
// every step is a reaction to the job or to gRPC.
#ifndef DOT_SERVER_RPC_TRIANGULATE_REACTOR_H_
#define DOT_SERVER_RPC_TRIANGULATE_REACTOR_H_

#include <grpcpp/grpcpp.h>

#include <memory>
#include <mutex>
#include <optional>

#include "dot/v1/triangulation.pb.h"
#include "rpc/answer_writer.h"
#include "rpc/job.h"
#include "rpc/job_response.h"

namespace dot::server {

class TriangulateReactor final
    : public grpc::ServerWriteReactor<grpc::ByteBuffer> {
 public:
  // `request` is parsed here: one that does not parse is refused by name.
  TriangulateReactor(JobRunner* runner, grpc::CallbackServerContext* context,
                     grpc::ByteBuffer request);

  void OnWriteDone(bool ok) override;
  void OnCancel() override;
  void OnDone() override;

 private:
  // Called on the computing thread.
  void OnProgress(const v1::Progress& progress);
  void OnJobDone();
  // Writes the next message of the answer, or finishes the RPC. Only ever
  // called by whoever holds the (single) right to write.
  void WriteNext();
  void FinishWith(const grpc::Status& status);
  // Starts writing message_ (and finishing with final_status_ when last).
  void Write(bool last);

  JobRunner* const runner_;
  grpc::CallbackServerContext* const context_;
  std::shared_ptr<Job> job_;
  grpc::Status final_status_;

  AnswerWriter writer_;
  std::optional<JobResponse> response_;
  v1::TriangulateResponse message_;  // the message being written
  grpc::ByteBuffer message_bytes_;   // message_, serialized
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_TRIANGULATE_REACTOR_H_

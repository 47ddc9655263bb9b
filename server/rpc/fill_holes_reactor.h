// SPDX-License-Identifier: AGPL-3.0-or-later
// FillHoles, the transport: the mesh streams in (first message: id and
// options; each message accepted by FillUpload), the use case
// (FillHolesCall) runs on the compute pool as one job, and progress per
// hole, the answer and the report stream back (AnswerStream). The reactor
// finishes only after the job's on_done, so the job never outlives it.
//
// Messages travel raw (grpc::ByteBuffer) and are parsed here, so that a
// message that does not parse is an error naming its position, not an end
// of the upload. The upload is bounded by timers (UploadTimers), not by
// the client's next message.
#ifndef DOT_SERVER_RPC_FILL_HOLES_REACTOR_H_
#define DOT_SERVER_RPC_FILL_HOLES_REACTOR_H_

#include <grpcpp/grpcpp.h>

#include "dot/v1/triangulation.pb.h"
#include "rpc/answer_stream.h"
#include "rpc/fill_holes_call.h"
#include "rpc/fill_upload.h"
#include "rpc/job.h"
#include "rpc/upload_timers.h"

namespace dot::server {

class FillHolesReactor final
    : public AnswerStream<
          grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>,
          v1::FillHolesResponse> {
 public:
  FillHolesReactor(JobRunner* runner, grpc::CallbackServerContext* context);

  void OnReadDone(bool ok) override;
  void OnCancel() override;
  void OnDone() override;

 private:
  // One message of the upload; not OK ends the call with that status.
  grpc::Status Accept();
  // The first message: the job admitted, its options checked once.
  grpc::Status Admit(const v1::FillHolesRequest& first);
  // The upload is complete: the fill is queued.
  void StartFill();
  // The mesh did not arrive in time, or the server began to drain.
  void OnUploadTimer();
  grpc::Status NextAnswer(v1::FillHolesResponse* message, bool* last) override;

  FillUpload upload_;
  FillHolesCall call_;  // touched by the compute thread only while it runs
  PolygonSoup soup_;    // moved into the fill
  grpc::ByteBuffer request_;  // the read in flight
  bool uploading_ = true;     // under mu_: reads go on, the timers may end it
  size_t messages_read_ = 0;  // under mu_: for the timers' message
  UploadTimers timers_;
  // What is logged if no first message is accepted: made when the call
  // arrives, so its latency and deadline are the call's own.
  std::shared_ptr<Job> unadmitted_;
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_FILL_HOLES_REACTOR_H_

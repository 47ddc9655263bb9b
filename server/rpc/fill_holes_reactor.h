// SPDX-License-Identifier: AGPL-3.0-or-later
// FillHoles: the mesh streams in (first message: id and options; each
// message accepted by FillUpload), the fill runs on the compute pool as one
// job (dot::FillSoup), and progress per hole, the answer (the filled mesh in
// chunks, or only the patches) and the report stream back. The reactor finishes
// only after the job's on_done, so the job never outlives it.
//
// Messages travel raw (grpc::ByteBuffer) and are parsed here, so that a
// message that does not parse is an error naming its position, not an end
// of the upload. The upload is bounded by timers (the first message within
// the server's limit, the rest within the job's deadline), not by the next
// message, and is charged to the server's FillHoles memory as it arrives.
#ifndef DOT_SERVER_RPC_FILL_HOLES_REACTOR_H_
#define DOT_SERVER_RPC_FILL_HOLES_REACTOR_H_

#include <grpcpp/alarm.h>
#include <grpcpp/grpcpp.h>

#include <memory>
#include <mutex>
#include <optional>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"
#include "rpc/answer_writer.h"
#include "rpc/fill_upload.h"
#include "rpc/job.h"
#include "wire/fill_wire.h"
#include "wire/wire.h"

namespace dot::server {

class FillHolesReactor final
    : public grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer> {
 public:
  FillHolesReactor(JobRunner* runner, grpc::CallbackServerContext* context);

  void OnReadDone(bool ok) override;
  void OnWriteDone(bool ok) override;
  void OnCancel() override;
  void OnDone() override;

 private:
  // One message of the upload; not OK ends the call with that status.
  grpc::Status Accept();
  // The first message: the job admitted, its options checked once, the
  // upload timers set.
  grpc::Status Admit(const v1::FillHolesRequest& first);
  // The upload is complete: the fill is queued.
  void StartFill();
  // The fill itself, on a compute thread.
  Status Fill(Job& job, const Control& control);
  // Called on the computing threads.
  void OnHole(int done, int total);
  void OnJobDone();
  // Writes the next message of the answer, or finishes. Only ever called
  // by whoever holds the (single) right to write.
  void WriteNext();
  void Write(const v1::FillHolesResponse& message, bool last);
  // Finishes the call once; later calls are ignored.
  void FinishWith(const grpc::Status& status);
  // An upload timer fired: the mesh did not arrive in time, or the server
  // began to drain.
  void OnUploadTimer();
  // Sets `timer` to call OnUploadTimer at `when`, if the reactor is alive.
  void SetTimer(grpc::Alarm* timer, std::chrono::system_clock::time_point when);

  JobRunner* const runner_;
  grpc::CallbackServerContext* const context_;
  FillUpload upload_;
  grpc::ByteBuffer request_;  // the read in flight
  std::shared_ptr<Job> job_;
  grpc::Status final_status_;
  size_t messages_read_ = 0;  // under mu_: for the timers' message

  // Input and output of the fill; touched by the compute thread only while
  // the job runs, by the reactor only before and after.
  FillOptions options_;  // from the first message, with the server's limits
  v1::FillAnswer answer_ = v1::FILL_ANSWER_MESH;
  PolygonSoup soup_;  // moved into the fill
  SoupFillResult result_;
  std::vector<SentPatch> patches_;  // FILL_ANSWER_PATCHES

  std::mutex mu_;
  bool uploading_ = true;  // reads go on; the timers may end the call
  bool finished_ = false;  // Finish was called
  AnswerWriter writer_;

  // The answer's writers, made once the job has succeeded.
  std::optional<wire::MeshChunker> chunks_;
  std::optional<wire::PatchWriter> patch_writer_;
  v1::FillHolesResponse message_;   // the message being written
  grpc::ByteBuffer message_bytes_;  // message_, serialized

  // The timers call back on gRPC's threads; the shared guard lets a late
  // callback find the reactor gone instead of touching freed memory.
  struct TimerGuard {
    std::mutex mu;
    FillHolesReactor* reactor;
  };
  std::shared_ptr<TimerGuard> timer_guard_;
  grpc::Alarm first_message_timer_, upload_timer_, drain_timer_;
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_FILL_HOLES_REACTOR_H_

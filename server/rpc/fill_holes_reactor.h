// SPDX-License-Identifier: AGPL-3.0-or-later
// FillHoles: the mesh streams in (first message: id and options), the fill
// runs on the compute pool as one job, and progress per hole, the filled
// mesh in chunks and the report stream back. The reactor finishes only
// after the job's on_done, so the job never outlives it.
#ifndef DOT_SERVER_RPC_FILL_HOLES_REACTOR_H_
#define DOT_SERVER_RPC_FILL_HOLES_REACTOR_H_

#include <grpcpp/grpcpp.h>

#include <memory>
#include <mutex>
#include <optional>

#include "dot/dot.h"
#include "dot/v1/triangulation.pb.h"
#include "rpc/job.h"
#include "wire/fill_wire.h"
#include "wire/wire.h"

namespace dot::server {

class FillHolesReactor final
    : public grpc::ServerBidiReactor<v1::FillHolesRequest,
                                     v1::FillHolesResponse> {
 public:
  FillHolesReactor(JobRunner* runner, grpc::CallbackServerContext* context);

  void OnReadDone(bool ok) override;
  void OnWriteDone(bool ok) override;
  void OnCancel() override;
  void OnDone() override;

 private:
  // The fill itself, on a compute thread.
  Status Fill(Job& job, const Control& control);
  // Called on the computing threads.
  void OnHole(int done, int total);
  void OnJobDone();
  // Writes the next message of the answer, or finishes. Only ever called
  // by whoever holds the (single) right to write.
  void WriteNext();
  void FinishWith(const grpc::Status& status);

  JobRunner* const runner_;
  grpc::CallbackServerContext* const context_;
  wire::FillRequestReader reader_;
  v1::FillHolesRequest request_;  // the message being read
  std::shared_ptr<Job> job_;
  grpc::Status final_status_;

  // Input and output of the fill; touched by the compute thread only while
  // the job runs, by the reactor only before and after.
  PolygonSoup soup_;
  FillResult result_;
  RepairReport repair_;
  size_t input_vertices_ = 0, input_faces_ = 0;

  std::mutex mu_;
  bool writing_ = false;   // a write is in flight
  bool job_done_ = false;  // on_done has run
  bool broken_ = false;    // a write failed: the client is gone
  Clock::time_point last_progress_{};
  v1::FillProgress pending_;

  std::optional<wire::MeshChunker> chunks_;
  bool report_sent_ = false;
  v1::FillHolesResponse message_;  // the message being written
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_FILL_HOLES_REACTOR_H_

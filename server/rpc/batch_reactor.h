// SPDX-License-Identifier: AGPL-3.0-or-later
// TriangulateBatch: many polygons over one bidirectional stream, solved
// concurrently, each answer written as soon as it is ready (tagged with its
// request id); a bad polygon gets an Error message and fails alone.
//
// At most `window` polygons of a stream are admitted and not yet answered;
// the reactor reads the next request only when one is answered, so HTTP/2
// flow control pushes back on a fast sender and memory stays bounded. An
// idle stream costs this object and nothing else: no thread waits on it.
#ifndef DOT_SERVER_RPC_BATCH_REACTOR_H_
#define DOT_SERVER_RPC_BATCH_REACTOR_H_

#include <grpcpp/grpcpp.h>

#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "dot/v1/triangulation.pb.h"
#include "rpc/job.h"
#include "rpc/job_response.h"

namespace dot::server {

// Messages travel raw (grpc::ByteBuffer) and are parsed here, so that one
// that does not parse fails alone (an Error naming its place in the stream)
// instead of looking like the end of the stream.
class BatchReactor final
    : public grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer> {
 public:
  BatchReactor(JobRunner* runner, grpc::CallbackServerContext* context);

  void OnReadDone(bool ok) override;
  void OnWriteDone(bool ok) override;
  void OnCancel() override;
  void OnDone() override;

 private:
  // One admitted request on its way out: a refusal, or a job that runs
  // and then streams its response.
  struct Item {
    std::shared_ptr<Job> job;
    grpc::Status refused;                 // not OK: refused at admission
    std::optional<JobResponse> response;  // set once the job has run
    bool written = false;                 // its last message was written
  };
  using Answer = std::pair<std::shared_ptr<Job>, grpc::Status>;

  // Starts whatever can start now (a read, a write) or finishes the RPC.
  // Every reaction ends by calling it; the decisions are taken under mu_
  // and acted on after it is released. `finished`, a job that has just
  // run, is filed in the same critical section: a compute thread must not
  // touch the reactor after it lets go of mu_, since gRPC may then finish
  // the stream and delete it (only gRPC's own reactions hold OnDone back).
  void Pump(std::shared_ptr<Job> finished = nullptr);
  // Under mu_, when no write is in flight: takes the next item to write
  // into current_ (dropping items once stopped); false when none is ready.
  bool TakeNextItem(std::vector<Answer>* answered);
  // With the write right (writing_): fills message_ from current_ and
  // starts the write. The mesh is serialized outside mu_.
  void WriteCurrent();
  void Stop(StopReason why);  // under mu_: cancel or broken

  JobRunner* const runner_;
  grpc::CallbackServerContext* const context_;
  const size_t window_;

  std::mutex mu_;
  bool reading_ = false, reads_done_ = false;
  bool writing_ = false, finished_ = false;
  bool stopped_ = false;  // cancelled, or a write failed
  grpc::Status final_status_;
  std::set<std::shared_ptr<Job>> running_;
  std::deque<Item> outbox_;      // finished or refused, waiting to be written
  std::optional<Item> current_;  // being written
  grpc::ByteBuffer request_;     // the read in flight
  int64_t requests_read_ = 0;
  v1::TriangulateResponse message_;
  grpc::ByteBuffer message_bytes_;  // message_, serialized, being written
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_BATCH_REACTOR_H_

// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/batch_reactor.h"

#include "rpc/raw_message.h"

namespace dot::server {
namespace {

void SetError(const std::string& id, const grpc::Status& status,
              v1::TriangulateResponse* message) {
  message->Clear();
  message->set_id(id);
  message->mutable_error()->set_code(status.error_code());
  message->mutable_error()->set_message(status.error_message());
}

}  // namespace

BatchReactor::BatchReactor(JobRunner* runner,
                           grpc::CallbackServerContext* context)
    : runner_(runner),
      context_(context),
      window_(2 * static_cast<size_t>(runner->compute_threads()) + 2) {
  Pump();
}

void BatchReactor::OnReadDone(bool ok) {
  if (!ok) {  // the client half-closed, or the stream broke
    std::lock_guard<std::mutex> lock(mu_);
    reading_ = false;
    reads_done_ = true;
  } else {
    // request_ is ours until reading_ is cleared.
    Item item;
    v1::TriangulateRequest request;
    const bool parsed = ParseRaw(&request_, &request);
    ++requests_read_;
    if (parsed) {
      item.job = runner_->Admit(request, context_->deadline(),
                                "TriangulateBatch", &item.refused);
    } else {  // not admitted: only answered (logged and counted)
      item.job = runner_->Unadmitted("TriangulateBatch", context_->deadline());
      item.refused = {grpc::StatusCode::INVALID_ARGUMENT,
                      "message " + std::to_string(requests_read_) +
                          " of this stream is not a TriangulateRequest (it "
                          "does not parse); the stream goes on"};
    }
    std::shared_ptr<Job> job = item.job;
    bool start = false;
    {
      std::lock_guard<std::mutex> lock(mu_);
      reading_ = false;
      if (item.refused.ok() && stopped_) {
        item.refused = {grpc::StatusCode::CANCELLED, "cancelled by the client"};
      }
      if (item.refused.ok()) {
        job->on_done = [this, job] { Pump(job); };
        running_.insert(job);
        start = true;
      } else {
        outbox_.push_back(std::move(item));
      }
    }
    if (start && !runner_->Start(job, false)) {
      job->on_done = nullptr;  // it holds the job
      std::lock_guard<std::mutex> lock(mu_);
      running_.erase(job);
      Item refused;
      refused.job = job;
      refused.refused = runner_->Overloaded();
      outbox_.push_back(std::move(refused));
    }
  }
  Pump();
}

void BatchReactor::OnWriteDone(bool ok) {
  std::vector<Answer> answered;
  {
    std::lock_guard<std::mutex> lock(mu_);
    writing_ = false;
    if (!ok) Stop(StopReason::kClientGone);
    if (current_ && (current_->written || !ok)) {
      const grpc::Status status = !ok ? final_status_
                                  : !current_->refused.ok()
                                      ? current_->refused
                                      : current_->response->status();
      answered.emplace_back(current_->job, status);
      current_.reset();
    }
  }
  for (const Answer& a : answered) runner_->Answered(*a.first, a.second);
  Pump();
}

void BatchReactor::OnCancel() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    Stop(std::chrono::system_clock::now() >= context_->deadline()
             ? StopReason::kClientDeadline
             : StopReason::kClientCancel);
  }
  Pump();
}

void BatchReactor::Stop(StopReason why) {
  if (stopped_) return;
  stopped_ = true;
  final_status_ = StoppedStatus(why);
  for (const auto& job : running_) job->Stop(why);
}

bool BatchReactor::TakeNextItem(std::vector<Answer>* answered) {
  for (;;) {
    if (!current_) {
      if (outbox_.empty()) return false;
      current_ = std::move(outbox_.front());
      outbox_.pop_front();
    }
    if (!stopped_) return true;
    answered->emplace_back(current_->job, final_status_);  // nobody to tell
    current_.reset();
  }
}

void BatchReactor::WriteCurrent() {
  Item& item = *current_;
  if (item.refused.ok() && !item.response) {
    const ServiceOptions& o = runner_->options();
    item.response.emplace(item.job, o.chunk_bytes, o.max_compute_ms);
  }
  const grpc::Status& error =
      !item.refused.ok() ? item.refused : item.response->status();
  if (!error.ok()) {
    SetError(item.job->id, error, &message_);
    item.written = true;
  } else {
    item.response->Next(&message_);
    item.written = item.response->done();
  }
  SerializeRaw(message_, &message_bytes_);
  StartWrite(&message_bytes_);
}

void BatchReactor::Pump(std::shared_ptr<Job> finished) {
  JobRunner* const runner = runner_;  // `this` may be gone after unlocking
  bool start_read = false, start_write = false, finish = false;
  std::vector<Answer> answered;
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (finished) {
      running_.erase(finished);
      Item item;
      item.job = std::move(finished);
      outbox_.push_back(std::move(item));
    }
    if (finished_) return;
    const size_t pending =
        running_.size() + outbox_.size() + (current_ ? 1 : 0);
    if (!reading_ && !reads_done_ && !stopped_ && pending < window_) {
      reading_ = start_read = true;
    }
    if (!writing_ && TakeNextItem(&answered)) writing_ = start_write = true;
    if (!reading_ && !writing_ && running_.empty() && outbox_.empty() &&
        !current_ && (reads_done_ || stopped_)) {
      finished_ = finish = true;
    }
  }
  for (const Answer& a : answered) runner->Answered(*a.first, a.second);
  // A read or write in flight keeps the stream (and this) alive.
  if (start_read) StartRead(&request_);
  if (start_write) WriteCurrent();
  // The last act: OnDone, which deletes this, may follow at once.
  if (finish) Finish(final_status_);
}

void BatchReactor::OnDone() {
  delete this;  // gRPC's callback API: a reactor owns itself until OnDone
}

}  // namespace dot::server

// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/fill_holes_reactor.h"

#include "rpc/job_response.h"

namespace dot::server {
namespace {

constexpr auto kProgressInterval = std::chrono::milliseconds(250);

}  // namespace

FillHolesReactor::FillHolesReactor(JobRunner* runner,
                                   grpc::CallbackServerContext* context)
    : runner_(runner),
      context_(context),
      reader_(static_cast<size_t>(runner->options().fill_max_vertices),
              static_cast<size_t>(runner->options().fill_max_faces)) {
  StartRead(&request_);
}

void FillHolesReactor::OnReadDone(bool ok) {
  if (ok) {
    if (!job_) {
      grpc::Status refused;
      auto job = runner_->AdmitTask("FillHoles", request_.id(),
                                    request_.options().time_budget_ms(),
                                    context_->deadline(), &refused);
      {
        std::lock_guard<std::mutex> lock(mu_);
        job_ = std::move(job);
      }
      if (!refused.ok()) {
        FinishWith(refused);
        return;
      }
      // Options are checked before the mesh is read, not after.
      FillOptions options;
      const Status s = wire::FillOptionsFromWire(request_.options(), &options);
      if (!s.ok()) {
        FinishWith(wire::ToGrpcStatus(s));
        return;
      }
    }
    // A slow upload is bound by the same deadline, drain and cancel as the
    // fill itself.
    if (job_->cancel) {
      FinishWith(job_->drained
                     ? grpc::Status(grpc::StatusCode::UNAVAILABLE,
                                    "server is shutting down; retry on "
                                    "another replica")
                     : grpc::Status(grpc::StatusCode::CANCELLED,
                                    "cancelled by the client"));
      return;
    }
    if (Clock::now() >= job_->deadline) {
      FinishWith({grpc::StatusCode::DEADLINE_EXCEEDED,
                  "the mesh did not arrive within the time limit"});
      return;
    }
    const Status s = reader_.Add(request_);
    if (!s.ok()) {
      FinishWith(wire::ToGrpcStatus(s));
      return;
    }
    StartRead(&request_);
    return;
  }
  // The client half-closed (or went away): the mesh is complete.
  if (context_->IsCancelled()) {
    FinishWith({grpc::StatusCode::CANCELLED, "the client went away"});
    return;
  }
  const Status s = reader_.Finish(&soup_);
  if (!s.ok() || !job_) {
    FinishWith(
        wire::ToGrpcStatus(s.ok() ? InvalidArgument("no mesh was sent") : s));
    return;
  }
  job_->on_done = [this] { OnJobDone(); };
  if (!runner_->StartTask(job_, [this](Job& job, const Control& control) {
        return Fill(job, control);
      })) {
    FinishWith(runner_->Overloaded());
  }
}

Status FillHolesReactor::Fill(Job& job, const Control& control) {
  FillOptions options;
  Status s = wire::FillOptionsFromWire(reader_.options(), &options);
  if (!s.ok()) return s;
  // The server's solve options, a request's memory budget only lowering
  // the server's.
  options.triangulate = job.options;
  options.triangulate.space = SearchSpace::kDelaunay;
  const uint64_t asked = reader_.options().memory_budget_bytes();
  const auto cap = static_cast<uint64_t>(job.options.memory_budget_bytes);
  options.triangulate.memory_budget_bytes =
      static_cast<int64_t>(asked > 0 ? std::min(asked, cap) : cap);
  options.all_space_max_vertices = job.options.all_space_max_vertices;
  options.threads = runner_->compute_threads();
  MeshData mesh;
  s = reader_.options().no_repair()
          ? TriangulateSoup(soup_, control, &mesh)
          : RepairMesh(soup_, control, &mesh, &repair_);
  soup_ = {};
  if (!s.ok()) return s;
  input_vertices_ = mesh.vertices.size();
  input_faces_ = mesh.triangles.size();
  result_ = FillHoles(mesh, options, control,
                      [this](int done, int total) { OnHole(done, total); });
  const FillReport& r = result_.report;
  job.log_detail = "vertices=" + std::to_string(input_vertices_) +
                   " faces=" + std::to_string(input_faces_) +
                   " holes=" + std::to_string(r.loops) +
                   " filled=" + std::to_string(r.filled) +
                   " added_faces=" + std::to_string(r.added_faces);
  return result_.status;
}

void FillHolesReactor::OnHole(int done, int total) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    const auto now = Clock::now();
    if (writing_ || job_done_ || broken_ ||
        (now - last_progress_ < kProgressInterval && done < total)) {
      return;
    }
    last_progress_ = now;
    writing_ = true;
    message_.Clear();
    message_.set_id(job_->id);
    v1::FillProgress* p = message_.mutable_progress();
    p->set_holes_done(done);
    p->set_holes_total(total);
    p->set_elapsed_ms(
        std::chrono::duration<double, std::milli>(now - job_->arrived).count());
  }
  StartWrite(&message_);
}

void FillHolesReactor::OnJobDone() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    job_done_ = true;
    if (writing_) return;  // OnWriteDone carries on
    writing_ = true;
  }
  WriteNext();
}

void FillHolesReactor::OnWriteDone(bool ok) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (!ok) {
      broken_ = true;
      if (job_) job_->cancel = true;
    }
    if (!job_done_) {  // a progress report; the job carries on
      writing_ = false;
      return;
    }
  }
  WriteNext();
}

void FillHolesReactor::WriteNext() {
  bool broken;
  {
    std::lock_guard<std::mutex> lock(mu_);
    broken = broken_;
  }
  if (broken) {
    FinishWith({grpc::StatusCode::CANCELLED, "the client went away"});
    return;
  }
  if (!chunks_) {
    const grpc::Status status =
        JobStatus(*job_, runner_->options().max_compute_ms);
    if (!status.ok()) {
      FinishWith(status);
      return;
    }
    chunks_.emplace(result_.mesh.vertices, result_.mesh.triangles, 0,
                    runner_->options().chunk_bytes);
  }
  message_.Clear();
  message_.set_id(job_->id);
  if (chunks_->Next(message_.mutable_mesh())) {
    StartWrite(&message_);
    return;
  }
  wire::FillReportToWire(result_.report, repair_, input_vertices_, input_faces_,
                         message_.mutable_report());
  final_status_ = grpc::Status::OK;
  StartWriteAndFinish(&message_, grpc::WriteOptions(), final_status_);
}

void FillHolesReactor::FinishWith(const grpc::Status& status) {
  final_status_ = status;
  Finish(status);
}

void FillHolesReactor::OnCancel() {
  std::lock_guard<std::mutex> lock(mu_);
  if (job_) job_->cancel = true;
}

void FillHolesReactor::OnDone() {
  if (final_status_.ok() && context_->IsCancelled()) {
    final_status_ = {grpc::StatusCode::CANCELLED, "the client went away"};
  }
  if (!job_) {
    grpc::Status ignored;
    job_ =
        runner_->AdmitTask("FillHoles", "", 0, context_->deadline(), &ignored);
  }
  runner_->Answered(*job_, final_status_);
  delete this;  // gRPC's callback API: a reactor owns itself until OnDone
}

}  // namespace dot::server

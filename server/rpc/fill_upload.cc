// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/fill_upload.h"

#include <string>

#include "rpc/job_response.h"

namespace dot::server {

FillUpload::FillUpload(JobRunner* runner)
    : runner_(runner),
      reader_(static_cast<size_t>(runner->options().fill_max_vertices),
              static_cast<size_t>(runner->options().fill_max_faces)) {}

FillUpload::~FillUpload() { runner_->ReleaseFillMemory(charged_); }

grpc::Status FillUpload::Add(const v1::FillHolesRequest& m, Job& job) {
  // A slow upload is bound by the same deadline, drain and cancel as the
  // fill itself.
  if (job.cancel) return StoppedStatus(job.stop);
  if (Clock::now() >= job.deadline) {
    job.StopAtDeadline();
    return {grpc::StatusCode::DEADLINE_EXCEEDED,
            "the mesh did not arrive within the time limit"};
  }
  const Status s = reader_.Add(m);
  if (!s.ok()) return wire::ToGrpcStatus(s);
  // Attribute channels are held about three times as sent (upload,
  // trace, answer), and each costs about 40 bytes a triangle corner in the
  // fill's own tables (entries traced through the repair and the merge).
  const int64_t bytes =
      FillMemoryBytes(static_cast<int64_t>(reader_.vertices()),
                      static_cast<int64_t>(reader_.faces())) +
      3 * reader_.attribute_bytes() +
      40 * static_cast<int64_t>(reader_.channels() * reader_.corners());
  const int64_t budget = runner_->options().fill_memory_bytes;
  if (bytes > budget) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "this mesh needs about " + std::to_string(bytes >> 20) +
                " MiB to fill, more than the server's memory for FillHoles "
                "calls (" +
                std::to_string(budget >> 20) +
                " MiB); send it in parts or ask for a larger "
                "--fill-memory-mb"};
  }
  if (bytes > charged_) {
    if (!runner_->ChargeFillMemory(bytes - charged_)) {
      return {grpc::StatusCode::RESOURCE_EXHAUSTED,
              "the server's memory for FillHoles calls (" +
                  std::to_string(budget >> 20) +
                  " MiB) is taken by other calls; this mesh needs about " +
                  std::to_string(bytes >> 20) + " MiB so far; retry later"};
    }
    charged_ = bytes;
  }
  return grpc::Status::OK;
}

}  // namespace dot::server

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

grpc::Status UploadMayGoOn(Job& job, const std::string& input) {
  if (job.cancel) return StoppedStatus(job.stop);
  if (Clock::now() >= job.deadline) {
    job.StopAtDeadline();
    return {grpc::StatusCode::DEADLINE_EXCEEDED,
            "the " + input + " did not arrive within the time limit"};
  }
  return grpc::Status::OK;
}

grpc::Status ChargeUpload(JobRunner* runner, int64_t bytes,
                          const std::string& method, const std::string& input,
                          int64_t* charged) {
  const int64_t budget = runner->options().fill_memory_bytes;
  if (bytes > budget) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "this " + input + " needs about " + std::to_string(bytes >> 20) +
                " MiB, more than the server's memory for " + method +
                " calls (" + std::to_string(budget >> 20) +
                " MiB); send it in parts or ask for a larger "
                "--fill-memory-mb"};
  }
  if (bytes > *charged) {
    if (!runner->ChargeFillMemory(bytes - *charged)) {
      return {grpc::StatusCode::RESOURCE_EXHAUSTED,
              "the server's memory for " + method + " calls (" +
                  std::to_string(budget >> 20) +
                  " MiB) is taken by other calls; this " + input +
                  " needs about " + std::to_string(bytes >> 20) +
                  " MiB so far; retry later"};
    }
    *charged = bytes;
  }
  return grpc::Status::OK;
}

grpc::Status FillUpload::Add(const v1::FillHolesRequest& m, Job& job) {
  // A slow upload is bound by the same deadline, drain and cancel as the
  // fill itself.
  grpc::Status go_on = UploadMayGoOn(job, "mesh");
  if (!go_on.ok()) return go_on;
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
  return ChargeUpload(runner_, bytes, "FillHoles", "mesh", &charged_);
}

}  // namespace dot::server

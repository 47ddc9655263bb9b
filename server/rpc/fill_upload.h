// SPDX-License-Identifier: AGPL-3.0-or-later
// The mesh of one FillHoles call as it arrives: each message checked and
// added under the server's limits (wire::FillRequestReader), a slow upload
// bound by the job's deadline and stops, and the memory the mesh will take
// charged against the server's FillHoles memory before it is held; the
// charge is released with the upload. No stream here: the reactor reads,
// this accepts.
#ifndef DOT_SERVER_RPC_FILL_UPLOAD_H_
#define DOT_SERVER_RPC_FILL_UPLOAD_H_

#include <grpcpp/grpcpp.h>

#include <cstdint>
#include <string>

#include "dot/v1/triangulation.pb.h"
#include "rpc/job.h"
#include "wire/fill_wire.h"

namespace dot::server {

// The checks every message of an upload passes first: the job not stopped
// and its deadline not passed (a slow upload is bound as the work is).
// `input` names what arrives ("mesh").
grpc::Status UploadMayGoOn(Job& job, const std::string& input);

// Charges `bytes` (what the call will hold, by what it has sent so far)
// against the server's memory for uploads (ServiceOptions::
// fill_memory_bytes), on top of `*charged`, which it raises; not OK names
// the need and the limit. `method` and `input` name the call ("FillHoles",
// "mesh") in the message.
grpc::Status ChargeUpload(JobRunner* runner, int64_t bytes,
                          const std::string& method, const std::string& input,
                          int64_t* charged);

class FillUpload {
 public:
  explicit FillUpload(JobRunner* runner);
  ~FillUpload();  // gives the charge back
  FillUpload(const FillUpload&) = delete;
  FillUpload& operator=(const FillUpload&) = delete;

  // One message of `job`'s upload; not OK ends the call with that status.
  grpc::Status Add(const v1::FillHolesRequest& message, Job& job);
  // The whole mesh, once the client has half-closed.
  Status Finish(PolygonSoup* soup) { return reader_.Finish(soup); }
  size_t messages() const { return reader_.messages(); }

 private:
  JobRunner* const runner_;
  wire::FillRequestReader reader_;
  int64_t charged_ = 0;  // FillHoles memory held by this call
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_FILL_UPLOAD_H_

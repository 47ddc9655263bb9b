// SPDX-License-Identifier: AGPL-3.0-or-later
// FillHoles, the transport: the mesh streams in (first message: id and
// options; each message accepted by FillUpload), the use case
// (FillHolesCall) runs on the compute pool as one job, and progress per
// hole, the answer and the report stream back (UploadReactor).
#ifndef DOT_SERVER_RPC_FILL_HOLES_REACTOR_H_
#define DOT_SERVER_RPC_FILL_HOLES_REACTOR_H_

#include "dot/v1/triangulation.pb.h"
#include "rpc/fill_holes_call.h"
#include "rpc/fill_upload.h"
#include "rpc/upload_reactor.h"

namespace dot::server {

struct FillHolesUse {
  using Request = v1::FillHolesRequest;
  using Response = v1::FillHolesResponse;
  using Input = PolygonSoup;
  using Upload = FillUpload;
  using Call = FillHolesCall;
  static constexpr char kMethod[] = "FillHoles";
  static constexpr char kInput[] = "mesh";
  using Progress = std::function<void(
      bool force, const std::function<void(Response*)>& fill)>;
  // The fill, with progress per phase and hole; a stopped fill keeps its
  // holes while its client waits.
  static Status Run(Call& call, Input soup, Job& job, const Control& control,
                    const Progress& progress);
};

using FillHolesReactor = UploadReactor<FillHolesUse>;

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_FILL_HOLES_REACTOR_H_

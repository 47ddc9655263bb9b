// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/fill_holes_reactor.h"

namespace dot::server {

Status FillHolesUse::Run(Call& call, Input soup, Job& job,
                         const Control& job_control, const Progress& progress) {
  wire::FillProgressClock clock(job.arrived);
  Control control = job_control;  // a stopped fill's holes are kept
  control.keep_partial = [&job] { return job.ClientWaits(); };
  return call.Run(
      std::move(soup), control,
      [&](FillPhase phase, int done, int total) {
        // A new phase, and the last hole, are always reported.
        const bool force =
            phase != FillPhase::kHoles || done == total || done == 0;
        progress(force, [&](Response* m) {
          *m->mutable_progress() = clock.Report(phase, done, total);
        });
      },
      &job.log_detail);
}

}  // namespace dot::server

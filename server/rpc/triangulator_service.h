// SPDX-License-Identifier: AGPL-3.0-or-later
// dot.v1.Triangulator on gRPC's callback API: each streaming RPC is a
// reactor of its own (rpc/*_reactor.h) over the shared JobRunner; no thread
// blocks on a call.
#ifndef DOT_SERVER_RPC_TRIANGULATOR_SERVICE_H_
#define DOT_SERVER_RPC_TRIANGULATOR_SERVICE_H_

#include <grpcpp/grpcpp.h>

#include "dot/v1/triangulation.grpc.pb.h"
#include "rpc/job.h"
#include "rpc/service_options.h"

namespace dot::server {

// Every method takes its messages raw and parses them itself
// (rpc/raw_message.h): a message that does not parse is refused by name.
using TriangulatorCallbackBase =
    v1::Triangulator::WithRawCallbackMethod_Triangulate<
        v1::Triangulator::WithRawCallbackMethod_TriangulateBatch<
            v1::Triangulator::WithRawCallbackMethod_GetServerInfo<
                v1::Triangulator::WithRawCallbackMethod_GetSource<
                    v1::Triangulator::WithRawCallbackMethod_FillHoles<
                        v1::Triangulator::WithRawCallbackMethod_SurfaceNetwork<
                            v1::Triangulator::Service>>>>>>;

class TriangulatorService final : public TriangulatorCallbackBase {
 public:
  // `cache` and `helpers` may be null (they only shape GetServerInfo here).
  TriangulatorService(JobRunner* runner, const SpaceCache* cache,
                      const DelaunayHelperPool* helpers);

  grpc::ServerWriteReactor<grpc::ByteBuffer>* Triangulate(
      grpc::CallbackServerContext* context,
      const grpc::ByteBuffer* request) override;
  grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>* TriangulateBatch(
      grpc::CallbackServerContext* context) override;
  grpc::ServerUnaryReactor* GetServerInfo(grpc::CallbackServerContext* context,
                                          const grpc::ByteBuffer* request,
                                          grpc::ByteBuffer* response) override;
  grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>* FillHoles(
      grpc::CallbackServerContext* context) override;
  grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>* SurfaceNetwork(
      grpc::CallbackServerContext* context) override;
  grpc::ServerWriteReactor<grpc::ByteBuffer>* GetSource(
      grpc::CallbackServerContext* context,
      const grpc::ByteBuffer* request) override;

 private:
  void FillServerInfo(v1::ServerInfo* info) const;

 public:
 private:
  JobRunner* const runner_;
  const SpaceCache* const cache_;
  const DelaunayHelperPool* const helpers_;
};

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_TRIANGULATOR_SERVICE_H_

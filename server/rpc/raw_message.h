// SPDX-License-Identifier: AGPL-3.0-or-later
// Every RPC of the service takes and gives raw bytes (gRPC's ByteBuffer) and
// parses them here. With typed methods gRPC's callback API answers a request
// that does not parse with UNIMPLEMENTED and no message, and ends a stream
// at such a message as if the client had half-closed; parsed by us, the bad
// message is refused by name (INVALID_ARGUMENT) and logged.
#ifndef DOT_SERVER_RPC_RAW_MESSAGE_H_
#define DOT_SERVER_RPC_RAW_MESSAGE_H_

#include <grpcpp/grpcpp.h>
#include <grpcpp/impl/codegen/proto_utils.h>

#include <string>

namespace dot::server {

// Whether `bytes` parse as a `Message`. `bytes` is left unusable.
template <typename Message>
bool ParseRaw(grpc::ByteBuffer* bytes, Message* message) {
  return grpc::SerializationTraits<Message>::Deserialize(bytes, message).ok();
}

// `message` serialized into `bytes` (cleared first).
template <typename Message>
void SerializeRaw(const Message& message, grpc::ByteBuffer* bytes) {
  bytes->Clear();  // Serialize wants an empty buffer
  bool own_buffer = false;
  grpc::SerializationTraits<Message>::Serialize(message, bytes, &own_buffer);
}

// INVALID_ARGUMENT for a request of `rpc` that is not a `type`.
inline grpc::Status UnparsableRequest(const std::string& rpc,
                                      const std::string& type) {
  return {grpc::StatusCode::INVALID_ARGUMENT,
          "the " + rpc + " request does not parse as a dot.v1." + type};
}

}  // namespace dot::server

#endif  // DOT_SERVER_RPC_RAW_MESSAGE_H_

// SPDX-License-Identifier: AGPL-3.0-or-later
#include "rpc/source_reactor.h"

#include "rpc/raw_message.h"

namespace dot::server {
namespace {
constexpr size_t kChunkBytes = 256 * 1024;
}  // namespace

SourceReactor::SourceReactor(const ServiceOptions& o) {
  if (!o.source_archive.empty()) {
    in_.open(o.source_archive, std::ios::binary);
  }
  if (o.source_archive.empty() || !in_) {
    Finish({grpc::StatusCode::UNIMPLEMENTED,
            "this server has no source archive (--source-archive '" +
                o.source_archive + "'); " +
                (o.source_url.empty() ? "ask its operator for the source"
                                      : "the source is at " + o.source_url)});
    return;
  }
  WriteNext();
}

SourceReactor::SourceReactor(const grpc::Status& refused) { Finish(refused); }

void SourceReactor::WriteNext() {
  std::string* data = chunk_.mutable_data();
  data->resize(kChunkBytes);
  in_.read(data->data(), static_cast<std::streamsize>(kChunkBytes));
  const std::streamsize got = in_.gcount();
  if (got <= 0) {
    Finish(in_.eof() ? grpc::Status::OK
                     : grpc::Status(grpc::StatusCode::INTERNAL,
                                    "reading the source archive failed"));
    return;
  }
  data->resize(static_cast<size_t>(got));
  SerializeRaw(chunk_, &chunk_bytes_);
  StartWrite(&chunk_bytes_);
}

void SourceReactor::OnWriteDone(bool ok) {
  if (!ok) {
    Finish({grpc::StatusCode::CANCELLED, "cancelled by the client"});
    return;
  }
  WriteNext();
}

void SourceReactor::OnDone() {
  delete this;  // gRPC's callback API: a reactor owns itself until OnDone
}

}  // namespace dot::server

// SPDX-License-Identifier: AGPL-3.0-or-later
#include "cli/json_envelope.h"

#include <google/protobuf/util/json_util.h>

#include <sstream>

#include "wire/json_text.h"
#include "wire/wire.h"

namespace dot::client {

std::string JsonQuote(const std::string& in) {
  return "\"" + wire::JsonEscape(in) + "\"";
}

std::string ProtoJson(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.always_print_primitive_fields = true;
  options.preserve_proto_field_names = true;
  std::string json;
  return google::protobuf::util::MessageToJsonString(message, &json, options)
                 .ok()
             ? json
             : "null";
}

std::string JsonEnvelope::ToJson() const {
  std::ostringstream s;
  s << "{\"version\":1,\"input\":" << JsonQuote(input)
    << ",\"outcome\":" << JsonQuote(outcome) << ",\"exit_code\":" << exit_code
    << ",\"rpc_status\":"
    << (rpc_status ? JsonQuote(std::string(wire::GrpcCodeName(*rpc_status)))
                   : std::string("null"))
    << ",\"error\":" << JsonQuote(error) << ",\"output\":" << JsonQuote(output)
    << ",\"latency_ms\":" << latency_ms << ",\"notes\":[";
  for (size_t i = 0; i < notes.size(); ++i) {
    s << (i ? "," : "") << JsonQuote(notes[i]);
  }
  s << "]";
  for (const auto& [name, json] : fields) {
    s << "," << JsonQuote(name) << ":" << json;
  }
  s << "}";
  return s.str();
}

}  // namespace dot::client

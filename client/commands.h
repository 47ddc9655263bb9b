// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl's subcommands. Each Add*Command registers itself on the app; its
// callback stores the process exit code in *exit_code.
#ifndef DOT_CLIENT_COMMANDS_H_
#define DOT_CLIENT_COMMANDS_H_

#include <string>
#include <vector>

#include "request_flags.h"

namespace CLI {
class App;
}

namespace dot::client {

struct Context {
  ConnectionFlags connection;
  int exit_code = 0;
};

void AddTriangulateCommand(CLI::App& app, Context* ctx);
void AddBatchCommand(CLI::App& app, Context* ctx);
void AddHealthCommand(CLI::App& app, Context* ctx);
void AddInfoCommands(CLI::App& app, Context* ctx);  // info, source
void AddLoadCommand(CLI::App& app, Context* ctx);
void AddGenerateCommand(CLI::App& app, Context* ctx);
void AddFillHolesCommand(CLI::App& app, Context* ctx);

// Shared helpers.
// Polygon files named, or found (*.xyz, *.txt, *.obj) in a directory.
std::vector<std::string> ExpandInputs(const std::vector<std::string>& args,
                                      std::string* error);
// Where the mesh for `input` goes: `output` itself for one input, or
// `output`/<stem>.<format> for many; <stem>.tri.<format> beside the input
// when no -o was given.
std::string OutputPathFor(const std::string& input, const std::string& output,
                          const std::string& format, bool many);
int ExitCodeFor(const grpc::Status& status);
// The channel to ctx->connection, or null after reporting a usage error.
std::shared_ptr<grpc::Channel> ChannelOrReport(Context* ctx);

}  // namespace dot::client

#endif  // DOT_CLIENT_COMMANDS_H_

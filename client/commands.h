// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl's subcommands. Each Add*Command registers itself on the app; its
// callback stores the process exit code in ctx->exit_code.
#ifndef DOT_CLIENT_COMMANDS_H_
#define DOT_CLIENT_COMMANDS_H_

#include "cli/context.h"
#include "cli/inputs.h"
#include "cli/output.h"

namespace CLI {
class App;
}

namespace dot::client {

void AddTriangulateCommand(CLI::App& app, Context* ctx);
void AddBatchCommand(CLI::App& app, Context* ctx);
void AddHealthCommand(CLI::App& app, Context* ctx);
void AddInfoCommands(CLI::App& app, Context* ctx);  // info, source
void AddLoadCommand(CLI::App& app, Context* ctx);
void AddGenerateCommand(CLI::App& app, Context* ctx);
void AddFillHolesCommand(CLI::App& app, Context* ctx);
void AddSurfaceCommand(CLI::App& app, Context* ctx);
void AddViewCommand(CLI::App& app, Context* ctx);
// bash or zsh completion, from the definition of `app` (call it last).
void AddCompletionCommand(CLI::App& app, Context* ctx);

}  // namespace dot::client

#endif  // DOT_CLIENT_COMMANDS_H_

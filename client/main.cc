// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl: command-line client of dot-server (and of the core, with --local).
#include <CLI/CLI.hpp>

#include "commands.h"
#include "exit_codes.h"

int main(int argc, char** argv) {
  CLI::App app{
      "dotctl: optimal, intersection-free triangulation of 3D polygons.\n"
      "Talks to a dot-server (--server, or DOT_SERVER), or runs the core "
      "in-process with 'triangulate --local'.\n"
      "Exit codes: 0 ok, 1 a request failed, 2 usage, 3 server unreachable, "
      "4 some polygon has no triangulation."};
  app.set_version_flag("--version", "dotctl " DOT_VERSION);
  app.require_subcommand(1);
  // Global options (--server, TLS, --timeout) are accepted after the
  // subcommand too, as in most CLIs: subcommands pass what they do not know
  // up to here.
  app.fallthrough();
  dot::client::Context ctx;
  dot::client::AddConnectionFlags(&app, &ctx.connection);
  dot::client::AddTriangulateCommand(app, &ctx);
  dot::client::AddBatchCommand(app, &ctx);
  dot::client::AddHealthCommand(app, &ctx);
  dot::client::AddInfoCommands(app, &ctx);
  dot::client::AddLoadCommand(app, &ctx);
  dot::client::AddGenerateCommand(app, &ctx);
  dot::client::AddFillHolesCommand(app, &ctx);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : dot::client::kExitUsage;
  }
  return ctx.exit_code;
}

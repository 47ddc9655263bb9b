// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl: command-line client of dot-server (and of the core, with --local).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstring>
#include <iostream>

#include "commands.h"
#include "dot/table_memory.h"
#include "exit_codes.h"
#include "remote_call.h"

namespace {

size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1,
                         diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// After a parse error: when the innermost command given expects a
// subcommand and got a word that names none, says so with the nearest
// name. Returns false when the error was something else.
bool ReportUnknownCommand(CLI::App& app) {
  CLI::App* at = &app;
  std::string path = "dotctl";
  for (;;) {
    const auto chosen = at->get_subcommands();
    if (chosen.empty()) break;
    at = chosen.front();
    path += " " + at->get_name();
  }
  const auto all = at->get_subcommands([](CLI::App*) { return true; });
  if (all.empty()) return false;
  std::string word;
  for (const std::string& arg : app.remaining()) {
    if (!arg.empty() && arg[0] != '-') {
      word = arg;
      break;
    }
  }
  if (word.empty()) return false;
  std::string best;
  size_t best_distance = std::string::npos;
  for (const CLI::App* sub : all) {
    const std::string& name = sub->get_name();
    const size_t d = name.rfind(word, 0) == 0 ? 0 : EditDistance(word, name);
    if (d < best_distance) {
      best_distance = d;
      best = name;
    }
  }
  std::cerr << path << ": unknown command '" << word << "'";
  if (best_distance <= std::max<size_t>(2, word.size() / 3)) {
    std::cerr << "; did you mean '" << best << "'?\n";
  } else {
    std::cerr << "; see " << path << " --help\n";
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  // Started by dotctl itself (--local with TetGen): a Delaunay helper.
  if (argc >= 2 &&
      std::strcmp(argv[1], dot::client::kDelaunayHelperArgument) == 0) {
    return dot::DelaunayHelperMain("dotctl --delaunay-helper", argc - 1,
                                   argv + 1);
  }
  // --local and batch runs solve one input after another: each reuses the
  // pages of the last one's tables.
  dot::SetTableCacheBytes(size_t{256} << 20);
  CLI::App app{
      "dotctl: optimal, intersection-free triangulation of 3D polygons.\n"
      "Talks to a dot-server (--server, or DOT_SERVER), or runs the core "
      "in-process with 'triangulate --local'.\n"
      "Exit codes: 0 ok, 1 a request failed, 2 usage or unreadable input, "
      "3 server unreachable, 4 some polygon has no triangulation, 5 a fill "
      "stopped early (what it filled is written)."};
  app.set_version_flag("--version", "dotctl " DOT_VERSION);
  app.require_subcommand(1);
  // Global options (--server, TLS, --timeout, -q, -v) are accepted after the
  // subcommand too, as in most CLIs: subcommands pass what they do not know
  // up to here.
  app.fallthrough();
  dot::client::Context ctx;
  dot::client::AddConnectionFlags(&app, &ctx.connection);
  auto* quiet = app.add_flag("-q,--quiet", ctx.quiet,
                             "print errors only (and what --json asks for)")
                    ->group("Output");
  app.add_flag("-v,--verbose", ctx.verbose,
               "also print timing lines (per request) on stderr")
      ->group("Output")
      ->excludes(quiet);
  dot::client::AddTriangulateCommand(app, &ctx);
  dot::client::AddBatchCommand(app, &ctx);
  dot::client::AddHealthCommand(app, &ctx);
  dot::client::AddInfoCommands(app, &ctx);
  dot::client::AddLoadCommand(app, &ctx);
  dot::client::AddGenerateCommand(app, &ctx);
  dot::client::AddFillHolesCommand(app, &ctx);
  dot::client::AddSurfaceCommand(app, &ctx);
  dot::client::AddViewCommand(app, &ctx);
  dot::client::AddCompletionCommand(app, &ctx);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (dynamic_cast<const CLI::Success*>(&e) ||
        dynamic_cast<const CLI::CallForHelp*>(&e) ||
        dynamic_cast<const CLI::CallForAllHelp*>(&e) ||
        dynamic_cast<const CLI::CallForVersion*>(&e) ||
        !ReportUnknownCommand(app)) {
      const int rc = app.exit(e);
      return rc == 0 ? 0 : dot::client::kExitUsage;
    }
    return dot::client::kExitUsage;
  }
  return ctx.exit_code;
}

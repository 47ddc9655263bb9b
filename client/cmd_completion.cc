// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl completion bash|zsh: a completion script made from the CLI's own
// definition (every subcommand and option CLI11 knows), so it cannot drift
// from the flags. zsh runs the bash function through bashcompinit.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"

namespace dot::client {
namespace {

// Words a level offers: its subcommands' names and its options' names.
std::string Words(const CLI::App* app) {
  std::string out;
  for (const CLI::App* sub : app->get_subcommands({})) {
    if (sub->get_name().empty()) continue;
    out += sub->get_name() + " ";
  }
  for (const CLI::Option* o : app->get_options()) {
    for (const std::string& n : o->get_lnames()) out += "--" + n + " ";
    for (const std::string& n : o->get_snames()) out += "-" + n + " ";
  }
  return out;
}

// One case per subcommand path ("generate network"), in the function.
void Cases(const CLI::App* app, const std::string& path, std::string* out) {
  for (const CLI::App* sub : app->get_subcommands({})) {
    if (sub->get_name().empty()) continue;
    const std::string p =
        path.empty() ? sub->get_name() : path + " " + sub->get_name();
    *out += "    \"" + p + "\") words=\"" + Words(sub) + "\" ;;\n";
    Cases(sub, p, out);
  }
}

// Subcommand names per level, for walking the words typed so far.
void Levels(const CLI::App* app, const std::string& path, std::string* out) {
  std::string names;
  for (const CLI::App* sub : app->get_subcommands({})) {
    if (sub->get_name().empty()) continue;
    names += sub->get_name() + " ";
    Levels(sub, path.empty() ? sub->get_name() : path + " " + sub->get_name(),
           out);
  }
  if (!names.empty())
    *out += "    \"" + path + "\") subs=\"" + names + "\" ;;\n";
}

std::string BashScript(const CLI::App& app) {
  std::string cases, levels;
  Cases(&app, "", &cases);
  Levels(&app, "", &levels);
  return "# dotctl completion (bash): source <(dotctl completion bash)\n"
         "_dotctl() {\n"
         "  local cur=${COMP_WORDS[COMP_CWORD]} path=\"\" w subs words\n"
         "  # The subcommand path typed so far: words naming a subcommand of\n"
         "  # the level reached.\n"
         "  for w in \"${COMP_WORDS[@]:1:COMP_CWORD-1}\"; do\n"
         "    subs=\"\"\n"
         "    case \"$path\" in\n" +
         levels +
         "    esac\n"
         "    if [[ \" $subs \" == *\" $w \"* ]]; then\n"
         "      path=${path:+$path }$w\n"
         "    fi\n"
         "  done\n"
         "  words=\"" +
         Words(&app) +
         "\"\n"
         "  case \"$path\" in\n" +
         cases +
         "  esac\n"
         "  # Global options are accepted after the subcommand too.\n"
         "  [[ -n $path ]] && words+=\" " +
         [&] {
           std::string globals;
           for (const CLI::Option* o : app.get_options()) {
             for (const std::string& n : o->get_lnames()) {
               globals += "--" + n + " ";
             }
           }
           return globals;
         }() +
         "\"\n"
         "  # One candidate a line: file names may hold spaces.\n"
         "  if [[ $cur == -* ]]; then\n"
         "    mapfile -t COMPREPLY < <(compgen -W \"$words\" -- \"$cur\")\n"
         "  else\n"
         "    mapfile -t COMPREPLY < <(compgen -W \"$words\" -- \"$cur\"; "
         "compgen -f -- \"$cur\")\n"
         "  fi\n"
         "}\n"
         "complete -o filenames -F _dotctl dotctl\n";
}

}  // namespace

void AddCompletionCommand(CLI::App& app, Context* ctx) {
  auto shell = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "completion",
      "Print a completion script for bash or zsh, made from dotctl's own "
      "options: source <(dotctl completion bash), or in ~/.zshrc: source "
      "<(dotctl completion zsh)");
  cmd->add_option("shell", *shell, "bash or zsh")
      ->required()
      ->check(CLI::IsMember({"bash", "zsh"}));
  CLI::App* root = &app;
  cmd->callback([root, shell] {
    if (*shell == "zsh") {
      std::cout << "# dotctl completion (zsh, through bashcompinit)\n"
                   "autoload -U +X compinit && compinit\n"
                   "autoload -U +X bashcompinit && bashcompinit\n";
    }
    std::cout << BashScript(*root);
  });
  (void)ctx;
}

}  // namespace dot::client

// The program's options as rows of text, from their CLI11 declarations: what the docs' generated
// tables (cli/docs.h) and the man page (cli/man_page.h) are made of. Option names and defaults
// are markdown inline code ("`--size`", "`512x512`").
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace sylva::cli {

using Command = std::pair<std::string, const CLI::App*>;  // "farm slurm", its app

struct OptionRow {
  std::string option;   // "`-o`, `--output`", or "`SCENE`" for a positional
  std::string meaning;  // the description
  std::string def;      // "`512x512`", "required", "off" (a flag) or "—"
};

// Every command that takes options, depth first in registration order: "render", "farm slurm".
std::vector<Command> commands_with_options(const CLI::App& app);

// The groups of options several commands share, by the slug the docs' blocks use ("view") and
// their --help heading ("View options"; cli/common_options.h).
const std::map<std::string, std::string>& shared_groups();
bool is_shared_group(const std::string& heading);

// The options of `cmd` outside the shared groups; --help only for the program itself.
std::vector<OptionRow> own_option_rows(const CLI::App& cmd);

// The options of the shared group `heading` across `commands`: each row has the first command's
// description and default, then the commands that lack the option and those whose default
// differs. `on` receives the commands that have the group.
std::vector<OptionRow> group_option_rows(const std::vector<Command>& commands,
                                         const std::string& heading, std::vector<std::string>* on);

// The block an option belongs to in the docs: "options COMMAND" or "group SLUG".
std::string option_block(const std::string& command, const CLI::Option* o);

// "`--size`" as option_rows name it.
std::string option_name(const CLI::Option* o);
bool is_help(const CLI::Option* o);

}  // namespace sylva::cli

// The sylva program's commands on one CLI11 app: what main runs, and what the README's
// generated tables are made from (cli/docs.h), so both see the same declarations.
#pragma once

#include <CLI/CLI.hpp>
#include <map>

#include "cli/commands.h"

namespace sylva::cli {

// Sets up `app` as the sylva program (description, --version) with every command registered;
// returns each command's action.
std::map<CLI::App*, Action> add_commands(CLI::App& app);

}  // namespace sylva::cli

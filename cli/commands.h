// The sylva subcommands. Each add_* registers its options on the app and returns the
// action to run once parsing succeeded (main runs it and turns InputError into exit 2).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace sylva::cli {

using Action = std::function<void()>;

Action add_sample_command(CLI::App& app);
Action add_info_command(CLI::App& app);
Action add_render_command(CLI::App& app);
Action add_buffers_command(CLI::App& app);
Action add_styles_command(CLI::App& app);
Action add_bake_command(CLI::App& app);
Action add_tradeoff_command(CLI::App& app);
Action add_compare_command(CLI::App& app);
Action add_turntable_command(CLI::App& app);
Action add_encode_command(CLI::App& app);
Action add_farm_command(CLI::App& app);

// Checks an output path before any work: the folder exists and the extension is allowed.
void check_output_path(const std::string& option, const std::string& path,
                       const std::vector<std::string>& extensions);

}  // namespace sylva::cli

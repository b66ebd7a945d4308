#include "cli/app.h"

#include <memory>

#include "cli/version.h"

namespace sylva::cli {

std::map<CLI::App*, Action> add_commands(CLI::App& app) {
  app.description(
      "sylva: non-photorealistic illustrations of 3D plants and trees.\n"
      "Run 'sylva <command> --help' for a command's options.");
  // --verbose is declared first: option callbacks run in declaration order once all arguments
  // are read, so it is set when --version's callback prints (in any order on the line).
  auto verbose = std::make_shared<bool>(false);  // owned by --version's callback, as long as app
  CLI::Option* more =
      app.add_flag("--verbose", *verbose,
                   "With --version: also the compiler and the libraries' versions (OpenCV, "
                   "the GL renderer, OpenEXR, Embree, ...)");
  CLI::Option* version = app.set_version_flag(
      "--version", [verbose] { return *verbose ? version_report() : version_line(); },
      "Print the version and git commit and exit");
  more->needs(version);
  app.require_subcommand(1);
  std::map<CLI::App*, Action> actions;
  for (Action (*add)(CLI::App&) :
       {&add_sample_command, &add_info_command, &add_render_command, &add_buffers_command,
        &add_styles_command, &add_compare_command, &add_turntable_command, &add_encode_command,
        &add_farm_command, &add_bake_command, &add_tradeoff_command}) {
    const size_t before = app.get_subcommands({}).size();
    Action a = add(app);
    actions[app.get_subcommands({})[before]] = a;
  }
  return actions;
}

}  // namespace sylva::cli

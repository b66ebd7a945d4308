#include "cli/app.h"

namespace sylva::cli {

std::map<CLI::App*, Action> add_commands(CLI::App& app) {
  app.description(
      "sylva: non-photorealistic illustrations of 3D plants and trees.\n"
      "Run 'sylva <command> --help' for a command's options.");
  app.set_version_flag("--version", "sylva 0.1.0");
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

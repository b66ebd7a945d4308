// sylva styles [NAME|FILE.toml]: the built-in style presets with one-line descriptions, or one
// preset's inheritance chain and every parameter with its value, default, range and meaning.
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "styles/style.h"

namespace sylva::cli {

Action add_styles_command(CLI::App& app) {
  auto name = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "styles", "List the style presets, or one preset's parameters (sylva styles ink)");
  cmd->add_option("preset", *name, "A built-in preset or a .toml file");
  return [name] {
    if (name->empty()) {
      std::printf("%-13s %-15s %s\n", "style", "builder", "description");
      for (const std::string& n : builtin_preset_names()) {
        const Style s(n);
        std::printf("%-13s %-15s %s\n", n.c_str(), s.builder_text().c_str(),
                    s.info().description.c_str());
      }
      std::printf(
          "\n'sylva styles NAME' lists a style's parameters; change them with\n"
          "--set section.key=value or in a preset file (see the README).\n");
      return;
    }
    Style s(*name);
    std::string chain;
    for (const std::string& c : s.info().chain)
      chain += (chain.empty() ? "" : " -> ") + c;
    std::printf("%s (%s): %s\n%s %s; presets applied: %s\n\n", s.info().name.c_str(),
                s.info().source.c_str(), s.info().description.c_str(),
                s.layers().empty() ? "builder" : "layers", s.builder_text().c_str(), chain.c_str());
    std::printf("%-24s %-12s %-12s %-40s %s\n", "key", "value", "default", "allowed", "meaning");
    for (const ParamSpec& p : s.set().specs())
      std::printf("%-24s %-12s %-12s %-40s %s\n", p.key.c_str(), s.set().value_text(p.key).c_str(),
                  p.default_text.c_str(), allowed_text(p).c_str(), p.doc.c_str());
  };
}

}  // namespace sylva::cli

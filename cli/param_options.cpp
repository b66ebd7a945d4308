#include "cli/param_options.h"

#include <algorithm>
#include <cctype>

namespace sylva::cli {

namespace {

std::string type_name(const ParamSpec& spec) {
  switch (spec.type) {
    case ParamType::Float:
      return "FLOAT";
    case ParamType::Int:
      return "INT";
    default:
      return "TEXT";
  }
}

// "radius of influence ..." -> "Radius of influence ...; auto, ... (foliage.rho)".
std::string help_of(const ParamSpec& spec) {
  std::string help = spec.doc;
  if (!help.empty()) help[0] = char(std::toupper(static_cast<unsigned char>(help[0])));
  if (spec.type != ParamType::Bool) help += "; " + allowed_text(spec);
  return help + " (" + spec.key + ")";
}

}  // namespace

std::string option_of_key(const std::string& key) {
  std::string name = "--" + key.substr(key.find('.') + 1);
  std::replace(name.begin(), name.end(), '_', '-');
  return name;
}

void add_param_options(CLI::App& cmd, const std::vector<ParamSpec>& specs, const std::string& group,
                       const std::vector<std::string>& skip) {
  for (const ParamSpec& spec : specs) {
    if (std::find(skip.begin(), skip.end(), spec.key) != skip.end()) continue;
    const std::string name = option_of_key(spec.key);
    const std::string help = help_of(spec);
    if (spec.type == ParamType::Bool) {
      cmd.add_flag(name, help)->group(group);
      continue;
    }
    cmd.add_option(name, help)
        ->type_name(type_name(spec))
        ->default_str(spec.default_text)
        ->group(group);
  }
}

std::vector<ParamAssignment> given_param_options(const CLI::App& cmd,
                                                 const std::vector<ParamSpec>& specs) {
  std::vector<ParamAssignment> given;
  for (const ParamSpec& spec : specs) {
    const std::string name = option_of_key(spec.key);
    const CLI::Option* opt = cmd.get_option_no_throw(name);
    if (opt == nullptr || opt->count() == 0) continue;
    const std::string value = spec.type == ParamType::Bool ? "true" : opt->as<std::string>();
    given.push_back({spec.key, value, name});
  }
  return given;
}

}  // namespace sylva::cli

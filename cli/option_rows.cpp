#include "cli/option_rows.h"

#include <algorithm>

#include "cli/common_options.h"

namespace sylva::cli {

namespace {

void collect_commands(const CLI::App& app, const std::string& prefix, std::vector<Command>& out) {
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    const std::string name = prefix.empty() ? sub->get_name() : prefix + " " + sub->get_name();
    const bool options =
        !sub->get_options([](const CLI::Option* o) { return !is_help(o); }).empty();
    if (options) out.emplace_back(name, sub);
    collect_commands(*sub, name, out);
  }
}

std::string default_of(const CLI::Option* o) {
  if (o->get_required()) return "required";
  if (o->get_expected_min() == 0) return "off";
  if (!o->get_default_str().empty()) return "`" + o->get_default_str() + "`";
  return "—";
}

std::vector<const CLI::Option*> options_in(const CLI::App& cmd, const std::string& group) {
  return cmd.get_options(
      [&](const CLI::Option* o) { return !is_help(o) && o->get_group() == group; });
}

std::string joined(const std::vector<std::string>& items) {
  std::string list;
  for (const std::string& c : items)
    list += (list.empty() ? "" : ", ") + c;
  return list;
}

OptionRow group_row(const std::string& name, const std::vector<Command>& with,
                    const std::string& group) {
  OptionRow row{name, "", ""};
  std::vector<std::string> lacking;
  std::map<std::string, std::vector<std::string>> other_defaults;
  for (const auto& [command, app] : with) {
    const CLI::Option* found = nullptr;
    for (const CLI::Option* o : options_in(*app, group))
      if (option_name(o) == name) found = o;
    if (found == nullptr) {
      lacking.push_back(command);
      continue;
    }
    if (row.meaning.empty()) {
      row.meaning = found->get_description();
      row.def = default_of(found);
    } else if (default_of(found) != row.def) {
      other_defaults[default_of(found)].push_back(command);
    }
  }
  for (const auto& [d, commands] : other_defaults)
    row.def += "; " + joined(commands) + ": " + d;
  if (!lacking.empty()) row.meaning += " (not on " + joined(lacking) + ")";
  return row;
}

}  // namespace

bool is_help(const CLI::Option* o) {
  const auto& l = o->get_lnames();
  return std::find(l.begin(), l.end(), "help") != l.end();
}

std::vector<Command> commands_with_options(const CLI::App& app) {
  std::vector<Command> out;
  collect_commands(app, "", out);
  return out;
}

const std::map<std::string, std::string>& shared_groups() {
  static const std::map<std::string, std::string> g = {
      {"scene", kSceneGroup}, {"view", kViewGroup},           {"foliage", kFoliageGroup},
      {"style", kStyleGroup}, {"turntable", kTurntableGroup}, {"gl", kGlGroup}};
  return g;
}

bool is_shared_group(const std::string& heading) {
  for (const auto& [slug, name] : shared_groups())
    if (name == heading) return true;
  return false;
}

std::string option_name(const CLI::Option* o) {
  if (!o->nonpositional()) {
    std::string n = o->get_name(true, false);
    std::transform(n.begin(), n.end(), n.begin(),
                   [](unsigned char c) { return char(std::toupper(c)); });
    return "`" + n + "`";
  }
  std::string n;
  for (const std::string& s : o->get_snames())
    n += (n.empty() ? "`-" : ", `-") + s + "`";
  for (const std::string& l : o->get_lnames())
    n += (n.empty() ? "`--" : ", `--") + l + "`";
  return n;
}

std::vector<OptionRow> own_option_rows(const CLI::App& cmd) {
  const bool help = cmd.get_parent() == nullptr;
  std::vector<OptionRow> rows;
  for (const CLI::Option* o : cmd.get_options([help](const CLI::Option* o) {
         return (help || !is_help(o)) && !is_shared_group(o->get_group());
       }))
    rows.push_back({option_name(o), o->get_description(), default_of(o)});
  return rows;
}

std::vector<OptionRow> group_option_rows(const std::vector<Command>& commands,
                                         const std::string& heading, std::vector<std::string>* on) {
  std::vector<Command> with;
  std::vector<std::string> names;
  for (const Command& c : commands) {
    const auto options = options_in(*c.second, heading);
    if (options.empty()) continue;
    with.push_back(c);
    if (on) on->push_back(c.first);
    for (const CLI::Option* o : options)
      if (std::find(names.begin(), names.end(), option_name(o)) == names.end())
        names.push_back(option_name(o));
  }
  std::vector<OptionRow> rows;
  for (const std::string& n : names)
    rows.push_back(group_row(n, with, heading));
  return rows;
}

std::string option_block(const std::string& command, const CLI::Option* o) {
  for (const auto& [slug, group] : shared_groups())
    if (o->get_group() == group) return "group " + slug;
  return "options " + command;
}

}  // namespace sylva::cli

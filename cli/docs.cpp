#include "cli/docs.h"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "cli/common_options.h"
#include "core/error.h"
#include "styles/presets.h"
#include "styles/style.h"

namespace sylva::cli {

namespace {

constexpr const char* kBegin = "<!-- generated: ";
constexpr const char* kBeginEnd = " -->";
constexpr const char* kEnd = "<!-- end generated -->";

using Command = std::pair<std::string, const CLI::App*>;  // "farm slurm", its app

// The shared groups' names in the README's blocks.
const std::map<std::string, std::string>& groups() {
  static const std::map<std::string, std::string> g = {{"scene", kSceneGroup},
                                                       {"view", kViewGroup},
                                                       {"foliage", kFoliageGroup},
                                                       {"style", kStyleGroup},
                                                       {"turntable", kTurntableGroup}};
  return g;
}

bool shared_group(const std::string& group) {
  for (const auto& [slug, name] : groups())
    if (name == group) return true;
  return false;
}

// A markdown table cell: no line breaks, '|' escaped.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c == '\n' ? ' ' : c;
  }
  return out;
}

std::string table(const std::vector<std::string>& header,
                  const std::vector<std::vector<std::string>>& rows) {
  std::ostringstream t;
  for (const std::string& h : header)
    t << "| " << h << ' ';
  t << "|\n";
  for (size_t i = 0; i < header.size(); ++i)
    t << "|---";
  t << "|\n";
  for (const auto& row : rows) {
    for (const std::string& c : row)
      t << "| " << cell(c) << ' ';
    t << "|\n";
  }
  return t.str();
}

bool is_help(const CLI::Option* o) {
  const auto& l = o->get_lnames();
  return std::find(l.begin(), l.end(), "help") != l.end();
}

// Every command that takes options, depth first in registration order: "render", "farm slurm".
void collect_commands(const CLI::App& app, const std::string& prefix, std::vector<Command>& out) {
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    const std::string name = prefix.empty() ? sub->get_name() : prefix + " " + sub->get_name();
    const bool options =
        !sub->get_options([](const CLI::Option* o) { return !is_help(o); }).empty();
    if (options) out.emplace_back(name, sub);
    collect_commands(*sub, name, out);
  }
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

// The options of `cmd` outside the shared groups; --help only for the program itself (every
// command has it).
std::string own_options(const CLI::App& cmd) {
  const bool help = cmd.get_parent() == nullptr;
  std::vector<std::vector<std::string>> rows;
  for (const CLI::Option* o : cmd.get_options([help](const CLI::Option* o) {
         return (help || !is_help(o)) && !shared_group(o->get_group());
       }))
    rows.push_back({option_name(o), o->get_description(), default_of(o)});
  return table({"option", "meaning", "default"}, rows);
}

// A row of a shared group: the first command's description and default, then the commands
// that lack the option and those whose default differs.
std::vector<std::string> group_row(const std::string& name, const std::vector<Command>& with,
                                   const std::string& group) {
  std::string meaning, def;
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
    if (meaning.empty()) {
      meaning = found->get_description();
      def = default_of(found);
    } else if (default_of(found) != def) {
      other_defaults[default_of(found)].push_back(command);
    }
  }
  for (const auto& [d, commands] : other_defaults) {
    std::string list;
    for (const std::string& c : commands)
      list += (list.empty() ? "" : ", ") + c;
    def += "; " + list + ": " + d;
  }
  if (!lacking.empty()) {
    std::string list;
    for (const std::string& c : lacking)
      list += (list.empty() ? "" : ", ") + c;
    meaning += " (not on " + list + ")";
  }
  return {name, meaning, def};
}

std::string group_options(const std::vector<Command>& commands, const std::string& group) {
  std::vector<Command> with;
  std::vector<std::string> names;
  for (const Command& c : commands) {
    const auto options = options_in(*c.second, group);
    if (options.empty()) continue;
    with.push_back(c);
    for (const CLI::Option* o : options)
      if (std::find(names.begin(), names.end(), option_name(o)) == names.end())
        names.push_back(option_name(o));
  }
  std::string list;
  for (const Command& c : with)
    list += (list.empty() ? "`" : ", `") + c.first + "`";
  std::vector<std::vector<std::string>> rows;
  for (const std::string& n : names)
    rows.push_back(group_row(n, with, group));
  return "On " + list + ".\n\n" + table({"option", "meaning", "default"}, rows);
}

// The built-in styles that give `key` another value than its default: "ink: 1.2, pen: 1.2".
std::string styles_changing(const std::string& key, const std::string& default_text) {
  std::string list;
  for (const std::string& name : builtin_preset_names()) {
    const Style style(name);
    const std::string value = style.set().value_text(key);
    if (value != default_text) list += (list.empty() ? "" : ", ") + name + ": " + value;
  }
  return list.empty() ? "—" : list;
}

std::string params(const std::string& section) {
  const Style standard("standard");
  std::vector<std::vector<std::string>> rows;
  for (const ParamSpec& spec : standard.set().specs()) {
    if (!spec.key.starts_with(section + ".")) continue;
    rows.push_back({"`" + spec.key + "`", allowed_text(spec), "`" + spec.default_text + "`",
                    styles_changing(spec.key, spec.default_text), spec.doc});
  }
  if (rows.empty()) throw InputError("README", "no style keys in section '" + section + "'");
  return table({"key", "allowed", "default", "built-in styles", "meaning"}, rows);
}

// The text of block "KIND NAME".
std::string block(const std::string& what, const CLI::App& app,
                  const std::vector<Command>& commands) {
  const size_t space = what.find(' ');
  const std::string kind = what.substr(0, space);
  const std::string name = space == std::string::npos ? "" : what.substr(space + 1);
  if (kind == "options" && name == "sylva") return own_options(app);
  if (kind == "options")
    for (const auto& [command, cmd] : commands)
      if (command == name) return own_options(*cmd);
  if (kind == "group" && groups().contains(name)) return group_options(commands, groups().at(name));
  if (kind == "params") return params(name);
  throw InputError("README", "unknown generated block '" + what + "'");
}

// What no block lists: "render --foo" or the key "ink.bar"; empty when all are listed.
std::string undocumented(const std::set<std::string>& blocks,
                         const std::vector<Command>& commands) {
  for (const auto& [command, cmd] : commands)
    for (const CLI::Option* o :
         cmd->get_options([](const CLI::Option* o) { return !is_help(o); })) {
      std::string block = "options " + command;
      for (const auto& [slug, group] : groups())
        if (o->get_group() == group) block = "group " + slug;
      if (!blocks.contains(block)) return command + " " + option_name(o) + " (" + block + ")";
    }
  const Style standard("standard");
  for (const ParamSpec& spec : standard.set().specs())
    if (!blocks.contains("params " + spec.key.substr(0, spec.key.find('.'))))
      return "the style key " + spec.key;
  return "";
}

}  // namespace

std::string generate_readme(const std::string& readme, const CLI::App& app) {
  std::vector<Command> commands;
  collect_commands(app, "", commands);
  std::istringstream in(readme);
  std::ostringstream out;
  std::set<std::string> blocks;
  std::string open;  // the block being skipped
  for (std::string line; std::getline(in, line);) {
    if (!open.empty()) {
      if (line != kEnd) continue;
      out << block(open, app, commands) << line << '\n';
      open.clear();
      continue;
    }
    out << line << '\n';
    if (line.starts_with(kBegin) && line.ends_with(kBeginEnd)) {
      open = line.substr(std::string(kBegin).size(),
                         line.size() - std::string(kBegin).size() - std::string(kBeginEnd).size());
      blocks.insert(open);
    }
  }
  if (!open.empty()) throw InputError("README", "generated block '" + open + "' is not closed");
  const std::string missing = undocumented(blocks, commands);
  if (!missing.empty()) throw InputError("README", "no generated table lists " + missing);
  return out.str();
}

}  // namespace sylva::cli

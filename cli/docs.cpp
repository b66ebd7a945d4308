#include "cli/docs.h"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "cli/option_rows.h"
#include "core/error.h"
#include "styles/presets.h"
#include "styles/style.h"

namespace sylva::cli {

namespace {

constexpr const char* kBegin = "<!-- generated: ";
constexpr const char* kBeginEnd = " -->";
constexpr const char* kEnd = "<!-- end generated -->";

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

std::string table(const std::vector<OptionRow>& rows) {
  std::vector<std::vector<std::string>> cells;
  for (const OptionRow& r : rows)
    cells.push_back({r.option, r.meaning, r.def});
  return table({"option", "meaning", "default"}, cells);
}

std::string group_options(const std::vector<Command>& commands, const std::string& heading) {
  std::vector<std::string> on;
  const std::vector<OptionRow> rows = group_option_rows(commands, heading, &on);
  std::string list;
  for (const std::string& c : on)
    list += (list.empty() ? "`" : ", `") + c + "`";
  return "On " + list + ".\n\n" + table(rows);
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

std::string params(const std::string& path, const std::string& section) {
  const Style standard("standard");
  std::vector<std::vector<std::string>> rows;
  for (const ParamSpec& spec : standard.set().specs()) {
    if (!spec.key.starts_with(section + ".")) continue;
    rows.push_back({"`" + spec.key + "`", allowed_text(spec), "`" + spec.default_text + "`",
                    styles_changing(spec.key, spec.default_text), spec.doc});
  }
  if (rows.empty()) throw InputError(path, "no style keys in section '" + section + "'");
  return table({"key", "allowed", "default", "built-in styles", "meaning"}, rows);
}

// The text of block "KIND NAME".
std::string block(const std::string& path, const std::string& what, const CLI::App& app,
                  const std::vector<Command>& commands) {
  const size_t space = what.find(' ');
  const std::string kind = what.substr(0, space);
  const std::string name = space == std::string::npos ? "" : what.substr(space + 1);
  if (kind == "options" && name == "sylva") return table(own_option_rows(app));
  if (kind == "options")
    for (const auto& [command, cmd] : commands)
      if (command == name) return table(own_option_rows(*cmd));
  if (kind == "group" && shared_groups().contains(name))
    return group_options(commands, shared_groups().at(name));
  if (kind == "params") return params(path, name);
  throw InputError(path, "unknown generated block '" + what + "'");
}

// What no block lists: "render --foo" or the key "ink.bar"; empty when all are listed.
std::string undocumented(const std::set<std::string>& blocks,
                         const std::vector<Command>& commands) {
  for (const auto& [command, cmd] : commands)
    for (const CLI::Option* o :
         cmd->get_options([](const CLI::Option* o) { return !is_help(o); })) {
      const std::string block = option_block(command, o);
      if (!blocks.contains(block)) return command + " " + option_name(o) + " (" + block + ")";
    }
  const Style standard("standard");
  for (const ParamSpec& spec : standard.set().specs())
    if (!blocks.contains("params " + spec.key.substr(0, spec.key.find('.'))))
      return "the style key " + spec.key;
  return "";
}

}  // namespace

std::vector<DocFile> generate_docs(const std::vector<DocFile>& files, const CLI::App& app) {
  const std::vector<Command> commands = commands_with_options(app);
  std::set<std::string> blocks;  // of every file
  std::vector<DocFile> out;
  for (const DocFile& file : files) {
    std::istringstream in(file.text);
    std::ostringstream text;
    std::string open;  // the block being skipped
    for (std::string line; std::getline(in, line);) {
      if (!open.empty()) {
        if (line != kEnd) continue;
        text << block(file.path, open, app, commands) << line << '\n';
        open.clear();
        continue;
      }
      text << line << '\n';
      if (line.starts_with(kBegin) && line.ends_with(kBeginEnd)) {
        open = line.substr(std::string(kBegin).size(), line.size() - std::string(kBegin).size() -
                                                           std::string(kBeginEnd).size());
        blocks.insert(open);
      }
    }
    if (!open.empty()) throw InputError(file.path, "generated block '" + open + "' is not closed");
    out.push_back({file.path, text.str()});
  }
  const std::string missing = undocumented(blocks, commands);
  if (!missing.empty()) throw InputError("docs", "no generated table lists " + missing);
  return out;
}

}  // namespace sylva::cli

#include "styles/presets.h"

#include <toml++/toml.h>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "core/io/atomic_file.h"
#include "styles/style.h"

namespace fs = std::filesystem;

namespace sylva {

namespace {

struct Loaded {
  std::string name, source, text;
  fs::path dir;  // for relative inherits; empty for built-ins
};

Loaded load(const std::string& name_or_path, const fs::path& relative_to,
            const std::string& where) {
  if (is_preset_path(name_or_path)) {
    fs::path p(name_or_path);
    if (p.is_relative() && !relative_to.empty()) p = relative_to / p;
    Loaded l;
    l.text = read_file_bytes(p.string());  // InputError(path, "no such file") when missing
    l.name = p.stem().string();
    l.source = p.string();
    l.dir = p.parent_path();
    return l;
  }
  for (const PresetFile& f : builtin_preset_files())
    if (f.name == name_or_path) return {f.name, "built-in", f.text, {}};
  std::string names;
  for (const std::string& n : builtin_preset_names())
    names += (names.empty() ? "" : ", ") + n;
  throw InputError(where, "unknown style '" + name_or_path + "' (built-in: " + names +
                              "; or a path ending in .toml)");
}

toml::table parse(const Loaded& l) {
  try {
    return toml::parse(l.text, l.source);
  } catch (const toml::parse_error& e) {
    std::ostringstream what;
    what << "line " << e.source().begin.line << ", column " << e.source().begin.column << ": "
         << e.description();
    throw InputError(l.source == "built-in" ? l.name + ".toml" : l.source, what.str());
  }
}

std::string file_label(const Loaded& l) {
  return l.source == "built-in" ? "preset '" + l.name + "'" : l.source;
}

void apply_value(const std::string& key, const toml::node& v, ParamSet& set,
                 const std::string& where) {
  if (v.is_integer() || v.is_floating_point()) {
    set.set_number(key, *v.value<double>(), where);
  } else if (v.is_boolean()) {
    set.set_bool(key, *v.value<bool>(), where);
  } else if (v.is_string()) {
    set.set_text(key, *v.value<std::string>(), where);
  } else {
    set.spec(key, where);  // an unknown key is reported as such first
    throw InputError(where, key + " must be a number, true/false or a string, not a " +
                                (v.is_array() ? std::string("list") : std::string("table")));
  }
}

// `layers = [...]`: preset names or paths (a relative path resolved against the file's folder).
std::vector<std::string> layer_names(const toml::node& v, const Loaded& l,
                                     const std::string& label) {
  const toml::array* list = v.as_array();
  if (!list || list->empty())
    throw InputError(label, "layers must be a list of one or more preset names or paths");
  std::vector<std::string> names;
  for (const toml::node& n : *list) {
    if (!n.is_string()) throw InputError(label, "layers must list strings");
    fs::path name(*n.value<std::string>());
    if (is_preset_path(name.string()) && name.is_relative() && !l.dir.empty()) name = l.dir / name;
    if (!is_preset_path(name.string())) load(name.string(), {}, label + ": layers");
    names.push_back(name.string());
  }
  return names;
}

void apply(const std::string& name_or_path, const fs::path& relative_to, ParamSet& set,
           const std::string& where, std::vector<std::string>& stack, PresetInfo& info) {
  const Loaded l = load(name_or_path, relative_to, where);
  const std::string id = l.source == "built-in" ? l.name : fs::weakly_canonical(l.source).string();
  for (const std::string& s : stack)
    if (s == id) {
      std::string cycle;
      for (const std::string& t : stack)
        cycle += t + " -> ";
      throw InputError(file_label(l), "inheritance cycle: " + cycle + id);
    }
  stack.push_back(id);
  const toml::table t = parse(l);
  const std::string label = file_label(l);
  // Inherited presets first, in order.
  if (const toml::node* inh = t.get("inherits")) {
    const toml::array* list = inh->as_array();
    if (!list) throw InputError(label, "inherits must be a list of preset names or paths");
    for (const toml::node& n : *list) {
      if (!n.is_string()) throw InputError(label, "inherits must list strings");
      apply(*n.value<std::string>(), l.dir, set, label, stack, info);
    }
  }
  std::string description;
  for (auto&& [k, v] : t) {
    const std::string key(k.str());
    if (key == "inherits") continue;
    if (key == "layers") {
      info.layers = layer_names(v, l, label);
      continue;
    }
    if (key == "description" || key == "builder") {
      if (!v.is_string()) throw InputError(label, key + " must be a string");
      const std::string text = *v.value<std::string>();
      if (key == "description") {
        description = text;
      } else {
        find_builder(text, label);  // InputError naming the builders
        info.builder = text;
      }
      continue;
    }
    const toml::table* section = v.as_table();
    if (!section) {
      throw InputError(label, "unknown top-level key '" + key +
                                  "' (allowed: description, builder, inherits, layers, and "
                                  "sections "
                                  "such as [edges])");
    }
    for (auto&& [k2, v2] : *section)
      apply_value(key + "." + std::string(k2.str()), v2, set, label);
  }
  if (!description.empty()) info.description = description;
  info.chain.push_back(l.name);
  info.name = l.name;
  info.source = l.source;
  stack.pop_back();
}

}  // namespace

bool is_preset_path(const std::string& s) {
  return s.size() > 5 && s.ends_with(".toml");
}

std::vector<std::string> builtin_preset_names() {
  std::vector<std::string> names;
  for (const PresetFile& f : builtin_preset_files())
    names.push_back(f.name);
  return names;
}

PresetInfo apply_preset(const std::string& name_or_path, ParamSet& set, const std::string& where) {
  PresetInfo info;
  std::vector<std::string> stack;
  apply(name_or_path, fs::path(), set, where, stack, info);
  const std::string label = info.source == "built-in" ? info.name + ".toml" : info.source;
  if (info.builder.empty() && info.layers.empty())
    throw InputError(label,
                     "names no builder (add builder = \"...\", layers = [...] or inherit "
                     "a preset that does)");
  if (!info.builder.empty() && !info.layers.empty())
    throw InputError(label, "names both a builder ('" + info.builder +
                                "') and layers: a stacked preset's layers name the builders");
  return info;
}

void apply_assignment(const std::string& assignment, ParamSet& set, const std::string& where) {
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(where, "expected section.key=value, got '" + assignment + "'");
  set.set_from_string(assignment.substr(0, eq), assignment.substr(eq + 1), where);
}

}  // namespace sylva

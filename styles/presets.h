// Style presets (DESIGN.md §2, §4): a TOML file names a style builder and only the parameters
// it changes, optionally on top of other presets:
//
//   description = "Pen drawing"        # one line, shown by `sylva styles`
//   builder = "ink"                    # a builder of styles/style.h
//   inherits = ["expressive"]          # applied first, in order; later ones win
//   [edges]
//   width = 2.0                        # any key of bind_style_params, in its section
//
// A stacked preset names `layers = ["watercolor", "ink"]` (presets, not builders) instead of a
// builder: each layer is its own preset, drawn from one set of G-buffers and composited in
// order (styles/style.h, Style); the keys the stacked preset sets apply to every layer.
//
// Built-in presets (styles/presets/*.toml) are compiled into the binary; `--style my.toml`
// loads a user file, whose `inherits` may name built-ins or other files (relative to it).
// Syntax errors (with line and column), unknown keys, wrong types, out-of-range values,
// unknown builders, missing files and inheritance cycles throw InputError naming the file.
#pragma once

#include <string>
#include <vector>

#include "core/params.h"

namespace sylva {

struct PresetFile {
  std::string name;  // file stem: "ink"
  std::string text;  // TOML
};
// Generated from styles/presets/*.toml (styles/CMakeLists.txt).
const std::vector<PresetFile>& builtin_preset_files();

struct PresetInfo {
  std::string name;                 // built-in name or the file's stem
  std::string source;               // "built-in" or the file path
  std::string description;          // the preset's own, else the nearest inherited one
  std::string builder;              // the last one set along the inheritance chain; "" = layers
  std::vector<std::string> layers;  // a stacked preset's layers (the last set along the chain)
  std::vector<std::string> chain;   // presets applied, in order, ending with this one
};

bool is_preset_path(const std::string& name_or_path);  // ends in .toml
std::vector<std::string> builtin_preset_names();

// Applies `name_or_path` to `set` (inherited presets first). `where` names the option that
// asked for it in errors about the name itself ("--style").
PresetInfo apply_preset(const std::string& name_or_path, ParamSet& set,
                        const std::string& where = "--style");

// "section.key=value" from the command line; throws InputError(where, ...).
void apply_assignment(const std::string& assignment, ParamSet& set, const std::string& where);

}  // namespace sylva

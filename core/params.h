// Named, range-checked parameters (DESIGN.md §4): a pass or style binds the fields of its
// parameter struct to dotted keys ("edges.width") with their type, unit, default (the field's
// value at bind time), valid range and a one-line doc. Presets (TOML), `--set key=value` and
// `--sweep` all go through set_*(), which check the type and the range and throw InputError
// naming where the value came from, the key and what is allowed. specs() lists every key for
// `sylva styles` and the README.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace sylva {

enum class ParamType { Float, Int, Bool, Color, Choice, Text };

struct ParamSpec {
  std::string key;  // "edges.width"
  ParamType type = ParamType::Float;
  double min = 0, max = 0;           // Float and Int: inclusive range
  bool min_open = false;             // Float: (min, ...] instead of [min, ...]
  std::vector<std::string> choices;  // Choice
  std::string forms;                 // Text: the accepted forms
  std::string unit;                  // "px at 1024 px", "degrees", "" for none
  std::string doc;                   // one line
  std::string default_text;          // the bound field's value when bound, as text
};

class ParamSet {
 public:
  // The field must outlive the set. Throws (SYLVA_CHECK) on a duplicate key or a default
  // outside its own range.
  void add_float(const std::string& key, float& field, double min, double max,
                 const std::string& unit, const std::string& doc, bool min_open = false);
  void add_int(const std::string& key, int& field, int min, int max, const std::string& unit,
               const std::string& doc);
  void add_bool(const std::string& key, bool& field, const std::string& doc);
  // "#RRGGBB" (sRGB) stored as linear RGB in [0, 1].
  void add_color(const std::string& key, glm::vec3& field, const std::string& doc);
  void add_choice(const std::string& key, std::string& field, std::vector<std::string> choices,
                  const std::string& doc);
  // Free text checked by `check` (which throws InputError(where, ...) when it is not
  // acceptable), e.g. "auto", "0.3" or "8%" for a scene length; `forms` describes them.
  using TextCheck = std::function<void(const std::string& text, const std::string& where)>;
  void add_text(const std::string& key, std::string& field, TextCheck check,
                const std::string& forms, const std::string& doc);

  bool has(const std::string& key) const;
  const std::vector<ParamSpec>& specs() const { return m_specs; }
  const ParamSpec& spec(const std::string& key, const std::string& where) const;

  // Typed setters (TOML values). `where` names the source, e.g. "ink.toml" or "--set".
  // Errors: unknown key (listing the section's keys), wrong type, out of range.
  void set_number(const std::string& key, double value, const std::string& where);
  void set_bool(const std::string& key, bool value, const std::string& where);
  void set_text(const std::string& key, const std::string& value, const std::string& where);
  // From the command line: parses `text` by the key's type ("2", "true", "#102030", "auto").
  void set_from_string(const std::string& key, const std::string& text, const std::string& where);

  std::string value_text(
      const std::string& key) const;  // current value, as set_from_string reads it

 private:
  struct Binding {
    float* f = nullptr;
    int* i = nullptr;
    bool* b = nullptr;
    glm::vec3* c = nullptr;
    std::string* s = nullptr;
    TextCheck check;
  };
  size_t index(const std::string& key, const std::string& where) const;
  void add(ParamSpec spec, Binding binding);
  std::vector<ParamSpec> m_specs;
  std::vector<Binding> m_bindings;
};

// "#RRGGBB" → linear RGB; false when malformed.
bool parse_hex_color(const std::string& text, glm::vec3& linear);
std::string hex_color(const glm::vec3& linear);

}  // namespace sylva

// Named, range-checked parameters (DESIGN.md §4): a pass or style binds the fields of its
// parameter struct to dotted keys ("edges.width") with their type, unit, default (the field's
// value at bind time), valid range and a one-line doc. Presets (TOML), `--set key=value` and
// `--sweep` and the CLI's aliases (`--rho` for foliage.rho) all go through set_*(), which check
// the type and the range and throw InputError naming where the value came from, the key and
// what is allowed; a choice is parsed into its enum there. specs() is the one declaration of
// every key: `sylva styles`, the CLI's aliases and help, and the README's tables are made
// from it.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
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

// What a spec accepts, as `sylva styles` and the README print it: "[0, 1] px", "(0, 100]",
// "true | false", "\"#RRGGBB\"", "a | b | c" or the text forms.
std::string allowed_text(const ParamSpec& spec);

// A value for a key and where it was given, e.g. {"foliage.rho", "8%", "--rho"}: what a
// program or the CLI's aliases apply to a set after its preset (ParamSet::set_from_string).
struct ParamAssignment {
  std::string key, value, where;
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
  // A choice parsed into an enum when set: `choices` pairs each accepted name with its value.
  template <typename E>
  void add_choice(const std::string& key, E& field, std::vector<std::pair<std::string, E>> choices,
                  const std::string& doc) {
    std::vector<std::string> names;
    auto values = std::make_shared<std::vector<E>>();
    for (auto& [name, value] : choices) {
      names.push_back(name);
      values->push_back(value);
    }
    E* f = &field;
    add_choice_binding(
        key, std::move(names), doc, [f, values](size_t i) { *f = (*values)[i]; },
        [f, values] {
          for (size_t i = 0; i < values->size(); ++i)
            if ((*values)[i] == *f) return i;
          return values->size();
        });
  }
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

  void set(const ParamAssignment& a) { set_from_string(a.key, a.value, a.where); }

  std::string value_text(
      const std::string& key) const;  // current value, as set_from_string reads it
  // Where the key's value was last set ("ink.toml", "--set", "--rho"); "" = the bound default.
  const std::string& source(const std::string& key) const;

  // Checks every bound field's current value as the setters would (for fields a program
  // filled in directly); throws InputError(where, ...) naming the key.
  void check_values(const std::string& where) const;
  // The same, each InputError naming its own key as where it is (e.g. "blobs.peaks").
  void check_values() const;

 private:
  struct Binding {
    float* f = nullptr;
    int* i = nullptr;
    bool* b = nullptr;
    glm::vec3* c = nullptr;
    std::string* s = nullptr;  // Text
    TextCheck check;
    std::function<void(size_t)> set_choice;  // Choice: store choices[i]
    std::function<size_t()> choice;          // Choice: the index of the value (size() = none)
  };
  void add_choice_binding(const std::string& key, std::vector<std::string> choices,
                          const std::string& doc, std::function<void(size_t)> set,
                          std::function<size_t()> get);
  size_t index(const std::string& key, const std::string& where) const;
  void check_value(size_t i, const std::string& where) const;
  void add(ParamSpec spec, Binding binding);
  void check_number(size_t i, double value, const std::string& where) const;
  std::vector<ParamSpec> m_specs;
  std::vector<Binding> m_bindings;
  std::vector<std::string> m_sources;
};

// "#RRGGBB" → linear RGB; false when malformed.
bool parse_hex_color(const std::string& text, glm::vec3& linear);
std::string hex_color(const glm::vec3& linear);

}  // namespace sylva

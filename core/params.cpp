#include "core/params.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/color.h"
#include "core/error.h"

namespace sylva {

namespace {

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// A float as the shortest of %.6g and %.9g that reads back as the same float, so what
// value_text prints is accepted again by an open range bound.
std::string float_text(float v) {
  const std::string shorter = number_text(v);
  if (std::strtof(shorter.c_str(), nullptr) == v) return shorter;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", double(v));
  return buf;
}

std::string range_text(const ParamSpec& s) {
  return std::string(s.min_open ? "(" : "[") + number_text(s.min) + ", " + number_text(s.max) + "]";
}

std::string choices_list(const ParamSpec& s) {
  std::string list;
  for (const std::string& c : s.choices)
    list += (list.empty() ? "" : ", ") + c;
  return list;
}

std::string section_of(const std::string& key) {
  const size_t dot = key.find('.');
  return dot == std::string::npos ? std::string() : key.substr(0, dot);
}

}  // namespace

bool parse_hex_color(const std::string& text, glm::vec3& linear) {
  if (text.size() != 7 || text[0] != '#') return false;
  for (int c = 0; c < 3; ++c) {
    unsigned v = 0;
    const char* b = text.data() + 1 + 2 * c;
    auto [p, ec] = std::from_chars(b, b + 2, v, 16);
    if (ec != std::errc() || p != b + 2) return false;
    linear[c] = srgb_to_linear(float(v) / 255.0f);
  }
  return true;
}

std::string hex_color(const glm::vec3& linear) {
  char buf[8];
  int v[3];
  for (int c = 0; c < 3; ++c)
    v[c] = int(std::lround(std::clamp(linear_to_srgb(linear[c]), 0.0f, 1.0f) * 255.0f));
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", v[0], v[1], v[2]);
  return buf;
}

std::string allowed_text(const ParamSpec& s) {
  switch (s.type) {
    case ParamType::Float:
    case ParamType::Int:
      return range_text(s) + (s.unit.empty() ? "" : " " + s.unit);
    case ParamType::Bool:
      return "true | false";
    case ParamType::Color:
      return "\"#RRGGBB\"";
    case ParamType::Choice: {
      std::string c;
      for (const std::string& x : s.choices)
        c += (c.empty() ? "" : " | ") + x;
      return c;
    }
    case ParamType::Text:
      return s.forms;
  }
  return "";
}

void ParamSet::add(ParamSpec spec, Binding binding) {
  SYLVA_CHECK(!has(spec.key), "duplicate parameter " + spec.key);
  m_specs.push_back(std::move(spec));
  m_bindings.push_back(std::move(binding));
  m_sources.emplace_back();
  m_specs.back().default_text = value_text(m_specs.back().key);
}

void ParamSet::add_float(const std::string& key, float& field, double min, double max,
                         const std::string& unit, const std::string& doc, bool min_open) {
  SYLVA_CHECK(std::isfinite(field) && (min_open ? field > min : field >= min) && field <= max,
              "default of " + key + " outside its range");
  ParamSpec s;
  s.key = key;
  s.type = ParamType::Float;
  s.min = min;
  s.max = max;
  s.min_open = min_open;
  s.unit = unit;
  s.doc = doc;
  Binding b;
  b.f = &field;
  add(std::move(s), std::move(b));
}

void ParamSet::add_int(const std::string& key, int& field, int min, int max,
                       const std::string& unit, const std::string& doc) {
  SYLVA_CHECK(field >= min && field <= max, "default of " + key + " outside its range");
  ParamSpec s;
  s.key = key;
  s.type = ParamType::Int;
  s.min = min;
  s.max = max;
  s.unit = unit;
  s.doc = doc;
  Binding b;
  b.i = &field;
  add(std::move(s), std::move(b));
}

void ParamSet::add_bool(const std::string& key, bool& field, const std::string& doc) {
  ParamSpec s;
  s.key = key;
  s.type = ParamType::Bool;
  s.doc = doc;
  Binding b;
  b.b = &field;
  add(std::move(s), std::move(b));
}

void ParamSet::add_color(const std::string& key, glm::vec3& field, const std::string& doc) {
  ParamSpec s;
  s.key = key;
  s.type = ParamType::Color;
  s.doc = doc;
  Binding b;
  b.c = &field;
  add(std::move(s), std::move(b));
}

void ParamSet::add_choice(const std::string& key, std::string& field,
                          std::vector<std::string> choices, const std::string& doc) {
  auto names = std::make_shared<const std::vector<std::string>>(choices);
  std::string* f = &field;
  add_choice_binding(
      key, std::move(choices), doc, [f, names](size_t i) { *f = (*names)[i]; },
      [f, names] { return size_t(std::find(names->begin(), names->end(), *f) - names->begin()); });
}

void ParamSet::add_choice_binding(const std::string& key, std::vector<std::string> choices,
                                  const std::string& doc, std::function<void(size_t)> set,
                                  std::function<size_t()> get) {
  SYLVA_CHECK(get() < choices.size(), "default of " + key + " is not one of its choices");
  ParamSpec s;
  s.key = key;
  s.type = ParamType::Choice;
  s.choices = std::move(choices);
  s.doc = doc;
  Binding b;
  b.set_choice = std::move(set);
  b.choice = std::move(get);
  add(std::move(s), std::move(b));
}

void ParamSet::add_text(const std::string& key, std::string& field, TextCheck check,
                        const std::string& forms, const std::string& doc) {
  check(field, key);  // the default must pass its own check
  ParamSpec s;
  s.key = key;
  s.type = ParamType::Text;
  s.forms = forms;
  s.doc = doc;
  Binding b;
  b.s = &field;
  b.check = std::move(check);
  add(std::move(s), std::move(b));
}

bool ParamSet::has(const std::string& key) const {
  for (const ParamSpec& s : m_specs)
    if (s.key == key) return true;
  return false;
}

size_t ParamSet::index(const std::string& key, const std::string& where) const {
  for (size_t i = 0; i < m_specs.size(); ++i)
    if (m_specs[i].key == key) return i;
  // List the keys of the same section (or the sections) so a typo is easy to fix.
  const std::string section = section_of(key);
  std::string known;
  for (const ParamSpec& s : m_specs) {
    const std::string other = section_of(s.key);
    const std::string item = other == section && !section.empty() ? s.key : other + ".*";
    if (known.find(item) == std::string::npos) known += (known.empty() ? "" : ", ") + item;
  }
  throw InputError(where, "unknown key '" + key + "' (known: " + known + ")");
}

const ParamSpec& ParamSet::spec(const std::string& key, const std::string& where) const {
  return m_specs[index(key, where)];
}

void ParamSet::check_number(size_t i, double value, const std::string& where) const {
  const ParamSpec& s = m_specs[i];
  const auto outside = [&](const char* as) {
    throw InputError(where, s.key + " = " + number_text(value) + " is outside " + range_text(s) +
                                as + (s.unit.empty() ? "" : " " + s.unit));
  };
  const bool below = s.min_open ? !(value > s.min) : !(value >= s.min);
  if (!std::isfinite(value) || below || value > s.max) outside("");
  if (s.type == ParamType::Int) {
    if (value != std::floor(value))
      throw InputError(where, s.key + " must be a whole number, got " + number_text(value));
  } else {
    // As a float: a value the double range admits may round to the open bound (1e-50 in
    // (0, ...] becomes 0) or overflow.
    const float f = float(value);
    if (!std::isfinite(f) || (s.min_open && !(f > s.min))) outside(" as a 32-bit float");
  }
}

void ParamSet::set_number(const std::string& key, double value, const std::string& where) {
  const size_t i = index(key, where);
  const ParamSpec& s = m_specs[i];
  if (s.type == ParamType::Text) {
    set_text(key, number_text(value), where);
    return;
  }
  if (s.type != ParamType::Float && s.type != ParamType::Int)
    throw InputError(where, key + " must be " +
                                (s.type == ParamType::Bool ? std::string("true or false")
                                                           : std::string("a text value")) +
                                ", got the number " + number_text(value));
  check_number(i, value, where);
  if (s.type == ParamType::Int)
    *m_bindings[i].i = int(value);
  else
    *m_bindings[i].f = float(value);
  m_sources[i] = where;
}

void ParamSet::set_bool(const std::string& key, bool value, const std::string& where) {
  const size_t i = index(key, where);
  if (m_specs[i].type != ParamType::Bool)
    throw InputError(where, key + " is not a true/false value");
  *m_bindings[i].b = value;
  m_sources[i] = where;
}

void ParamSet::set_text(const std::string& key, const std::string& value,
                        const std::string& where) {
  const size_t i = index(key, where);
  const ParamSpec& s = m_specs[i];
  switch (s.type) {
    case ParamType::Color: {
      glm::vec3 c;
      if (!parse_hex_color(value, c))
        throw InputError(where, key + " must be a colour \"#RRGGBB\", got \"" + value + "\"");
      *m_bindings[i].c = c;
      break;
    }
    case ParamType::Choice: {
      const auto at = std::find(s.choices.begin(), s.choices.end(), value);
      if (at == s.choices.end())
        throw InputError(where, key + " = \"" + value + "\" is not one of " + choices_list(s));
      m_bindings[i].set_choice(size_t(at - s.choices.begin()));
      break;
    }
    case ParamType::Text:
      m_bindings[i].check(value, where + ": " + key);
      *m_bindings[i].s = value;
      break;
    default:
      throw InputError(where, key + " must be " +
                                  (s.type == ParamType::Bool ? std::string("true or false")
                                                             : "a number in " + range_text(s)) +
                                  ", got \"" + value + "\"");
  }
  m_sources[i] = where;
}

void ParamSet::set_from_string(const std::string& key, const std::string& text,
                               const std::string& where) {
  const ParamSpec& s = m_specs[index(key, where)];
  if (s.type == ParamType::Float || s.type == ParamType::Int) {
    double v = 0.0;
    const char* end = text.data() + text.size();
    auto [p, ec] = std::from_chars(text.data(), end, v);
    if (text.empty() || ec != std::errc() || p != end)
      throw InputError(where,
                       key + " must be a number in " + range_text(s) + ", got \"" + text + "\"");
    set_number(key, v, where);
  } else if (s.type == ParamType::Bool) {
    if (text == "true" || text == "1" || text == "on") {
      set_bool(key, true, where);
    } else if (text == "false" || text == "0" || text == "off") {
      set_bool(key, false, where);
    } else {
      throw InputError(where, key + " must be true or false, got \"" + text + "\"");
    }
  } else {
    set_text(key, text, where);
  }
}

std::string ParamSet::value_text(const std::string& key) const {
  const size_t i = index(key, "parameter");
  const Binding& b = m_bindings[i];
  switch (m_specs[i].type) {
    case ParamType::Float:
      return float_text(*b.f);
    case ParamType::Int:
      return std::to_string(*b.i);
    case ParamType::Bool:
      return *b.b ? "true" : "false";
    case ParamType::Color:
      return hex_color(*b.c);
    case ParamType::Choice: {
      const size_t c = b.choice();
      SYLVA_CHECK(c < m_specs[i].choices.size(), key + " holds a value that is not a choice");
      return m_specs[i].choices[c];
    }
    case ParamType::Text:
      return *b.s;
  }
  return "";
}

const std::string& ParamSet::source(const std::string& key) const {
  return m_sources[index(key, "parameter")];
}

void ParamSet::check_values(const std::string& where) const {
  for (size_t i = 0; i < m_specs.size(); ++i)
    check_value(i, where);
}

void ParamSet::check_values() const {
  for (size_t i = 0; i < m_specs.size(); ++i)
    check_value(i, m_specs[i].key);
}

void ParamSet::check_value(size_t i, const std::string& where) const {
  const ParamSpec& s = m_specs[i];
  const Binding& b = m_bindings[i];
  switch (s.type) {
    case ParamType::Float:
      check_number(i, double(*b.f), where);
      break;
    case ParamType::Int:
      check_number(i, double(*b.i), where);
      break;
    case ParamType::Bool:
      break;
    case ParamType::Color:
      for (int c = 0; c < 3; ++c)
        if (!((*b.c)[c] >= 0.0f && (*b.c)[c] <= 1.0f))
          throw InputError(where, s.key + " must be a colour with linear channels in [0, 1]");
      break;
    case ParamType::Choice:
      if (b.choice() >= s.choices.size())
        throw InputError(where, s.key + " holds a value that is not one of " + choices_list(s));
      break;
    case ParamType::Text:
      b.check(*b.s, where == s.key ? where : where + ": " + s.key);
      break;
  }
}

}  // namespace sylva

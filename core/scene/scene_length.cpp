#include "core/scene/scene_length.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace sylva {

namespace {

bool parse_number(const std::string& s, double& out) {
  if (s.empty()) return false;
  const char* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, out);
  return ec == std::errc() && p == end && std::isfinite(out);
}

}  // namespace

SceneLength SceneLength::parse(const std::string& text, const std::string& where) {
  SceneLength l;
  if (text == "auto") return l;
  const std::string forms =
      "expected 'auto', a length in scene units > 0 (e.g. 0.3) or a "
      "percentage of the scene (e.g. 8%), got '" +
      text + "'";
  if (!text.empty() && text.back() == '%') {
    if (!parse_number(text.substr(0, text.size() - 1), l.value) || !(l.value > 0.0) ||
        l.value > 10000.0)
      throw InputError(where, forms + "; percentages must be in (0, 10000]");
    l.kind = Kind::Relative;
    return l;
  }
  if (!parse_number(text, l.value) || !(l.value > 0.0)) throw InputError(where, forms);
  l.kind = Kind::Absolute;
  return l;
}

double SceneLength::resolve(double reference, double automatic) const {
  switch (kind) {
    case Kind::Absolute:
      return value;
    case Kind::Relative:
      return value * 0.01 * reference;
    case Kind::Auto:
      break;
  }
  return automatic;
}

std::string SceneLength::str() const {
  if (kind == Kind::Auto) return "auto";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g%s", value, kind == Kind::Relative ? "%" : "");
  return buf;
}

}  // namespace sylva

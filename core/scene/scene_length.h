// A length in scene units that can also be given relative to the scene ("8%" of a reference
// length such as the foliage diagonal) or left to a rule ("auto"), so presets and options
// work on models of any scale (DESIGN.md §4).
#pragma once

#include <string>

namespace sylva {

struct SceneLength {
  enum class Kind { Auto, Absolute, Relative };
  Kind kind = Kind::Auto;
  double value = 0.0;  // Absolute: scene units; Relative: percent of the reference

  // "auto", "0.3" (scene units, > 0, finite) or "8%" (of the reference, in (0, 10000]).
  // Throws InputError(where, ...) naming the accepted forms.
  static SceneLength parse(const std::string& text, const std::string& where);
  // The length in scene units: the absolute value, the share of `reference`, or `automatic`.
  double resolve(double reference, double automatic) const;
  std::string str() const;  // round-trips through parse
};

}  // namespace sylva

// For the parameter harnesses: every value in the set reads back through set_from_string
// (what `sylva styles` prints is accepted again), so no accepted input left a value out of
// its range or not finite.
#pragma once

#include "core/params.h"
#include "tests/fuzz/fuzz_support.h"

namespace sylva::fuzz {

inline void check_params_read_back(ParamSet& set) {
  for (const ParamSpec& spec : std::vector<ParamSpec>(set.specs())) {
    const std::string text = set.value_text(spec.key);
    try {
      set.set_from_string(spec.key, text, "read back");
    } catch (const InputError& e) {
      fail(spec.key + " = " + text + " does not read back: " + e.what());
    }
  }
}

}  // namespace sylva::fuzz

// CLI options made from ParamSet specs (core/params.h): "--rho" for foliage.rho, an alias of
// `--set foliage.rho=VALUE`. The option's help, default and type come from the spec, and its
// value is checked by the spec when it is applied (errors name the option and the key).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "core/params.h"

namespace sylva::cli {

// "foliage.ka_min" -> "--ka-min": the key after its section, '_' as '-'.
std::string option_of_key(const std::string& key);

// Adds an option per spec (a flag for a Bool) to `group`, leaving out the keys in `skip`.
void add_param_options(CLI::App& cmd, const std::vector<ParamSpec>& specs, const std::string& group,
                       const std::vector<std::string>& skip = {});

// The options of `specs` given on `cmd`, as assignments naming the option ("--rho").
std::vector<ParamAssignment> given_param_options(const CLI::App& cmd,
                                                 const std::vector<ParamSpec>& specs);

}  // namespace sylva::cli

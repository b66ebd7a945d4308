// Options of the Luft preprocessing (render, buffers, bake, and later tradeoff): --rho,
// --tau, --fraction, --grid, --blend, --normal-source, --ka-min, --d-min, --exponent,
// --ka-encoding, --smooth, --decimate, --per-triangle, --surface-out, --no-cache, --cache-dir.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "npr/illumination_pass.h"

namespace sylva::cli {

using IlluminationOptions = FoliageSettings;
// with_ka_encoding = false leaves out --ka-encoding (for bake, which writes ka both ways).
void add_illumination_options(CLI::App& cmd, IlluminationOptions& o, bool with_ka_encoding = true);

// Copies the options of add_illumination_options given explicitly on `cmd` into `set`
// (foliage.* keys), so they win over a preset; errors name the option.
void apply_explicit_illumination_options(const CLI::App& cmd, ParamSet& set);

// Parses and range-checks; seed comes from the scene options. Throws InputError naming the
// option.
IlluminationSetup illumination_setup(const IlluminationOptions& o, uint64_t seed,
                                     const Scene& scene);

// The result cache folder of --cache-dir / --no-cache: "" with --no-cache, else --cache-dir,
// else default_cache_dir().
std::string result_cache_dir(const IlluminationOptions& o);

}  // namespace sylva::cli

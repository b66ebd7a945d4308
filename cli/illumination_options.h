// Options of the Luft preprocessing (render, buffers, bake, and later tradeoff): --rho,
// --tau, --fraction, --grid, --blend, --normal-source, --ka-min, --d-min, --exponent,
// --ka-encoding, --smooth, --decimate, --per-triangle, --surface-out, --no-cache, --cache-dir.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "npr/illumination_pass.h"

namespace sylva::cli {

struct IlluminationOptions {
  std::string rho = "auto", tau = "auto", fraction = "auto", d_min = "auto";
  int grid = 128;
  float blend = 1.0f;
  std::string normal_source = "surface";
  float ka_min = 0.2f;
  float exponent = 1.0f;
  std::string ka_encoding = "attribute";
  int smooth = 0;
  double decimate = 1.0;
  bool per_triangle = false;
  std::string surface_out;
  bool no_cache = false;
  std::string cache_dir;  // empty = default_cache_dir()
};
// with_ka_encoding = false leaves out --ka-encoding (for bake, which writes ka both ways).
void add_illumination_options(CLI::App& cmd, IlluminationOptions& o, bool with_ka_encoding = true);

// Parses and range-checks; seed comes from the scene options. Throws InputError naming the
// option.
IlluminationSetup illumination_setup(const IlluminationOptions& o, uint64_t seed,
                                     const Scene& scene);

}  // namespace sylva::cli

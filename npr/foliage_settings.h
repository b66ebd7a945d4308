// The Luft preprocessing's settings as a user gives them (the foliage.* preset keys, `--set
// foliage.*`, and the CLI's --rho, --tau, ... made from the same specs), declared once as
// ParamSet specs, and their resolution into FoliageParams (npr/foliage_illumination.h): the
// enums are parsed when set, "auto" and relative lengths are left for the preprocessing to
// resolve against the scene. A program renders with these without any CLI code.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/params.h"
#include "npr/foliage_illumination.h"

namespace sylva {

struct FoliageSettings {
  // Text where "auto" or a relative length is allowed (see bind_foliage_params).
  std::string rho = "auto", tau = "auto", fraction = "auto", d_min = "auto";
  int grid = 128;
  float blend = 1.0f;
  NormalSource normal_source = NormalSource::Surface;
  float ka_min = 0.2f;
  float exponent = 1.0f;
  KaEncoding ka_encoding = KaEncoding::Attribute;  // exact inside triangles (sylva tradeoff)
  int smooth = 0;
  float decimate = 1.0f;
  bool per_triangle = false;
  // Not a preset key: rho = auto's radius from the picture's scale (FoliageParams::
  // picture_rho), set by styles with ink.detail; 0 = none.
  double picture_rho = 0.0;
};

// Binds the preset keys foliage.rho, .tau, .fraction, .grid, .blend, .normal_source, .ka_min,
// .d_min, .exponent, .ka_encoding, .smooth, .decimate, .per_triangle with their ranges.
void bind_foliage_params(ParamSet& set, FoliageSettings& s);
// The specs bind_foliage_params declares, with the defaults of FoliageSettings{}.
std::vector<ParamSpec> foliage_param_specs();

// The preprocessing's parameters for `settings` (checked against the specs first: InputError
// naming the key) with `seed` choosing the leaves a fraction keeps.
FoliageParams foliage_params(const FoliageSettings& settings, uint64_t seed);

// The parameter names the preprocessing's errors use ("tau", "ka-min", see
// compute_foliage_illumination), each mapped to its key and where `set` took its value:
// "foliage.tau (from --tau)", or "foliage.tau" for the default.
std::map<std::string, std::string> foliage_parameter_names(const ParamSet& set);

}  // namespace sylva

#include "npr/foliage_settings.h"

#include <charconv>
#include <cmath>

#include "core/error.h"

namespace sylva {

namespace {

// "auto" -> nullopt, else the finite number `text` holds; nullopt and false when it holds none.
bool parse_auto_or_number(const std::string& text, std::optional<double>& value) {
  value.reset();
  if (text == "auto") return true;
  double v = 0.0;
  const char* end = text.data() + text.size();
  auto [p, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || p != end || !std::isfinite(v)) return false;
  value = v;
  return true;
}

// "auto" or a finite number accepted by `ok`; throws InputError(where, "<forms>").
ParamSet::TextCheck auto_or(bool (*ok)(double), const char* forms) {
  return [ok, forms](const std::string& text, const std::string& where) {
    std::optional<double> v;
    if (!parse_auto_or_number(text, v) || (v && !ok(*v)))
      throw InputError(where, std::string("must be ") + forms + ", got '" + text + "'");
  };
}

}  // namespace

void bind_foliage_params(ParamSet& set, FoliageSettings& s) {
  set.add_text(
      "foliage.rho", s.rho,
      [](const std::string& text, const std::string& where) { SceneLength::parse(text, where); },
      "auto, scene units (0.3) or % of the foliage diagonal (8%)",
      "radius of influence of each leaf (Luft Eq. 2); auto = max(8%, 3 x the mean leaf spacing)");
  set.add_text("foliage.tau", s.tau, auto_or([](double v) { return v >= 0.0; }, "'auto' or >= 0"),
               "auto or a density >= 0",
               "surface threshold (Eq. 3); auto = half the 10th percentile of the density at "
               "the leaves (the surface wraps nearly every leaf)");
  set.add_text("foliage.fraction", s.fraction,
               auto_or([](double v) { return v > 0.0 && v <= 1.0; }, "'auto' or in (0, 1]"),
               "auto or (0, 1]",
               "share of leaves used as generators (Luft §3.1's speed-up); auto = all, up to "
               "2^28 kernel evaluations (about 30% of a 100,000-leaf tree at grid 128)");
  set.add_int("foliage.grid", s.grid, 2, 1024, "cells",
              "marching-cubes cells along the longest axis");
  set.add_float("foliage.blend", s.blend, 0, 1, "",
                "weight of the surface normal: N' = normalize((1 - blend) N + blend N_s) (Luft "
                "§3.3)");
  set.add_choice("foliage.normal_source", s.normal_source,
                 {{"surface", NormalSource::Surface}, {"gradient", NormalSource::Gradient}},
                 "nearest implicit-surface vertex, or -grad F at the vertex");
  set.add_float("foliage.ka_min", s.ka_min, 0, 1, "",
                "smallest ambient coefficient (Eq. 4): ka falls from 1 at density 0 to ka_min "
                "at d_min");
  set.add_text("foliage.d_min", s.d_min, auto_or([](double v) { return v > 0.0; }, "'auto' or > 0"),
               "auto or a density > 0",
               "density where ka reaches ka_min (Eq. 4); auto = the 90th percentile of the "
               "density at foliage vertices");
  set.add_float("foliage.exponent", s.exponent, 0, 100, "", "exponent n of Eq. 4", true);
  set.add_choice("foliage.ka_encoding", s.ka_encoding,
                 {{"attribute", KaEncoding::Attribute}, {"length", KaEncoding::Length}},
                 "where ka goes: a vertex attribute, or the normal's length (Luft; interpolation "
                 "shortens it, so triangle interiors come out darker: sylva tradeoff measures it)");
  set.add_int("foliage.smooth", s.smooth, 0, 100, "passes", "Laplacian smoothing of the surface");
  set.add_float("foliage.decimate", s.decimate, 0, 1, "", "share of surface triangles kept", true);
  set.add_bool("foliage.per_triangle", s.per_triangle,
               "one generator per foliage triangle instead of per leaf");
}

std::vector<ParamSpec> foliage_param_specs() {
  FoliageSettings s;
  ParamSet set;
  bind_foliage_params(set, s);
  return set.specs();
}

FoliageParams foliage_params(const FoliageSettings& settings, uint64_t seed) {
  // The specs check the values: bound to defaults (which pass the binding's own checks), then
  // given the settings' values.
  FoliageSettings s;
  ParamSet set;
  bind_foliage_params(set, s);
  s = settings;
  set.check_values("foliage settings");

  FoliageParams p;
  p.rho = SceneLength::parse(s.rho, "foliage.rho");
  p.picture_rho = s.picture_rho;
  std::optional<double> v;
  parse_auto_or_number(s.tau, v);
  if (v) p.tau = float(*v);
  parse_auto_or_number(s.fraction, v);
  p.fraction = v;
  parse_auto_or_number(s.d_min, v);
  if (v) {
    p.ambient.d_min = float(*v);
    p.d_min_auto = false;
  }
  p.grid = s.grid;
  p.blend = s.blend;
  p.normals = s.normal_source;
  p.ambient.ka_min = s.ka_min;
  p.ambient.exponent = s.exponent;
  p.optimize.smooth_iterations = s.smooth;
  p.optimize.keep_fraction = s.decimate;
  p.per_triangle = s.per_triangle;
  p.seed = seed;
  return p;
}

std::map<std::string, std::string> foliage_parameter_names(const ParamSet& set) {
  std::map<std::string, std::string> names;
  for (const char* name : {"rho", "tau", "fraction", "grid", "ka-min", "d-min", "exponent"}) {
    std::string key = std::string("foliage.") + name;
    for (char& c : key)
      if (c == '-') c = '_';
    if (!set.has(key)) continue;
    const std::string& source = set.source(key);
    names[name] = source.empty() ? key : key + " (from " + source + ")";
  }
  return names;
}

}  // namespace sylva

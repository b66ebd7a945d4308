#include "cli/illumination_options.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "cli/commands.h"
#include "core/cache/result_cache.h"
#include "core/error.h"

namespace sylva::cli {

void add_illumination_options(CLI::App& cmd, IlluminationOptions& o, bool with_ka_encoding) {
  const std::string group = "Foliage illumination (Luft et al.; styles that use it)";
  auto add = [&](const std::string& name, auto& value, const std::string& help) {
    cmd.add_option(name, value, help)->capture_default_str()->group(group);
  };
  add("--rho", o.rho,
      "Radius of influence: auto, scene units (0.3) or % of the foliage diagonal (8%)");
  add("--tau", o.tau, "Surface threshold: auto or a density >= 0");
  add("--fraction", o.fraction, "Share of leaves used as generators: auto or (0, 1]");
  add("--grid", o.grid, "Marching-cubes cells along the longest axis, [2, 1024]");
  add("--blend", o.blend, "Weight of the surface normal in the realigned normal, [0, 1]");
  add("--normal-source", o.normal_source,
      "surface (nearest implicit-surface vertex) or gradient (-grad F at the vertex)");
  add("--ka-min", o.ka_min, "Smallest ambient coefficient (Eq. 4), [0, 1]");
  add("--d-min", o.d_min, "Density where ka reaches ka-min: auto or > 0");
  add("--exponent", o.exponent, "Exponent n of Eq. 4, (0, 100]");
  if (with_ka_encoding)
    add("--ka-encoding", o.ka_encoding,
        "attribute (a vertex attribute) or length (in the normal, as Luft et al.)");
  add("--smooth", o.smooth, "Laplacian smoothing passes on the surface, [0, 100]");
  add("--decimate", o.decimate, "Share of surface triangles kept, (0, 1]");
  cmd.add_flag("--per-triangle", o.per_triangle, "One generator per foliage triangle")
      ->group(group);
  cmd.add_option("--surface-out", o.surface_out, "Also write the implicit surface (.glb)")
      ->group(group);
  cmd.add_flag("--no-cache", o.no_cache,
               "Recompute the preprocessing; do not read or write the cache")
      ->group(group);
  cmd.add_option("--cache-dir", o.cache_dir,
                 "Result cache folder (default $SYLVA_CACHE_DIR, else ~/.cache/sylva)")
      ->group(group);
}

namespace {

// "auto" → nullopt, else a finite number.
std::optional<double> auto_or_number(const std::string& text, const std::string& where) {
  if (text == "auto") return std::nullopt;
  double v = 0.0;
  const char* end = text.data() + text.size();
  auto [p, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || p != end || !std::isfinite(v))
    throw InputError(where, "expected 'auto' or a number, got '" + text + "'");
  return v;
}

}  // namespace

void apply_explicit_illumination_options(const CLI::App& cmd, ParamSet& set) {
  for (const CLI::Option* opt : cmd.get_options()) {
    const std::string key = foliage_key_of_option(opt->get_name());
    if (key.empty() || opt->count() == 0) continue;
    if (opt->get_expected_min() == 0) {
      set.set_bool(key, true, opt->get_name());  // a flag
    } else {
      set.set_from_string(key, opt->as<std::string>(), opt->get_name());
    }
  }
}

IlluminationSetup illumination_setup(const IlluminationOptions& o, uint64_t seed,
                                     const Scene& scene) {
  IlluminationSetup s;
  s.scene = &scene;
  FoliageParams& p = s.params;
  p.rho = SceneLength::parse(o.rho, "--rho");
  p.picture_rho = o.picture_rho;
  if (auto tau = auto_or_number(o.tau, "--tau")) {
    if (*tau < 0.0) throw InputError("--tau", "must be 'auto' or a density >= 0");
    p.tau = float(*tau);
  }
  if (auto f = auto_or_number(o.fraction, "--fraction")) {
    if (!(*f > 0.0 && *f <= 1.0)) throw InputError("--fraction", "must be 'auto' or in (0, 1]");
    p.fraction = *f;
  }
  if (auto d = auto_or_number(o.d_min, "--d-min")) {
    if (!(*d > 0.0)) throw InputError("--d-min", "must be 'auto' or a density > 0");
    p.ambient.d_min = float(*d);
    p.d_min_auto = false;
  }
  if (o.grid < 2 || o.grid > 1024) throw InputError("--grid", "must be in [2, 1024] cells");
  p.grid = o.grid;
  if (!(o.blend >= 0.0f && o.blend <= 1.0f)) throw InputError("--blend", "must be in [0, 1]");
  p.blend = o.blend;
  if (o.normal_source == "surface") {
    p.normals = NormalSource::Surface;
  } else if (o.normal_source == "gradient") {
    p.normals = NormalSource::Gradient;
  } else {
    throw InputError("--normal-source",
                     "unknown value '" + o.normal_source + "' (allowed: surface, gradient)");
  }
  p.ambient.ka_min = o.ka_min;
  p.ambient.exponent = o.exponent;
  try {
    validate_ambient(p.ambient);
  } catch (const InputError& e) {
    throw InputError("--" + e.where(), e.reason());
  }
  if (o.ka_encoding == "length") {
    s.encoding = KaEncoding::Length;
  } else if (o.ka_encoding == "attribute") {
    s.encoding = KaEncoding::Attribute;
  } else {
    throw InputError("--ka-encoding",
                     "unknown value '" + o.ka_encoding + "' (allowed: length, attribute)");
  }
  if (o.smooth < 0 || o.smooth > 100) throw InputError("--smooth", "must be in [0, 100]");
  if (!(o.decimate > 0.0 && o.decimate <= 1.0)) throw InputError("--decimate", "must be in (0, 1]");
  p.optimize.smooth_iterations = o.smooth;
  p.optimize.keep_fraction = o.decimate;
  p.per_triangle = o.per_triangle;
  p.seed = seed;
  if (!o.surface_out.empty()) check_output_path("--surface-out", o.surface_out, {".glb"});
  s.surface_out = o.surface_out;
  s.cache_dir = result_cache_dir(o);
  s.option_prefix = "--";
  s.on_done = [](const FoliageStats& st) {
    std::fprintf(stderr, "foliage illumination: %s\n", describe(st).c_str());
  };
  return s;
}

std::string result_cache_dir(const IlluminationOptions& o) {
  if (o.no_cache) return "";
  return o.cache_dir.empty() ? default_cache_dir() : o.cache_dir;
}

}  // namespace sylva::cli

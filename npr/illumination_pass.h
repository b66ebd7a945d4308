// The Luft preprocessing as a scene-level render-graph node (DESIGN.md §3): it writes
// "vertex-shading" (std::shared_ptr<const VertexShading>), which the raster pass reads only
// for styles that want realigned normals or density ka, so for every other style compile()
// culls it and nothing is computed.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "core/graph/render_graph.h"
#include "core/params.h"
#include "npr/foliage_illumination.h"

namespace sylva {

// What the normal buffer and the shading see.
enum class NormalMode {
  Original,         // the model's normals; no preprocessing
  Realigned,        // Luft §3.3 realigned unit normals, density ka
  RealignedScaled,  // as Realigned, and the normal target keeps |N| = ka (Luft Fig. 7c)
};
// "original", "realigned", "realigned-scaled"; throws InputError(where, ...).
NormalMode parse_normal_mode(const std::string& text, const std::string& where);

// The preprocessing's parameters as a user gives them (CLI options, preset keys foliage.*):
// text where "auto" or a relative length is allowed; parsed by cli::illumination_setup.
struct FoliageSettings {
  std::string rho = "auto", tau = "auto", fraction = "auto", d_min = "auto";
  int grid = 128;
  float blend = 1.0f;
  std::string normal_source = "surface";
  float ka_min = 0.2f;
  float exponent = 1.0f;
  std::string ka_encoding = "attribute";
  int smooth = 0;
  float decimate = 1.0f;
  bool per_triangle = false;
  // Not a preset key: rho = auto's radius from the picture's scale (FoliageParams::
  // picture_rho), set by styles with ink.detail; 0 = none.
  double picture_rho = 0.0;
  // Not preset keys: where the run writes and caches.
  std::string surface_out;
  bool no_cache = false;
  std::string cache_dir;  // empty = default_cache_dir()
};

// Binds the preset keys foliage.rho, .tau, .fraction, .grid, .blend, .normal_source, .ka_min,
// .d_min, .exponent, .ka_encoding, .smooth, .decimate, .per_triangle with their ranges.
void bind_foliage_params(ParamSet& set, FoliageSettings& s);
// The preset key of a CLI option ("--ka-min" -> "foliage.ka_min"); "" if it has none.
std::string foliage_key_of_option(const std::string& option);

struct IlluminationSetup {
  const Scene* scene = nullptr;  // outlives execute()
  FoliageParams params;
  KaEncoding encoding = KaEncoding::Attribute;  // exact inside triangles (see sylva tradeoff)
  std::string surface_out;  // when set, the implicit surface is written there as .glb
  std::string cache_dir;    // result cache folder (npr/foliage_cache.h); empty = no cache
  std::function<void(const FoliageStats&)> on_done;  // progress/report hook, may be empty
  std::string option_prefix;  // "--": parameter errors name the CLI option ("--tau")
  // When set, the first run stores its result here and every later run (other graphs over
  // the same scene and settings, e.g. the frames of a turntable) reuses it: the
  // preprocessing is view-independent, so it is computed once per animation.
  std::shared_ptr<std::shared_ptr<const VertexShading>> memo;
};

// Returns the "vertex-shading" resource.
int add_foliage_illumination_pass(RenderGraph& graph, IlluminationSetup setup);

}  // namespace sylva

// The Luft preprocessing as a scene-level render-graph node (DESIGN.md §3): it writes
// "vertex-shading" (std::shared_ptr<const VertexShading>), which the raster pass reads only
// for styles that want realigned normals or density ka, so for every other style compile()
// culls it and nothing is computed.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/graph/render_graph.h"
#include "core/params.h"
#include "npr/foliage_illumination.h"
#include "npr/foliage_settings.h"

namespace sylva {

// What the normal buffer and the shading see.
enum class NormalMode {
  Original,         // the model's normals; no preprocessing
  Realigned,        // Luft §3.3 realigned unit normals, density ka
  RealignedScaled,  // as Realigned, and the normal target keeps |N| = ka (Luft Fig. 7c)
};
// The names of the modes: "original", "realigned", "realigned-scaled".
std::vector<std::pair<std::string, NormalMode>> normal_mode_choices();
// One of normal_mode_choices' names; throws InputError(where, ...).
NormalMode parse_normal_mode(const std::string& text, const std::string& where);

// How a run uses the preprocessing besides its parameters: what it writes and caches.
struct FoliageRun {
  std::string surface_out;  // when set, the implicit surface is written there as .glb
  std::string cache_dir;    // result cache folder (npr/foliage_cache.h); empty = no cache
  std::function<void(const FoliageStats&)> on_done;  // progress/report hook, may be empty
};

struct IlluminationSetup {
  const Scene* scene = nullptr;  // outlives execute()
  FoliageParams params;
  KaEncoding encoding = KaEncoding::Attribute;  // exact inside triangles (see sylva tradeoff)
  std::string surface_out;  // when set, the implicit surface is written there as .glb
  std::string cache_dir;    // result cache folder (npr/foliage_cache.h); empty = no cache
  std::function<void(const FoliageStats&)> on_done;  // progress/report hook, may be empty
  // The names the preprocessing's errors use ("tau") mapped to the names to report instead
  // (foliage_parameter_names: "foliage.tau (from --tau)"); others are reported as they are.
  std::map<std::string, std::string> parameter_names;
  // When set, the first run stores its result here and every later run (other graphs over
  // the same scene and settings, e.g. the frames of a turntable) reuses it: the
  // preprocessing is view-independent, so it is computed once per animation.
  std::shared_ptr<std::shared_ptr<const VertexShading>> memo;
};

// The setup for `settings` (foliage_params, seeded by `seed`) on `scene` with `run`'s outputs;
// errors name the foliage.* keys. Throws InputError for settings outside their specs.
IlluminationSetup foliage_setup(const FoliageSettings& settings, const FoliageRun& run,
                                uint64_t seed, const Scene& scene);

// Returns the "vertex-shading" resource.
Handle<std::shared_ptr<const VertexShading>> add_foliage_illumination_pass(RenderGraph& graph,
                                                                           IlluminationSetup setup);

}  // namespace sylva

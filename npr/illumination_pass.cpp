#include "npr/illumination_pass.h"

#include <cstdio>
#include <memory>

#include "core/error.h"
#include "core/scene/gltf_write.h"
#include "core/scene/load.h"
#include "npr/foliage_cache.h"

namespace sylva {

NormalMode parse_normal_mode(const std::string& text, const std::string& where) {
  if (text == "original") return NormalMode::Original;
  if (text == "realigned") return NormalMode::Realigned;
  if (text == "realigned-scaled") return NormalMode::RealignedScaled;
  throw InputError(where,
                   "unknown value '" + text + "' (allowed: original, realigned, realigned-scaled)");
}

namespace {

void write_surface(const SurfaceMesh& surface, const std::string& path) {
  Scene s;
  Mesh m;
  m.name = "implicit_surface";
  m.positions = surface.positions;
  m.normals = surface.normals;
  m.indices = surface.indices;
  s.meshes.push_back(std::move(m));
  LoadOptions none;
  none.foliage = "none";
  finish_scene(s, none);
  write_glb(s, path);
}

}  // namespace

int add_foliage_illumination_pass(RenderGraph& graph, IlluminationSetup setup) {
  SYLVA_CHECK(setup.scene != nullptr, "foliage illumination needs a scene");
  const int out = graph.resource("vertex-shading");
  graph.add_pass("foliage-illumination", {}, {out}, [out, setup](PassContext& ctx) {
    FoliageIllumination r;
    try {
      const ResultCache cache(setup.cache_dir);
      FoliageCacheUse use;
      r = cached_foliage_illumination(*setup.scene, setup.params,
                                      setup.cache_dir.empty() ? nullptr : &cache, &use);
      if (!use.warning.empty())
        std::fprintf(stderr, "sylva: warning: result cache not written: %s\n", use.warning.c_str());
    } catch (const InputError& e) {
      if (setup.option_prefix.empty() || e.where() == "scene") throw;
      const std::string what = e.what();
      throw InputError(setup.option_prefix + e.where(), what.substr(e.where().size() + 2));
    }
    if (!setup.surface_out.empty()) write_surface(r.surface, setup.surface_out);
    if (setup.on_done) setup.on_done(r.stats);
    ctx.write(out, std::make_shared<const VertexShading>(vertex_shading(r, setup.encoding)));
  });
  return out;
}

}  // namespace sylva

#include "npr/illumination_pass.h"

#include <cstdio>
#include <memory>

#include "core/error.h"
#include "core/scene/gltf_write.h"
#include "core/scene/load.h"
#include "npr/foliage_cache.h"

namespace sylva {

std::vector<std::pair<std::string, NormalMode>> normal_mode_choices() {
  return {{"original", NormalMode::Original},
          {"realigned", NormalMode::Realigned},
          {"realigned-scaled", NormalMode::RealignedScaled}};
}

NormalMode parse_normal_mode(const std::string& text, const std::string& where) {
  std::string allowed;
  for (const auto& [name, mode] : normal_mode_choices()) {
    if (name == text) return mode;
    allowed += (allowed.empty() ? "" : ", ") + name;
  }
  throw InputError(where, "unknown value '" + text + "' (allowed: " + allowed + ")");
}

IlluminationSetup foliage_setup(const FoliageSettings& settings, const FoliageRun& run,
                                uint64_t seed, const Scene& scene) {
  IlluminationSetup s;
  s.scene = &scene;
  s.params = foliage_params(settings, seed);
  s.encoding = settings.ka_encoding;
  s.surface_out = run.surface_out;
  s.cache_dir = run.cache_dir;
  s.on_done = run.on_done;
  FoliageSettings bound = settings;
  ParamSet set;
  bind_foliage_params(set, bound);
  s.parameter_names = foliage_parameter_names(set);
  return s;
}

namespace {

Mesh surface_mesh(const SurfaceMesh& surface, const std::string& name) {
  Mesh m;
  m.name = name;
  m.positions = surface.positions;
  m.normals = surface.normals;
  m.indices = surface.indices;
  return m;
}

// The implicit surface as a .glb; in a scene of many plants each plant's surface in its own
// space, placed by its plant's instances (plants without a surface left out).
void write_surface(const FoliageIllumination& r, const Scene& scene, const std::string& path) {
  Scene s;
  if (!scene.instanced()) {
    s.meshes.push_back(surface_mesh(r.surface, "implicit_surface"));
  } else {
    std::vector<int> plant_of(scene.plants.size(), -1);
    for (size_t p = 0; p < r.plant_surfaces.size() && p < scene.plants.size(); ++p) {
      if (r.plant_surfaces[p].indices.empty()) continue;
      const std::string name = "implicit_surface " + scene.plants[p].name;
      s.plants.push_back({name, {uint32_t(s.meshes.size())}, {}});
      s.meshes.push_back(surface_mesh(r.plant_surfaces[p], name));
      plant_of[p] = int(s.plants.size() - 1);
    }
    for (const Instance& inst : scene.instances)
      if (plant_of[inst.plant] >= 0)
        s.instances.push_back({uint32_t(plant_of[inst.plant]), inst.transform, inst.name});
  }
  LoadOptions none;
  none.foliage = "none";
  finish_scene(s, none);
  write_glb(s, path);
}

}  // namespace

Handle<std::shared_ptr<const VertexShading>> add_foliage_illumination_pass(
    RenderGraph& graph, IlluminationSetup setup) {
  SYLVA_CHECK(setup.scene != nullptr, "foliage illumination needs a scene");
  const auto out = graph.resource<std::shared_ptr<const VertexShading>>("vertex-shading");
  graph.add_pass("foliage-illumination", {}, {out}, [out, setup](PassContext& ctx) {
    if (setup.memo && *setup.memo) {
      ctx.write(out, *setup.memo);
      return;
    }
    FoliageIllumination r;
    try {
      const ResultCache cache(setup.cache_dir);
      FoliageCacheUse use;
      r = cached_foliage_illumination(*setup.scene, setup.params,
                                      setup.cache_dir.empty() ? nullptr : &cache, &use);
      if (!use.warning.empty())
        std::fprintf(stderr, "sylva: warning: result cache not written: %s\n", use.warning.c_str());
    } catch (const InputError& e) {
      const auto name = setup.parameter_names.find(e.where());
      if (name == setup.parameter_names.end()) throw;
      throw InputError(name->second, e.reason());
    }
    if (!setup.surface_out.empty()) write_surface(r, *setup.scene, setup.surface_out);
    if (setup.on_done) setup.on_done(r.stats);
    auto shading = std::make_shared<const VertexShading>(vertex_shading(r, setup.encoding));
    if (setup.memo) *setup.memo = shading;
    ctx.write(out, shading);
  });
  return out;
}

}  // namespace sylva

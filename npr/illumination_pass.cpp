#include "npr/illumination_pass.h"

#include <charconv>
#include <cmath>
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

// "auto" or a finite number accepted by `ok`; throws InputError(where, "<forms>").
ParamSet::TextCheck auto_or(bool (*ok)(double), const char* forms) {
  return [ok, forms](const std::string& text, const std::string& where) {
    if (text == "auto") return;
    double v = 0.0;
    const char* end = text.data() + text.size();
    auto [p, ec] = std::from_chars(text.data(), end, v);
    if (text.empty() || ec != std::errc() || p != end || !std::isfinite(v) || !ok(v))
      throw InputError(where, std::string("must be ") + forms + ", got '" + text + "'");
  };
}

}  // namespace

void bind_foliage_params(ParamSet& set, FoliageSettings& s) {
  set.add_text(
      "foliage.rho", s.rho,
      [](const std::string& text, const std::string& where) { SceneLength::parse(text, where); },
      "auto, scene units (0.3) or % of the foliage diagonal (8%)",
      "radius of influence of each leaf (Luft Eq. 2)");
  set.add_text("foliage.tau", s.tau, auto_or([](double v) { return v >= 0.0; }, "'auto' or >= 0"),
               "auto or a density >= 0", "surface threshold (Eq. 3)");
  set.add_text("foliage.fraction", s.fraction,
               auto_or([](double v) { return v > 0.0 && v <= 1.0; }, "'auto' or in (0, 1]"),
               "auto or (0, 1]", "share of leaves used as generators");
  set.add_int("foliage.grid", s.grid, 2, 1024, "cells",
              "marching-cubes cells along the longest axis");
  set.add_float("foliage.blend", s.blend, 0, 1, "", "weight of the surface normal (Luft §3.3)");
  set.add_choice("foliage.normal_source", s.normal_source, {"surface", "gradient"},
                 "nearest implicit-surface vertex, or -grad F at the vertex");
  set.add_float("foliage.ka_min", s.ka_min, 0, 1, "", "smallest ambient coefficient (Eq. 4)");
  set.add_text("foliage.d_min", s.d_min, auto_or([](double v) { return v > 0.0; }, "'auto' or > 0"),
               "auto or a density > 0", "density where ka reaches ka_min (Eq. 4)");
  set.add_float("foliage.exponent", s.exponent, 0, 100, "", "exponent n of Eq. 4", true);
  set.add_choice("foliage.ka_encoding", s.ka_encoding, {"attribute", "length"},
                 "ka as a vertex attribute, or in the normal's length (Luft)");
  set.add_int("foliage.smooth", s.smooth, 0, 100, "passes", "Laplacian smoothing of the surface");
  set.add_float("foliage.decimate", s.decimate, 0, 1, "", "share of surface triangles kept", true);
  set.add_bool("foliage.per_triangle", s.per_triangle, "one generator per foliage triangle");
}

std::string foliage_key_of_option(const std::string& option) {
  static const char* const kOptions[] = {
      "rho",   "tau",      "fraction",    "grid",   "blend",    "normal-source", "ka-min",
      "d-min", "exponent", "ka-encoding", "smooth", "decimate", "per-triangle"};
  for (const char* o : kOptions)
    if (option == std::string("--") + o) {
      std::string key = std::string("foliage.") + o;
      for (char& c : key)
        if (c == '-') c = '_';
      return key;
    }
  return "";
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

int add_foliage_illumination_pass(RenderGraph& graph, IlluminationSetup setup) {
  SYLVA_CHECK(setup.scene != nullptr, "foliage illumination needs a scene");
  const int out = graph.resource("vertex-shading");
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
      if (setup.option_prefix.empty() || e.where() == "scene") throw;
      const std::string what = e.what();
      throw InputError(setup.option_prefix + e.where(), what.substr(e.where().size() + 2));
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

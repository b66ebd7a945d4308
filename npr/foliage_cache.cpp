#include "npr/foliage_cache.h"

#include <cmath>

#include "core/cache/content_hash.h"
#include "foliage_code_version.h"  // generated: SYLVA_FOLIAGE_CODE_VERSION

namespace sylva {

namespace {

constexpr const char* kKind = "foliage";

void add_optional(ContentHash& h, bool present, double value) {
  h.add(uint8_t(present));
  h.add(present ? value : 0.0);
}

bool finite_unit(const std::vector<glm::vec3>& v) {
  for (const glm::vec3& n : v)
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z) ||
        std::abs(glm::length(n) - 1.0f) > 1e-3f)
      return false;
  return true;
}

// FoliageStats field by field (the struct's padding would make the bytes vary).
template <class Stats, class F>
bool each_stat(Stats& s, F&& f) {
  return f(s.leaves) && f(s.generators) && f(s.rho) && f(s.tau) && f(s.fraction) && f(s.d_min) &&
         f(s.density_min) && f(s.density_max) && f(s.surface_triangles) && f(s.seconds_field) &&
         f(s.seconds_surface) && f(s.seconds_shading);
}

}  // namespace

std::string foliage_cache_key(const Scene& scene, const FoliageParams& p) {
  ContentHash h;
  h.add(std::string(SYLVA_FOLIAGE_CODE_VERSION));
  h.add(uint64_t(scene.meshes.size()));
  for (const Mesh& m : scene.meshes) {
    h.add(m.positions);
    h.add(m.normals);
    h.add(m.indices);
    h.add(m.primitive_ids);
    h.add(m.roles);
  }
  h.add(uint8_t(p.rho.kind));
  h.add(p.rho.value);
  h.add(p.picture_rho);
  add_optional(h, p.tau.has_value(), p.tau.value_or(0.0f));
  add_optional(h, p.fraction.has_value(), p.fraction.value_or(0.0));
  h.add(uint8_t(p.per_triangle));
  h.add(int32_t(p.grid));
  h.add(p.blend);
  h.add(uint8_t(p.normals));
  h.add(p.ambient.ka_min);
  h.add(p.ambient.d_min);
  h.add(p.ambient.exponent);
  h.add(uint8_t(p.d_min_auto));
  h.add(int32_t(p.optimize.smooth_iterations));
  h.add(p.optimize.keep_fraction);
  h.add(p.seed);
  return h.hex();
}

std::string serialize_foliage(const FoliageIllumination& r) {
  ByteWriter w;
  w.put(uint64_t(r.normals.size()));
  for (size_t m = 0; m < r.normals.size(); ++m) {
    w.put(r.normals[m]);
    w.put(r.ka[m]);
  }
  w.put(r.surface.positions);
  w.put(r.surface.normals);
  w.put(r.surface.indices);
  each_stat(r.stats, [&](const auto& v) {
    w.put(v);
    return true;
  });
  return w.take();
}

bool deserialize_foliage(const std::string& payload, const Scene& scene, FoliageIllumination& out) {
  ByteReader in(payload);
  uint64_t meshes = 0;
  if (!in.get(meshes) || meshes != scene.meshes.size()) return false;
  out.normals.assign(meshes, {});
  out.ka.assign(meshes, {});
  for (size_t m = 0; m < meshes; ++m) {
    const size_t vertices = scene.meshes[m].positions.size();
    if (!in.get(out.normals[m]) || !in.get(out.ka[m]) || out.normals[m].size() != vertices ||
        out.ka[m].size() != vertices || !finite_unit(out.normals[m]))
      return false;
    for (float k : out.ka[m])
      if (!(k >= 0.0f && k <= 1.0f)) return false;
  }
  SurfaceMesh& s = out.surface;
  if (!in.get(s.positions) || !in.get(s.normals) || !in.get(s.indices) ||
      !each_stat(out.stats, [&](auto& v) { return in.get(v); }) || !in.done())
    return false;
  if (s.normals.size() != s.positions.size() || s.indices.size() % 3 != 0 ||
      !finite_unit(s.normals))
    return false;
  for (uint32_t i : s.indices)
    if (i >= s.positions.size()) return false;
  for (const glm::vec3& q : s.positions)
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) return false;
  return true;
}

namespace {

// One flat scene (or plant) through the cache.
FoliageIllumination cached_one(const Scene& scene, const FoliageParams& params,
                               const ResultCache* cache, FoliageCacheUse& u) {
  validate_foliage_params(params);
  const std::string key = foliage_cache_key(scene, params);
  if (std::optional<std::string> bytes = cache->load(kKind, key)) {
    FoliageIllumination r;
    if (deserialize_foliage(*bytes, scene, r)) {
      r.stats.from_cache = true;
      u.hit = true;
      return r;
    }
  }
  FoliageIllumination r = compute_foliage_illumination(scene, params);
  if (!cache->store(kKind, key, serialize_foliage(r), &u.warning) && u.warning.empty())
    u.warning = "cannot write the cache";
  return r;
}

}  // namespace

FoliageIllumination cached_foliage_illumination(const Scene& scene, const FoliageParams& params,
                                                const ResultCache* cache, FoliageCacheUse* use) {
  FoliageCacheUse local;
  FoliageCacheUse& u = use ? *use : local;
  u = {};
  if (!cache) return compute_foliage_illumination(scene, params);
  validate_foliage_params(params);
  bool all_hit = true;
  FoliageIllumination r = foliage_per_plant(scene, [&](const Scene& plant) {
    FoliageCacheUse one;
    FoliageIllumination out = cached_one(plant, params, cache, one);
    all_hit = all_hit && one.hit;
    if (u.warning.empty()) u.warning = one.warning;
    return out;
  });
  u.hit = all_hit;
  return r;
}

}  // namespace sylva

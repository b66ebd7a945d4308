// A preprocessing cache file (core/cache/result_cache.h: header, then the Luft foliage result
// of npr/foliage_cache.h) as a second render finds it in the cache folder: ResultCache::load
// then deserialize_foliage against the scene it was made for (the 100-leaf sample tree,
// tests/fuzz/fuzz_scenes.h). Whatever is accepted must fit that scene: unit normals and ka in
// [0, 1] per vertex, a surface with finite positions and indices in range.
#include <cmath>
#include <filesystem>

#include "npr/foliage_cache.h"
#include "tests/fuzz/fuzz_scenes.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

using sylva::fuzz::fail;

void check(const sylva::Scene& scene, const sylva::FoliageIllumination& r) {
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    if (r.normals[m].size() != scene.meshes[m].positions.size()) fail("normal count");
    for (const glm::vec3& n : r.normals[m])
      if (!(std::abs(glm::length(n) - 1.0f) < 1e-3f)) fail("normal not finite and unit");
    for (float k : r.ka[m])
      if (!(k >= 0.0f && k <= 1.0f)) fail("ka outside [0, 1]");
  }
  for (uint32_t i : r.surface.indices)
    if (i >= r.surface.positions.size()) fail("surface index out of range");
  for (const glm::vec3& p : r.surface.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail("surface position not finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const sylva::fuzz::CacheScene& c = sylva::fuzz::cache_scene();
  const sylva::ResultCache cache(sylva::fuzz::scratch_dir());
  const std::string path = cache.path(c.kind, c.key);
  sylva::fuzz::write_input(data, size, std::filesystem::path(path).filename().string());
  if (std::optional<std::string> payload = cache.load(c.kind, c.key)) {
    sylva::FoliageIllumination r;
    if (sylva::deserialize_foliage(*payload, c.scene, r)) check(c.scene, r);
  }
  return 0;
}

// Caching the Luft preprocessing (DESIGN.md §3): the result of compute_foliage_illumination is
// stored under a content key made of the mesh data it reads (positions, normals, indices,
// roles, primitive ids), every parameter, and a hash of the preprocessing's own source code
// (generated at build time), so a second render of the same scene (or every frame of a
// turntable) reads it back instead of recomputing it, and a code change never serves a stale
// result.
#pragma once

#include <string>

#include "core/cache/result_cache.h"
#include "npr/foliage_illumination.h"

namespace sylva {

// 32 hex digits.
std::string foliage_cache_key(const Scene& scene, const FoliageParams& params);

std::string serialize_foliage(const FoliageIllumination& result);
// False when the payload is damaged or does not fit the scene (mesh and vertex counts),
// or holds a non-finite or out-of-range value; `out` is then unspecified.
bool deserialize_foliage(const std::string& payload, const Scene& scene, FoliageIllumination& out);

struct FoliageCacheUse {
  bool hit = false;
  std::string warning;  // why the result could not be stored, if it could not
};

// compute_foliage_illumination through `cache` (nullptr: always compute). A hit sets
// stats.from_cache; its timings are those of the run that computed it. An instanced scene
// has an entry per plant (keyed by the plant alone, so the same plant in another scene hits
// it); `use->hit` then says every plant was read from the cache.
FoliageIllumination cached_foliage_illumination(const Scene& scene, const FoliageParams& params,
                                                const ResultCache* cache,
                                                FoliageCacheUse* use = nullptr);

}  // namespace sylva

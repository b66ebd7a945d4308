// Hegeman et al.'s approximate ambient occlusion for a scene of many plants
// (core/gl/ao_shading.h's plant_shells and crowns): each plant with foliage is fitted alone in
// its own space exactly as scene_ao_shading fits a flat scene (its shells, and for
// ao.alpha_rho = auto its own ray tracer), so every instance's crown darkens its own leaves as
// the plant alone does; each instance's crown sphere (its plant's foliage bounding sphere
// moved by the instance's transform, the radius times the transform's largest axis scale)
// occludes the wood, ground and grass near it (Eq. 7-8, summed over the crowns); grass
// (Eq. 9) and a flat ground come from the whole scene in world space.
#pragma once

#include <cstdint>

#include "core/gl/ao_shading.h"
#include "core/scene/scene.h"
#include "npr/ao_pass.h"

namespace sylva {

// `scene` is instanced. Throws InputError("ao.model", ...) when no plant has foliage or grass.
AoShading plants_ao_shading(const Scene& scene, const AoSettings& settings, uint64_t seed);

}  // namespace sylva

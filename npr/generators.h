// Generator points of the implicit surface (Luft et al. §3.1): one per foliage primitive
// (a leaf = connected component of foliage triangles, or each foliage triangle) at its
// centre of mass (area-weighted centroid), optionally a seeded random fraction of them.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/scene/scene.h"

namespace sylva {

struct GeneratorOptions {
  double fraction = 1.0;      // share of primitives kept, (0, 1]; at least one generator is kept
  bool per_triangle = false;  // one generator per foliage triangle instead of per leaf
  uint64_t seed = 1;          // which primitives the fraction keeps
};

// Needs roles and primitive ids (finish_scene). Generators come out in primitive-id order
// (triangle order with per_triangle), so the same scene and options give the same points.
// Throws InputError("fraction", ...) outside (0, 1]. Empty when the scene has no foliage.
std::vector<glm::vec3> make_generators(const Scene& scene, const GeneratorOptions& options);

}  // namespace sylva

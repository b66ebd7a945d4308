// The ambient visibility (AO) the raster pass evaluates per fragment (core/gl/rasterizer.h):
// plain uniforms, so the npr/ code that fits them (npr/ao_uniforms.h) needs no scene types.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace sylva {

// Ambient visibility (AO) the raster pass evaluates per fragment: written to the AO target and
// multiplying the colour's ambient term (ambient * ka * AO; with Ka the AO *is* ka, applied
// once). None: AO target 1 on geometry and the colour exactly as without AO.
struct AoShading {
  enum class Model : uint8_t { None = 0, Constant = 1, Ka = 2, Shells = 3 };
  Model model = Model::None;
  float constant = 1.0f;  // Constant: the visibility, [0, 1]
  // Shells: Hegeman et al. Eq. 4-6 (npr/hegeman_ao.h) in the unit ball of each shell. Shell i
  // maps a world point x to u = inverse[i] * (x - centre[i]) and a normal n to
  // transpose[i] * n (L^T for L = axes * diag(radii)); volume_scale[i] = |det L| (0 = a
  // shell without volume: visibility 1). A fragment uses the shell whose anchor is nearest
  // (lowest index on ties). At most kMaxAoShells.
  float alpha_rho = 0.0f;  // per scene unit cubed, >= 0
  std::vector<glm::vec3> centres, anchors;
  std::vector<glm::mat3> inverse, transpose;
  std::vector<float> volume_scale;
};
inline constexpr int kMaxAoShells = 64;

}  // namespace sylva

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
  // 0 shells: a scene without foliage (e.g. a grass patch), only the terms below apply.
  float alpha_rho = 0.0f;  // per scene unit cubed, >= 0
  std::vector<glm::vec3> centres, anchors;
  std::vector<glm::mat3> inverse, transpose;
  std::vector<float> volume_scale;
  // Shells, fragments that are not foliage (wood, ground, other, grass): Hegeman et al.
  // Eq. 7-8, V = 1 - A / (2 pi) with A the solid angle of the crown's sphere above the
  // fragment's tangent plane, clamped inside the sphere, as npr/hegeman_ao.h's
  // object_visibility with horizon clipping. crown_radius <= 0: no crown, V = 1.
  glm::vec3 crown_centre{0.0f};
  float crown_radius = 0.0f;  // scene units, finite
  // true: the exact solid angle 2 pi (1 - sqrt(1 - (r/d)^2)); false: the paper's pi (r/d)^2.
  bool exact_solid_angle = true;
  // Shells, grass fragments (Role::Grass): Eq. 9 times the crown's occlusion, P_z = y -
  // grass_ground clamped to [0, grass_height] (+Y up). grass_height <= 0: no grass term.
  float grass_ground = 0.0f;  // y of the grass roots, scene units, finite
  float grass_height = 0.0f;  // h, the grass field's height, scene units, finite
  // Shells, wood and other fragments (not foliage, ground or grass) above a flat ground: the
  // plane also hides theta / pi of their hemisphere (npr/hegeman_ao.h's
  // ground_plane_occlusion, +Y up), subtracted from Eq. 8's V. ground_plane false: no plane.
  bool ground_plane = false;
  float ground_y = 0.0f;  // the plane's height, scene units, finite

  // A scene of many plants (Shells; the shell and crown fields above are then unused, the
  // grass and ground ones still apply): each plant's own shells in its own space, which a
  // foliage fragment evaluates in its instance's plant space (so every instance darkens as its
  // plant alone does), and per instance its crown sphere in world space; a fragment that is
  // not foliage is occluded by every crown within kAoCrownReach radii of it, their solid
  // angles added (Eq. 7-8 summed over the crowns). Empty: a flat scene.
  struct PlantShells {
    float alpha_rho = 0.0f;  // per plant-space unit cubed, >= 0
    std::vector<glm::vec3> centres, anchors;
    std::vector<glm::mat3> inverse, transpose;
    std::vector<float> volume_scale;
  };
  std::vector<PlantShells> plant_shells;  // per plant (no shells: a plant without foliage)
  std::vector<glm::vec4> crowns;          // per instance: world centre, radius (<= 0: none)
};
inline constexpr int kMaxAoShells = 64;
// A crown farther than this many of its radii from a fragment is left out of the sum: its
// solid angle is then below 1 / 128 of the hemisphere.
inline constexpr float kAoCrownReach = 8.0f;

}  // namespace sylva

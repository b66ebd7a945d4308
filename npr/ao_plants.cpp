#include "npr/ao_plants.h"

#include <algorithm>

#include "core/error.h"
#include "core/scene/instances.h"

namespace sylva {

namespace {

// World bounds of the triangles with `role` (meshes without roles have none).
Bounds role_bounds(const Scene& scene, Role role) {
  for (const Mesh& m : scene.meshes)
    if (m.roles.size() != m.triangle_count()) return {};
  return scene.bounds(role);
}

// A flat ground (Role::Ground triangles all at one height) and a grass field, as
// scene_ao_shading reads them, in world space.
void ground_and_grass(const Scene& scene, AoShading& ao) {
  const Bounds ground = role_bounds(scene, Role::Ground), grass = role_bounds(scene, Role::Grass);
  const bool flat =
      !ground.empty() && ground.max.y - ground.min.y <= 1e-6f * std::max(1.0f, ground.diagonal());
  ao.ground_plane = flat;
  ao.ground_y = flat ? ground.min.y : 0.0f;
  if (grass.empty()) return;
  ao.grass_ground = grass.min.y;
  ao.grass_height = grass.max.y - grass.min.y;
}

AoShading::PlantShells plant_shells(const AoShading& fitted) {
  AoShading::PlantShells p;
  p.alpha_rho = fitted.alpha_rho;
  p.centres = fitted.centres;
  p.anchors = fitted.anchors;
  p.inverse = fitted.inverse;
  p.transpose = fitted.transpose;
  p.volume_scale = fitted.volume_scale;
  return p;
}

}  // namespace

AoShading plants_ao_shading(const Scene& scene, const AoSettings& settings, uint64_t seed) {
  SYLVA_CHECK(scene.instanced(), "plants_ao_shading: a scene of many plants");
  AoShading ao;
  ao.model = ao_model_of(settings.model);
  ao.constant = settings.constant;
  ao.exact_solid_angle = settings.solid_angle == SolidAngleModel::Exact;
  std::vector<glm::vec4> crowns(scene.plants.size(), glm::vec4(0.0f));  // plant space
  bool any = false;
  for (size_t p = 0; p < scene.plants.size(); ++p) {
    const Scene plant = plant_scene(scene, p);
    const bool foliage = !role_bounds(plant, Role::Foliage).empty();
    const bool grass = !role_bounds(plant, Role::Grass).empty();
    any = any || foliage || grass;
    if (!foliage) {
      ao.plant_shells.emplace_back();
      continue;
    }
    const AoShading fitted = scene_ao_shading(plant, settings, seed);
    ao.plant_shells.push_back(plant_shells(fitted));
    crowns[p] = glm::vec4(fitted.crown_centre, fitted.crown_radius);
  }
  if (!any) throw InputError("ao.model", "'" + ao_model_name(settings.model) + "' needs foliage");
  for (const Instance& inst : scene.instances) {
    const glm::vec4 c = crowns[inst.plant];
    float scale = 0.0f;
    for (int k = 0; k < 3; ++k)
      scale = std::max(scale, glm::length(glm::vec3(inst.transform[k])));
    ao.crowns.emplace_back(glm::vec3(inst.transform * glm::vec4(glm::vec3(c), 1.0f)),
                           c.w > 0.0f ? c.w * scale : 0.0f);
  }
  ground_and_grass(scene, ao);
  return ao;
}

}  // namespace sylva

#include "core/scene/ground_plane.h"

#include <algorithm>

namespace sylva {

void add_ground_plane(Scene& scene, const glm::vec4& color) {
  const Bounds b = scene.bounds();
  const Sphere s = scene.framing_sphere();
  if (b.empty() || s.empty()) return;
  const float half = s.radius > 0.0f ? kGroundHalfSizeInRadii * s.radius : 1.0f;
  const float y = b.min.y;
  const float x0 = s.centre.x - half, x1 = s.centre.x + half;
  const float z0 = s.centre.z - half, z1 = s.centre.z + half;

  Material material;
  material.name = "sylva-ground";
  material.base_color = glm::clamp(color, glm::vec4(0.0f), glm::vec4(1.0f));
  material.double_sided = true;
  scene.materials.push_back(material);

  uint32_t cluster = scene.branch_cluster_id();
  if (cluster == 0) cluster = std::max<uint32_t>(1, scene.max_cluster_id() + 1);
  const uint32_t primitive = scene.max_primitive_id() + 1;

  Mesh m;
  m.name = "sylva-ground";
  m.material = int(scene.materials.size()) - 1;
  // Counter-clockwise seen from above (+Y), so the front face looks up.
  m.positions = {{x0, y, z0}, {x0, y, z1}, {x1, y, z1}, {x1, y, z0}};
  m.normals.assign(4, glm::vec3(0.0f, 1.0f, 0.0f));
  m.uvs = {{0.0f, 0.0f}, {0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.primitive_ids.assign(2, primitive);
  m.cluster_ids.assign(2, cluster);
  m.roles.assign(2, Role::Ground);
  scene.meshes.push_back(std::move(m));
}

}  // namespace sylva

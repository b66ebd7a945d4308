#include "core/scene/ground_plane.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva {

void add_ground_plane(Scene& scene, const glm::vec4& color) {
  const Bounds b = scene.bounds();
  const Sphere s = scene.framing_sphere();
  if (b.empty() || s.empty()) return;
  const float radius = s.radius > 0.0f ? kGroundRadiusInRadii * s.radius : 1.0f;
  const float y = b.min.y;

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
  // The centre, then the rim; each triangle (centre, rim i + 1, rim i) is counter-clockwise
  // seen from above (+Y), so the front face looks up.
  const glm::vec3 centre(s.centre.x, y, s.centre.z);
  m.positions.push_back(centre);
  for (int i = 0; i < kGroundSegments; ++i) {
    const double a = 2.0 * std::numbers::pi * i / kGroundSegments;
    m.positions.push_back(
        centre + glm::vec3(float(radius * std::cos(a)), 0.0f, float(radius * std::sin(a))));
  }
  m.normals.assign(m.positions.size(), glm::vec3(0.0f, 1.0f, 0.0f));
  for (const glm::vec3& p : m.positions)
    m.uvs.push_back(glm::vec2(0.5f + 0.5f * (p.x - centre.x) / radius,
                              0.5f + 0.5f * (p.z - centre.z) / radius));
  for (uint32_t i = 0; i < uint32_t(kGroundSegments); ++i)
    m.indices.insert(m.indices.end(), {0u, 1u + (i + 1) % uint32_t(kGroundSegments), 1u + i});
  const size_t triangles = size_t(kGroundSegments);
  m.primitive_ids.assign(triangles, primitive);
  m.cluster_ids.assign(triangles, cluster);
  m.roles.assign(triangles, Role::Ground);
  if (scene.instanced()) {
    // A plant of its own, placed once where it is; its cluster id in the id buffer is the
    // one of every instance's non-foliage (core/scene/instances.h).
    m.primitive_ids.assign(triangles, 1u);
    scene.plants.push_back({"sylva-ground", {uint32_t(scene.meshes.size())}, {}});
    scene.instances.push_back({uint32_t(scene.plants.size() - 1), glm::mat4(1.0f), "sylva-ground"});
  }
  scene.meshes.push_back(std::move(m));
}

}  // namespace sylva

#include "core/gl/depth_range.h"

#include <algorithm>

namespace sylva {

void fit_camera_depth(Camera& camera, const Scene& scene) {
  bool ground = false;  // meshes without roles have no ground
  for (const Mesh& m : scene.meshes)
    for (size_t t = 0; t < m.triangle_count() && t < m.roles.size() && !ground; ++t)
      ground = m.roles[t] == Role::Ground;
  const Bounds b = scene.bounds();
  if (b.empty() || !ground) return;
  const float dist = glm::length(camera.eye - b.center());
  const float far_plane = std::max(camera.far_plane, dist + 0.5f * b.diagonal() * 1.01f);
  const float near_plane =
      std::min(camera.near_plane, std::max(dist - 0.5f * b.diagonal() * 1.01f, far_plane * 1e-3f));
  if (far_plane == camera.far_plane && near_plane == camera.near_plane) return;
  const float n = near_plane, f = far_plane;
  // glm's right-handed, -1..1 depth projections (glm::perspective, glm::ortho).
  if (camera.ortho) {
    camera.proj[2][2] = -2.0f / (f - n);
    camera.proj[3][2] = -(f + n) / (f - n);
  } else {
    camera.proj[2][2] = -(f + n) / (f - n);
    camera.proj[3][2] = -2.0f * f * n / (f - n);
  }
  camera.near_plane = n;
  camera.far_plane = f;
}

}  // namespace sylva

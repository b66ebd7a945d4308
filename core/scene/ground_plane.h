// A ground plane under a scene (`--ground`): one double-sided quad (two triangles) with
// Role::Ground, so the crown's occlusion (Hegeman et al. Eq. 7-8) has something to fall on.
// Y is up (glTF). The scene's framing leaves the ground out (Scene::framing_sphere), so adding
// it does not change the camera.
#pragma once

#include <glm/glm.hpp>

#include "core/scene/scene.h"

namespace sylva {

// Half the side of the square ground, in multiples of the framing radius (the radius of
// Scene::framing_sphere before the ground is added): 4 R, so the ground reaches past the
// frame's edges for the default camera.
inline constexpr float kGroundHalfSizeInRadii = 4.0f;

// Appends a mesh "sylva-ground" with its own material "sylva-ground" (base colour `color`,
// linear RGBA, each component in [0, 1]; opaque, double-sided): a square centred under the
// framing sphere's centre, in the plane y = the lowest point of the scene (min y of all
// vertices used by triangles), side 2 * kGroundHalfSizeInRadii * R. Normals +Y, uvs over
// [0, 1]^2, primitive id max_primitive_id() + 1, cluster id the scene's branch cluster
// (branch_cluster_id(), or max_cluster_id() + 1 when there is none; at least 1).
// An empty scene (nothing to stand on) gets no ground. A radius of 0 (a single point) gives a
// 2 x 2 unit ground.
void add_ground_plane(Scene& scene, const glm::vec4& color);

}  // namespace sylva

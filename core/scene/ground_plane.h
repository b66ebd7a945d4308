// A ground plane under a scene (`--ground`): one double-sided disc with Role::Ground, so the
// crown's occlusion (Hegeman et al. Eq. 7-8) has something to fall on. Y is up (glTF). The
// scene's framing leaves the ground out (Scene::framing_sphere), so adding it does not change
// the camera.
#pragma once

#include <glm/glm.hpp>

#include "core/scene/scene.h"

namespace sylva {

// The disc's radius in multiples of the framing radius (the radius of Scene::framing_sphere
// before the ground is added): 30 R. Far enough that, for the default camera at low
// elevation, its edge lies within a few degrees of the horizon and reads as one (at 4 R, a
// square's far edges and corner showed behind the plant and drew as lines in ink).
inline constexpr float kGroundRadiusInRadii = 30.0f;
// Sides of the polygon the disc is made of (a fan of as many triangles around its centre):
// each side bows in by 1 - cos(pi / 64), 0.12 % of the radius.
inline constexpr int kGroundSegments = 64;

// Appends a mesh "sylva-ground" with its own material "sylva-ground" (base colour `color`,
// linear RGBA, each component in [0, 1]; opaque, double-sided): a disc centred under the
// framing sphere's centre, in the plane y = the lowest point of the scene (min y of all
// vertices used by triangles), radius kGroundRadiusInRadii * R, kGroundSegments triangles
// fanned from its centre. Normals +Y, uvs over [0, 1]^2 (the disc's bounding square),
// primitive id max_primitive_id() + 1, cluster id the scene's branch cluster
// (branch_cluster_id(), or max_cluster_id() + 1 when there is none; at least 1). In an
// instanced scene the disc is a plant of its own ("sylva-ground", primitive id 1) with one
// instance at the identity, drawn last.
// An empty scene (nothing to stand on) gets no ground. A radius of 0 (a single point) gives a
// ground of radius 1 unit.
void add_ground_plane(Scene& scene, const glm::vec4& color);

}  // namespace sylva

// Orbit camera around the centre of the scene bounds. Convention: +Y up (glTF); azimuth 0,
// elevation 0 puts the camera on the +Z side looking toward -Z; azimuth turns
// counter-clockwise about +Y seen from above (azimuth 90 = camera on +X); elevation raises
// the camera toward +Y. Distance 0 = automatic framing (the bounding sphere fits the view).
#pragma once

#include <glm/glm.hpp>

#include "core/scene/scene.h"

namespace sylva {

struct OrbitParams {
  float azimuth_deg = 30.0f;    // degrees, any value (wrapped)
  float elevation_deg = 15.0f;  // degrees, [-89, 89]
  float distance = 0.0f;        // scene units from the bounds centre; 0 = auto; >= 0
  float fov_deg = 35.0f;        // vertical field of view, degrees, [1, 150]
  bool ortho = false;           // orthographic: the view height fits the bounding sphere
};

struct Camera {
  glm::mat4 view{1.0f};
  glm::mat4 proj{1.0f};
  glm::vec3 eye{0.0f};
  float near_plane = 0.1f;
  float far_plane = 100.0f;
  bool ortho = false;
  int width = 0;
  int height = 0;
};

// Throws InputError naming the option (--elevation, --distance, --fov) when out of range.
// The camera orbits the sphere's centre; automatic distance (and the orthographic extent) fit
// the sphere with a 5% margin. The Bounds form frames the box's circumscribed sphere.
Camera make_orbit_camera(const Sphere& sphere, const OrbitParams& params, int width, int height);
Camera make_orbit_camera(const Bounds& bounds, const OrbitParams& params, int width, int height);

// A camera stored in the file (Scene::cameras) for a width x height image: its view is the
// inverse of its node's rigid transform; perspective keeps the vertical field of view and
// orthographic the half height ymag, the width following the image's aspect ratio (the file's
// aspect ratio is not used); near and far are the file's znear and zfar, and an infinite far
// (zfar 0) becomes the far side of `sphere` (the scene's framing sphere) seen from the eye,
// at least 2 x znear. Throws InputError("--size", ...) for a size outside [1, 16384].
Camera make_file_camera(const SceneCamera& camera, const Sphere& sphere, int width, int height);

// A square camera seeing the whole sphere from a light, for shadow maps: orthographic along
// `toward_light` (world direction from the scene toward a directional light, any length
// > 0), or, when `point` is set, perspective from the world position `toward_light` aimed at
// the centre (a light inside the sphere gets a 150 degree field of view). Depth hugs the
// sphere. size in [1, 16384] pixels. For a directional light, a non-empty `casters` sphere
// (the whole scene, when `sphere` holds only what the picture shows) moves the near plane
// toward the light until every caster in it is in front of the camera, so what stands
// outside `sphere` still casts its shadow into it.
Camera make_light_camera(const Sphere& sphere, const glm::vec3& toward_light, bool point, int size,
                         const Sphere& casters = {});

}  // namespace sylva

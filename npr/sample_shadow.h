// How much of the key light reaches a point inside a plant (issue "Pen-and-ink that depicts the
// tree": tone zones from the key light's shadow map): a shadow map splatted from the scene's
// surface samples (npr/surface_samples.h) rather than rasterised, so it costs a few
// milliseconds and moves with the scene. Each texel keeps the nearest sample's depth along the
// light; a point that far behind the first surface the light meets receives
// exp(-behind / reach) of it, as light is absorbed going through a crown (the soft, blurred
// depth test of DESIGN.md §6: no point switches from lit to dark as the view turns, and deep
// inside the crown is darker than just under its lit skin).
#pragma once

#include <glm/glm.hpp>
#include <opencv2/core.hpp>

#include "core/gl/camera.h"
#include "npr/surface_samples.h"

namespace sylva {

struct SampleShadow {
  Camera light;     // the light's camera (make_light_camera)
  cv::Mat depth;    // CV_32FC1 the nearest sample's depth along the light, +inf where none
  float bias = 0;   // scene units: a surface does not shadow itself
  float reach = 0;  // scene units over which the light falls to 1/e behind the first surface
  bool empty() const { return depth.empty(); }
};

// The shadow map of `samples` from a light toward `toward_light` (a direction, or a position
// when `point`), covering `sphere`, `size` texels square (>= 8); reach is `reach` x the
// sphere's radius.
SampleShadow sample_shadow_map(const SurfaceSamples& samples, const Sphere& sphere,
                               const glm::vec3& toward_light, bool point, int size, float reach);

// The share of the light reaching world point `p`, in (0, 1]; 1 with an empty map.
float light_reaching(const SampleShadow& map, const glm::vec3& p);

}  // namespace sylva

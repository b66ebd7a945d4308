#include "core/gl/lights.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace sylva {

Lighting Lighting::three_point() {
  // View space: +X right, +Y up, +Z toward the viewer. Intensities sum (with ambient) to
  // about 1.45 at the brightest so lit foliage saturates only where key and fill overlap.
  Lighting l;
  l.ambient = 0.35f;
  Light key;  // upper left, in front of the subject
  key.vector = glm::normalize(glm::vec3(-0.6f, 0.7f, 0.8f));
  key.color = glm::vec3(0.8f);
  key.specular = 0.15f;
  key.shininess = 32.0f;
  Light fill;  // right, slightly low, no highlight
  fill.vector = glm::normalize(glm::vec3(1.0f, 0.1f, 0.4f));
  fill.color = glm::vec3(0.3f);
  Light rim;  // behind and above: lights the crown's silhouette facing up and away
  rim.vector = glm::normalize(glm::vec3(0.0f, 0.8f, -1.0f));
  rim.color = glm::vec3(0.25f);
  l.lights = {key, fill, rim};
  return l;
}

void validate_lighting(const Lighting& lighting) {
  if (!(lighting.ambient >= 0.0f && lighting.ambient <= 1.0f)) {
    throw InputError("lights", "ambient must be in [0, 1]");
  }
  if (lighting.lights.size() > static_cast<size_t>(kMaxLights)) {
    throw InputError("lights", "at most " + std::to_string(kMaxLights) + " lights, got " +
                                   std::to_string(lighting.lights.size()));
  }
  for (size_t i = 0; i < lighting.lights.size(); ++i) {
    const Light& light = lighting.lights[i];
    const std::string which = "light " + std::to_string(i) + ": ";
    for (int c = 0; c < 3; ++c) {
      if (!(std::isfinite(light.color[c]) && light.color[c] >= 0.0f)) {
        throw InputError("lights", which + "colour must be finite and >= 0");
      }
      if (!std::isfinite(light.vector[c])) {
        throw InputError("lights", which + "vector must be finite");
      }
    }
    if (!(light.specular >= 0.0f && light.specular <= 1.0f)) {
      throw InputError("lights", which + "specular must be in [0, 1]");
    }
    if (!(light.shininess >= 1.0f && light.shininess <= 1024.0f)) {
      throw InputError("lights", which + "shininess must be in [1, 1024]");
    }
    if (light.type == Light::Type::Directional && glm::length(light.vector) < 1e-12f) {
      throw InputError("lights", which + "a directional light needs a non-zero direction");
    }
  }
}

glm::vec3 light_in_view(const Light& light, const glm::mat4& view) {
  if (light.type == Light::Type::Point)
    return light.camera_fixed ? light.vector : glm::vec3(view * glm::vec4(light.vector, 1.0f));
  return glm::normalize(light.camera_fixed ? light.vector : glm::mat3(view) * light.vector);
}

}  // namespace sylva

// Lights for local illumination (Luft et al. Eq. 1): an ambient intensity plus up to 8
// directional or point lights, each fixed to the scene (world space) or to the camera
// (view space).
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace sylva {

struct Light {
  enum class Type { Directional, Point } type = Type::Directional;
  // Directional: direction the light travels *from* (toward the light), normalised on use.
  // Point: position; no distance attenuation (NPR lighting wants the same tone near and far).
  // World space, or view space when camera_fixed.
  glm::vec3 vector{0.0f, 1.0f, 0.0f};
  glm::vec3 color{1.0f};    // linear RGB intensity, >= 0
  float specular = 0.0f;    // specular weight, [0, 1]
  float shininess = 32.0f;  // Phong exponent, [1, 1024]
  bool camera_fixed = true;
};

inline constexpr int kMaxLights = 8;

struct Lighting {
  float ambient = 0.35f;      // ambient intensity, [0, 1], multiplied by ka
  std::vector<Light> lights;  // at most 8

  // Key light from the upper left front, fill from the right, rim from behind; all
  // camera-fixed so a turntable keeps its lighting.
  static Lighting three_point();
};

// Throws InputError("lights", ...) for more than kMaxLights lights, a negative or non-finite
// intensity, specular outside [0, 1], shininess outside [1, 1024], ambient outside [0, 1]
// or a zero-length directional vector.
void validate_lighting(const Lighting& lighting);

// The light's vector in view space (`view` = world -> view): a directional light's unit
// direction toward the light, or a point light's position.
glm::vec3 light_in_view(const Light& light, const glm::mat4& view);

}  // namespace sylva

// The CPU side of the AO shader tests: Hegeman shells fitted to points, their raster uniforms
// and npr/hegeman_ao.h's visibility, behind plain types.
#pragma once

#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "core/gl/ao_shading.h"

namespace sylva::test {

struct CpuAo {
  AoShading uniforms;
  std::function<float(const glm::vec3& x, const glm::vec3& n)> visibility;  // hegeman_visibility
  // object_visibility of the crown sphere (exact solid angle, horizon clipped): what
  // non-foliage fragments get.
  std::function<float(const glm::vec3& x, const glm::vec3& n)> object;
};

// k shells (spheres or ellipsoids) fitted to `points` (seed 1); alpha_rho makes Eq. 6's
// exponent `exponent_at_centre` at the centre of the first shell. The crown sphere of
// Eq. 7-8 is the points' bounding sphere.
CpuAo make_cpu_ao(const std::vector<glm::vec3>& points, bool ellipsoid, int k,
                  float exponent_at_centre);

}  // namespace sylva::test

#include "tests/styles/ao_cpu.h"

#include <memory>
#include <numbers>

#include "npr/ao_shells.h"
#include "npr/ao_uniforms.h"
#include "npr/hegeman_ao.h"

namespace sylva::test {

CpuAo make_cpu_ao(const std::vector<glm::vec3>& points, bool ellipsoid, int k,
                  float exponent_at_centre) {
  ShellOptions options;
  options.kind = ellipsoid ? ShellKind::Ellipsoid : ShellKind::Sphere;
  options.shells = k;
  auto shells = std::make_shared<const Shells>(fit_shells(points, options));
  const Ellipsoid& e = shells->shells[0];
  const float volume = 4.0f / 3.0f * std::numbers::pi_v<float> * e.radii.x * e.radii.y * e.radii.z;
  const float alpha_rho = exponent_at_centre / volume;
  CpuAo out;
  const Sphere crown = fit_bounding_sphere(points);
  out.uniforms = ao_shading(*shells, alpha_rho, crown);
  out.object = [crown](const glm::vec3& x, const glm::vec3& n) {
    return object_visibility(crown, x, n);
  };
  out.visibility = [shells, alpha_rho](const glm::vec3& x, const glm::vec3& n) {
    return hegeman_visibility(*shells, x, n, alpha_rho);
  };
  return out;
}

}  // namespace sylva::test

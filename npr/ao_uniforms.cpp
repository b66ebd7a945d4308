#include "npr/ao_uniforms.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/random.h"
#include "npr/ao_fit.h"
#include "npr/ao_shells.h"
#include "npr/hegeman_ao.h"

namespace sylva {

namespace {

constexpr size_t kFitSamples = 256;

float fitted_alpha_rho(const Shells& shells, const AoShellFit& fit) {
  const size_t n = std::min(fit.sample_points.size(), fit.sample_normals.size());
  if (n == 0 || !fit.trace) throw InputError("ao.alpha_rho", "auto needs foliage in the scene");
  uint64_t state = fit.seed ^ 0xA0A0A0A0A0A0A0A0ull;
  std::vector<glm::vec3> p, nr;
  for (size_t i = 0; i < std::min(n, kFitSamples); ++i) {
    const size_t j = n <= kFitSamples ? i : size_t(splitmix64(state) % n);
    const glm::vec3 normal = fit.sample_normals[j];
    p.push_back(fit.sample_points[j]);
    nr.push_back(normal);
    p.push_back(fit.sample_points[j]);
    nr.push_back(-normal);
  }
  const std::vector<float> v = fit.trace(p, nr);
  SYLVA_CHECK(v.size() == p.size(), "AO tracer: one visibility per point");
  // Each face weighted by its visibility: a face's chance of being seen by a camera in a
  // uniformly random direction outside the crown is proportional to it, so the fit favours
  // the outer leaves a render shows over buried ones (unweighted, alpha_rho came out about
  // twice what suits the visible leaves and the model too dark). All faces fully occluded:
  // equal weights.
  double total = 0.0;
  for (float x : v)
    total += double(x);
  std::vector<AlphaRhoSample> samples;
  for (size_t i = 0; i < p.size(); ++i) {
    const CapGeometry g = ellipsoid_cap(shells.shells[shells.nearest(p[i])], p[i], nr[i]);
    samples.push_back({g.weighted_volume, double(v[i]), total > 0.0 ? double(v[i]) : 1.0});
  }
  return float(fit_alpha_rho(samples).alpha_rho);
}

}  // namespace

AoShading ao_shading(const Shells& shells, float alpha_rho, const Sphere& crown) {
  SYLVA_CHECK(!shells.shells.empty() && shells.shells.size() <= size_t(kMaxAoShells) &&
                  shells.anchors.size() == shells.shells.size(),
              "ao_shading: 1 to 64 shells with one anchor each");
  AoShading ao;
  ao.model = AoShading::Model::Shells;
  ao.alpha_rho = alpha_rho;
  for (size_t i = 0; i < shells.shells.size(); ++i) {
    const Ellipsoid& e = shells.shells[i];
    const glm::dmat3 l(glm::dvec3(e.axes[0]) * double(e.radii.x),
                       glm::dvec3(e.axes[1]) * double(e.radii.y),
                       glm::dvec3(e.axes[2]) * double(e.radii.z));
    const double det = std::abs(glm::determinant(l));
    const bool solid =
        e.radii.x > 0.0f && e.radii.y > 0.0f && e.radii.z > 0.0f && det > 0.0 && std::isfinite(det);
    ao.centres.push_back(e.centre);
    ao.anchors.push_back(shells.anchors[i]);
    ao.inverse.push_back(solid ? glm::mat3(glm::inverse(l)) : glm::mat3(1.0f));
    ao.transpose.push_back(solid ? glm::mat3(glm::transpose(l)) : glm::mat3(1.0f));
    ao.volume_scale.push_back(solid ? float(det) : 0.0f);
  }
  if (!crown.empty() && std::isfinite(crown.radius)) {
    ao.crown_centre = crown.centre;
    ao.crown_radius = crown.radius;
  }
  return ao;
}

AoShading fit_ao_shading(const std::vector<glm::vec3>& foliage, const AoShellFit& fit) {
  ShellOptions options;
  options.shells = fit.shells;
  options.kind = fit.ellipsoid ? ShellKind::Ellipsoid : ShellKind::Sphere;
  options.seed = fit.seed;
  const Shells shells = fit_shells(foliage, options);
  const float alpha_rho = fit.alpha_rho >= 0.0f ? fit.alpha_rho : fitted_alpha_rho(shells, fit);
  return ao_shading(shells, alpha_rho, fit_bounding_sphere(foliage));
}

}  // namespace sylva

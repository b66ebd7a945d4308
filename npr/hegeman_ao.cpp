#include "npr/hegeman_ao.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/error.h"

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;

bool finite3(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Unit vector along v, or false when v has no direction (zero length or non-finite).
bool direction(const glm::dvec3& v, glm::dvec3& out) {
  if (!finite3(v)) return false;
  // Scale first: components as small as float denormals square to 0 otherwise.
  const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(m > 0.0)) return false;
  const glm::dvec3 s = v / m;
  out = s / std::sqrt(glm::dot(s, s));
  return true;
}

// The cap cut from the ball (c, R) by the plane through x with normal n (n may be zero).
CapGeometry ball_cap(const glm::dvec3& c, double radius, const glm::dvec3& x, const glm::dvec3& n,
                     double volume_scale) {
  CapGeometry g;
  g.radius = radius;
  if (!(radius > 0.0) || !std::isfinite(radius) || !finite3(c) || !finite3(x)) return g;
  const glm::dvec3 to_centre = c - x;
  glm::dvec3 dir;
  double t = 0.0;  // signed distance of the centre in front of the plane
  glm::dvec3 in_plane(0.0);
  if (direction(n, dir)) {
    t = glm::dot(dir, to_centre);
    in_plane = to_centre - t * dir;
  } else if (direction(-to_centre, dir)) {
    // Zero normal: face away from the centre. The centre then lies on the normal's line, so
    // d = 0 and the centre is |x - c| behind the plane.
    t = -glm::length(to_centre);
  }
  g.h = std::clamp(radius + t, 0.0, 2.0 * radius);
  g.d = glm::length(in_plane);
  g.volume = cap_volume(g.h, radius) * volume_scale;
  g.f = off_centre_factor(g.h, g.d);
  g.weighted_volume = g.f * g.volume;
  if (!std::isfinite(g.weighted_volume)) g.weighted_volume = 0.0, g.volume = 0.0;
  return g;
}

float visibility_from(const CapGeometry& g, float alpha_rho) {
  // Negated test: NaN alpha_rho counts as 0.
  if (!(alpha_rho > 0.0f)) return 1.0f;
  const double exponent = double(alpha_rho) * g.weighted_volume;  // < 1e155 for float inputs
  if (!(exponent > 0.0)) return 1.0f;
  return std::clamp(float(std::exp(-exponent)), 0.0f, 1.0f);
}

std::string format_value(float v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.9g", double(v));
  return buf;
}

}  // namespace

void validate_alpha_rho(float alpha_rho) {
  if (!(std::isfinite(alpha_rho) && alpha_rho >= 0.0f))
    throw InputError("alpha-rho", "must be finite and >= 0, got " + format_value(alpha_rho));
}

double cap_volume(double h, double radius) {
  if (!(radius > 0.0) || std::isnan(h)) return 0.0;
  const double hc = std::clamp(h, 0.0, 2.0 * radius);
  return kPi * hc * hc * (3.0 * radius - hc) / 3.0;  // Hegeman et al. Eq. 4
}

double off_centre_factor(double h, double d) {
  const double h2 = h * h, d2 = d * d;
  if (!(h2 + d2 > 0.0)) return 1.0;  // h = d = 0 (and NaN): the d = 0 limit
  if (!std::isfinite(h2 + d2)) {     // rescale huge values instead of dividing inf by inf
    const double m = std::max(std::abs(h), std::abs(d));
    return off_centre_factor(h / m, d / m);
  }
  return std::clamp(h2 / (h2 + d2), 0.0, 1.0);  // Hegeman et al. Eq. 5
}

CapGeometry sphere_cap(const Sphere& sphere, const glm::vec3& x, const glm::vec3& n) {
  return ball_cap(glm::dvec3(sphere.centre), double(sphere.radius), glm::dvec3(x), glm::dvec3(n),
                  1.0);
}

CapGeometry ellipsoid_cap(const Ellipsoid& e, const glm::vec3& x, const glm::vec3& n) {
  const glm::dmat3 axes(e.axes);
  const glm::dvec3 radii(e.radii);
  CapGeometry none;
  if (!(radii.x > 0.0 && radii.y > 0.0 && radii.z > 0.0) || !finite3(radii)) return none;
  const glm::dmat3 l(axes[0] * radii.x, axes[1] * radii.y, axes[2] * radii.z);
  const double det = std::abs(glm::determinant(l));
  if (!(det > 0.0) || !std::isfinite(det)) return none;
  const glm::dmat3 inv = glm::inverse(l);
  const glm::dvec3 u = inv * (glm::dvec3(x) - glm::dvec3(e.centre));
  const glm::dvec3 nu = glm::transpose(l) * glm::dvec3(n);
  if (!finite3(u) || !finite3(inv[0]) || !finite3(inv[1]) || !finite3(inv[2])) return none;
  return ball_cap(glm::dvec3(0.0), 1.0, u, nu, det);
}

float hegeman_visibility(const Sphere& sphere, const glm::vec3& x, const glm::vec3& n,
                         float alpha_rho) {
  return visibility_from(sphere_cap(sphere, x, n), alpha_rho);  // Hegeman et al. Eq. 6
}

float hegeman_visibility(const Ellipsoid& ellipsoid, const glm::vec3& x, const glm::vec3& n,
                         float alpha_rho) {
  return visibility_from(ellipsoid_cap(ellipsoid, x, n), alpha_rho);
}

float hegeman_visibility(const Shells& shells, const glm::vec3& x, const glm::vec3& n,
                         float alpha_rho) {
  SYLVA_CHECK(shells.shells.size() == shells.anchors.size() && !shells.shells.empty(),
              "hegeman_visibility needs one anchor per shell and at least one shell");
  return hegeman_visibility(shells.shells[shells.nearest(x)], x, n, alpha_rho);
}

double sphere_solid_angle(double r, double dist, SolidAngleModel model) {
  if (!(r > 0.0) || std::isnan(dist)) return 0.0;
  const double s = dist > r ? r / std::abs(dist) : 1.0;     // sin of the cone's half-angle
  if (model == SolidAngleModel::Paper) return kPi * s * s;  // Hegeman et al. Eq. 7
  // 2 pi (1 - cos beta) written without the cancellation of 1 - cos for small angles.
  return 2.0 * kPi * s * s / (1.0 + std::sqrt(std::max(0.0, 1.0 - s * s)));
}

double cone_solid_angle_above_horizon(double beta, double gamma) {
  beta = std::clamp(beta, 0.0, kPi / 2.0);
  gamma = std::clamp(gamma, 0.0, kPi);
  const double sb = std::sin(beta), cb = std::cos(beta);
  const double full = 2.0 * kPi * sb * sb / (1.0 + cb);
  if (gamma + beta <= kPi / 2.0) return full;  // wholly above the horizon
  if (gamma - beta >= kPi / 2.0) return 0.0;   // wholly below
  const double sg = std::sin(gamma), cg = std::cos(gamma);
  // Mazonka 2012, Eq. for two caps with half-angles beta and pi/2 at angular distance gamma.
  const double a1 = std::acos(std::clamp(cg / sb, -1.0, 1.0));
  const double a2 = std::acos(std::clamp(-cg * cb / (sg * sb), -1.0, 1.0));
  return std::clamp(2.0 * (kPi - a1 - cb * a2), 0.0, full);
}

float object_visibility(const Sphere& crown, const glm::vec3& x, const glm::vec3& n,
                        const ObjectOcclusion& options) {
  const double r = crown.radius;
  if (!(r > 0.0) || !std::isfinite(r)) return 1.0f;
  const glm::dvec3 to_centre = glm::dvec3(crown.centre) - glm::dvec3(x);
  if (!finite3(to_centre)) return 1.0f;
  const double dist = glm::length(to_centre);
  double a = sphere_solid_angle(r, dist, options.model);
  glm::dvec3 nd, w;
  if (options.horizon_clip && direction(glm::dvec3(n), nd)) {
    double share = 0.5;  // x at the centre: no direction to the crown
    if (direction(to_centre, w)) {
      const double beta = dist > r ? std::asin(std::clamp(r / dist, 0.0, 1.0)) : kPi / 2.0;
      const double gamma = std::acos(std::clamp(glm::dot(nd, w), -1.0, 1.0));
      const double whole = sphere_solid_angle(std::sin(beta), 1.0, SolidAngleModel::Exact);
      share = whole > 0.0 ? cone_solid_angle_above_horizon(beta, gamma) / whole : 0.0;
    }
    a *= std::clamp(share, 0.0, 1.0);
  }
  return std::clamp(float(1.0 - a / (2.0 * kPi)), 0.0f, 1.0f);  // Hegeman et al. Eq. 8
}

float grass_visibility(float height_above_ground, float blade_height, const glm::vec3& normal,
                       const glm::vec3& up) {
  const double h = blade_height;
  if (!(h > 0.0) || !std::isfinite(h)) return 1.0f;
  const double pz =
      std::isnan(height_above_ground) ? 0.0 : std::clamp(double(height_above_ground), 0.0, h);
  glm::dvec3 nd, ud;
  double cos_theta = 0.0;
  if (direction(glm::dvec3(normal), nd) && direction(glm::dvec3(up), ud))
    cos_theta = std::clamp(glm::dot(nd, ud), -1.0, 1.0);
  return std::clamp(float(pz / (2.0 * h) * (1.0 + cos_theta)), 0.0f, 1.0f);  // Eq. 9
}

float ground_plane_occlusion(float height_above_ground, const glm::vec3& normal,
                             const glm::vec3& up) {
  if (!(height_above_ground >= 0.0f) || !std::isfinite(height_above_ground)) return 0.0f;
  glm::dvec3 nd, ud;
  if (!direction(glm::dvec3(up), ud)) return 0.0f;
  if (!direction(glm::dvec3(normal), nd)) return 0.5f;  // the average over all orientations
  const double theta = std::acos(std::clamp(glm::dot(nd, ud), -1.0, 1.0));
  return std::clamp(float(theta / kPi), 0.0f, 1.0f);
}

}  // namespace sylva

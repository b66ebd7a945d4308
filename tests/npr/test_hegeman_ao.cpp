#include "npr/hegeman_ao.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "core/error.h"
#include "npr/ao_fit.h"

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr float kFloatMax = std::numeric_limits<float>::max();

std::vector<glm::vec3> random_unit_vectors(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::vector<glm::vec3> out;
  while (out.size() < n) {
    const glm::vec3 v(g(rng), g(rng), g(rng));
    if (glm::length(v) > 1e-3f) out.push_back(glm::normalize(v));
  }
  return out;
}

bool in_unit_interval(float v) {
  return std::isfinite(v) && v >= 0.0f && v <= 1.0f;
}

TEST(HegemanCapVolume, EndsAndMiddle) {
  const double r = 2.5;
  EXPECT_EQ(cap_volume(0.0, r), 0.0);
  EXPECT_NEAR(cap_volume(2.0 * r, r), 4.0 / 3.0 * kPi * r * r * r, 1e-12);
  EXPECT_NEAR(cap_volume(r, r), 2.0 / 3.0 * kPi * r * r * r, 1e-12);
  EXPECT_EQ(cap_volume(-1.0, r), 0.0);                         // clamped
  EXPECT_EQ(cap_volume(10.0 * r, r), cap_volume(2.0 * r, r));  // clamped
  EXPECT_EQ(cap_volume(1.0, 0.0), 0.0);
  EXPECT_EQ(cap_volume(1.0, -1.0), 0.0);
  EXPECT_EQ(cap_volume(std::nan(""), 1.0), 0.0);
  double last = 0.0;  // increasing in h
  for (int i = 1; i <= 100; ++i) {
    const double v = cap_volume(2.0 * r * i / 100.0, r);
    EXPECT_GT(v, last);
    last = v;
  }
}

TEST(HegemanOffCentre, RangeAndDegenerateCases) {
  for (double h : {0.0, 1e-300, 1e-3, 0.5, 1.0, 7.0, 1e300})
    for (double d : {0.0, 1e-300, 1e-3, 0.5, 1.0, 7.0, 1e300}) {
      const double f = off_centre_factor(h, d);
      EXPECT_TRUE(std::isfinite(f) && f >= 0.0 && f <= 1.0) << h << " " << d;
    }
  EXPECT_EQ(off_centre_factor(0.0, 0.0), 1.0);  // the d = 0 limit
  EXPECT_EQ(off_centre_factor(0.3, 0.0), 1.0);
  EXPECT_EQ(off_centre_factor(0.0, 0.3), 0.0);
  EXPECT_DOUBLE_EQ(off_centre_factor(1.0, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(off_centre_factor(-1.0, 1.0), 0.5);
}

TEST(HegemanSphere, CapGeometryOfSimplePlanes) {
  const Sphere s{glm::vec3(1, 2, 3), 2.0f};
  CapGeometry g = sphere_cap(s, s.centre, glm::vec3(0, 1, 0));  // through the centre
  EXPECT_DOUBLE_EQ(g.h, 2.0);
  EXPECT_DOUBLE_EQ(g.d, 0.0);
  EXPECT_DOUBLE_EQ(g.f, 1.0);
  EXPECT_NEAR(g.volume, 2.0 / 3.0 * kPi * 8.0, 1e-9);
  // On the surface, facing in: the whole ball; facing out: nothing.
  const glm::vec3 top = s.centre + glm::vec3(0, 2, 0);
  EXPECT_NEAR(sphere_cap(s, top, glm::vec3(0, -1, 0)).h, 4.0, 1e-6);
  EXPECT_NEAR(sphere_cap(s, top, glm::vec3(0, 1, 0)).h, 0.0, 1e-6);
  EXPECT_EQ(hegeman_visibility(s, top, glm::vec3(0, 1, 0), 1.0f), 1.0f);
  // Off-centre in the plane: d measured from the foot of the centre.
  g = sphere_cap(s, s.centre + glm::vec3(1, 0.5f, 0), glm::vec3(0, 1, 0));
  EXPECT_NEAR(g.h, 1.5, 1e-6);
  EXPECT_NEAR(g.d, 1.0, 1e-6);
  EXPECT_NEAR(g.f, 2.25 / 3.25, 1e-6);
  EXPECT_NEAR(g.weighted_volume, g.f * cap_volume(1.5, 2.0), 1e-6);
}

TEST(HegemanSphere, VisibilityInRangeAndDecreasingInAlphaRho) {
  const Sphere s{glm::vec3(0.5f, -1.0f, 2.0f), 3.0f};
  const auto dirs = random_unit_vectors(400, 7);
  const auto offsets = random_unit_vectors(400, 8);
  for (size_t i = 0; i < dirs.size(); ++i) {
    const glm::vec3 x = s.centre + offsets[i] * (3.0f * float(i % 10) / 10.0f);
    float last = 1.0f;
    for (float ar : {0.001f, 0.01f, 0.05f, 0.2f}) {
      const float v = hegeman_visibility(s, x, dirs[i], ar);
      EXPECT_GT(v, 0.0f);
      EXPECT_LE(v, 1.0f);
      EXPECT_LE(v, last);
      last = v;
    }
    EXPECT_EQ(hegeman_visibility(s, x, dirs[i], 0.0f), 1.0f);
    const CapGeometry g = sphere_cap(s, x, dirs[i]);
    EXPECT_TRUE(g.f >= 0.0 && g.f <= 1.0);
    EXPECT_TRUE(g.h >= 0.0 && g.h <= 6.0);
  }
  // Strictly decreasing where the cap has volume.
  EXPECT_LT(hegeman_visibility(s, s.centre, glm::vec3(1, 0, 0), 0.02f),
            hegeman_visibility(s, s.centre, glm::vec3(1, 0, 0), 0.01f));
}

TEST(HegemanSphere, Extremes) {
  const Sphere s{glm::vec3(0.0f), 1.0f};
  const glm::vec3 n(0, 0, 1);
  // Huge alpha_rho: 0, finite. Huge radius and alpha_rho together stay finite.
  EXPECT_EQ(hegeman_visibility(s, glm::vec3(0.0f), n, kFloatMax), 0.0f);
  EXPECT_TRUE(in_unit_interval(
      hegeman_visibility(Sphere{glm::vec3(0), 1e30f}, glm::vec3(0), n, kFloatMax)));
  // Tiny sphere: almost no volume.
  const Sphere tiny{glm::vec3(0.0f), 1e-30f};
  EXPECT_EQ(hegeman_visibility(tiny, glm::vec3(0.0f), n, 1e6f), 1.0f);
  EXPECT_EQ(hegeman_visibility(Sphere{glm::vec3(0), 0.0f}, glm::vec3(0), n, 1e6f), 1.0f);
  EXPECT_EQ(hegeman_visibility(Sphere{glm::vec3(0), -1.0f}, glm::vec3(0), n, 1e6f), 1.0f);
  // At the centre every plane cuts half the ball: V = exp(-alpha_rho 2/3 pi R^3).
  for (const glm::vec3& d : random_unit_vectors(20, 3))
    EXPECT_NEAR(hegeman_visibility(s, glm::vec3(0.0f), d, 0.5f), std::exp(-0.5 * 2.0 / 3.0 * kPi),
                1e-6);
  // Negative / NaN alpha_rho count as 0.
  EXPECT_EQ(hegeman_visibility(s, glm::vec3(0.0f), n, -1.0f), 1.0f);
  EXPECT_EQ(hegeman_visibility(s, glm::vec3(0.0f), n, std::nanf("")), 1.0f);
}

TEST(HegemanSphere, ZeroNormalFacesOutward) {
  const Sphere s{glm::vec3(1.0f), 2.0f};
  const glm::vec3 x = s.centre + glm::vec3(0.3f, -0.4f, 1.0f);
  const glm::vec3 outward = glm::normalize(x - s.centre);
  for (const glm::vec3& zero :
       {glm::vec3(0.0f), glm::vec3(std::nanf(""), 0, 0), glm::vec3(INFINITY, 1, 0)}) {
    const float v = hegeman_visibility(s, x, zero, 0.3f);
    EXPECT_TRUE(in_unit_interval(v));
    EXPECT_NEAR(v, hegeman_visibility(s, x, outward, 0.3f), 1e-6);
    // At the centre: any plane through the centre.
    EXPECT_NEAR(hegeman_visibility(s, s.centre, zero, 0.3f),
                hegeman_visibility(s, s.centre, glm::vec3(0, 1, 0), 0.3f), 1e-6);
  }
  // Denormal-length normals still have a direction.
  const float tiny = std::numeric_limits<float>::denorm_min();
  EXPECT_NEAR(hegeman_visibility(s, x, glm::vec3(0, 0, -tiny), 0.3f),
              hegeman_visibility(s, x, glm::vec3(0, 0, -1), 0.3f), 1e-6);
}

TEST(HegemanSphere, PointsOutside) {
  const Sphere s{glm::vec3(0.0f), 1.0f};
  const glm::vec3 x(0, 0, 5);
  EXPECT_EQ(hegeman_visibility(s, x, glm::vec3(0, 0, 1), 1.0f), 1.0f);  // facing away
  const CapGeometry toward = sphere_cap(s, x, glm::vec3(0, 0, -1));
  EXPECT_DOUBLE_EQ(toward.h, 2.0);  // the whole ball in front
  const CapGeometry side = sphere_cap(s, x, glm::vec3(1, 0, 0));
  EXPECT_NEAR(side.h, 1.0, 1e-9);
  EXPECT_NEAR(side.d, 5.0, 1e-6);
  for (const glm::vec3& d : random_unit_vectors(50, 11))
    EXPECT_TRUE(in_unit_interval(hegeman_visibility(s, glm::vec3(1e30f, 0, 0), d, 1.0f)));
}

TEST(HegemanEllipsoid, EqualAxesEqualTheSphere) {
  const Sphere s{glm::vec3(1, -2, 0.5f), 1.7f};
  const auto dirs = random_unit_vectors(200, 21);
  const auto offs = random_unit_vectors(200, 22);
  for (size_t i = 0; i < dirs.size(); ++i) {
    Ellipsoid e;
    e.centre = s.centre;
    e.axes = glm::mat3(glm::rotate(glm::mat4(1.0f), float(i) * 0.37f, offs[(i + 1) % 200]));
    e.radii = glm::vec3(s.radius);
    const glm::vec3 x = s.centre + offs[i] * (2.5f * float(i % 7) / 6.0f);
    EXPECT_NEAR(hegeman_visibility(e, x, dirs[i], 0.1f), hegeman_visibility(s, x, dirs[i], 0.1f),
                1e-6);
    EXPECT_NEAR(ellipsoid_cap(e, x, dirs[i]).volume, sphere_cap(s, x, dirs[i]).volume, 1e-4);
  }
  EXPECT_NEAR(hegeman_visibility(as_ellipsoid(s), s.centre, glm::vec3(0), 0.1f),
              hegeman_visibility(s, s.centre, glm::vec3(0), 0.1f), 1e-6);
}

TEST(HegemanEllipsoid, VolumeScalesWithTheAxes) {
  Ellipsoid e;
  e.radii = glm::vec3(3.0f, 1.0f, 0.5f);
  // A plane through the centre cuts half the ellipsoid, whatever its orientation.
  for (const glm::vec3& d : random_unit_vectors(30, 5))
    EXPECT_NEAR(ellipsoid_cap(e, glm::vec3(0), d).volume, 2.0 / 3.0 * kPi * 1.5, 1e-5);
  // The normal maps by the inverse-transpose: a plane tangent at the tip along x
  // (normal -x) holds the whole ellipsoid.
  EXPECT_NEAR(ellipsoid_cap(e, glm::vec3(3, 0, 0), glm::vec3(-1, 0, 0)).volume,
              4.0 / 3.0 * kPi * 1.5, 1e-5);
  // Tilted plane through the tip of the x axis: the image normal is no longer the same
  // direction, but the cap still lies on the inner side.
  const CapGeometry g = ellipsoid_cap(e, glm::vec3(3, 0, 0), glm::normalize(glm::vec3(-1, 1, 0)));
  EXPECT_GT(g.volume, 0.0);
  EXPECT_LT(g.volume, 4.0 / 3.0 * kPi * 1.5);
}

TEST(HegemanEllipsoid, FlatAndDegenerate) {
  Ellipsoid e;
  e.radii = glm::vec3(1.0f, 1.0f, 0.0f);  // flat: no volume
  EXPECT_EQ(hegeman_visibility(e, glm::vec3(0), glm::vec3(0, 0, 1), 100.0f), 1.0f);
  e.radii = glm::vec3(1.0f, 1.0f, -1.0f);
  EXPECT_EQ(hegeman_visibility(e, glm::vec3(0), glm::vec3(0, 0, 1), 100.0f), 1.0f);
  e.radii = glm::vec3(1.0f, INFINITY, 1.0f);
  EXPECT_EQ(hegeman_visibility(e, glm::vec3(0), glm::vec3(0, 0, 1), 100.0f), 1.0f);
  e.radii = glm::vec3(1.0f);
  e.axes = glm::mat3(glm::vec3(1, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1));  // singular
  EXPECT_EQ(hegeman_visibility(e, glm::vec3(0), glm::vec3(0, 0, 1), 100.0f), 1.0f);
  // Very thin but positive: finite, close to 1 for moderate alpha_rho.
  e.axes = glm::mat3(1.0f);
  e.radii = glm::vec3(1.0f, 1.0f, 1e-30f);
  for (const glm::vec3& d : random_unit_vectors(50, 9)) {
    const float v = hegeman_visibility(e, glm::vec3(0.1f, 0.2f, 1e-31f), d, 1.0f);
    EXPECT_TRUE(in_unit_interval(v));
    EXPECT_GT(v, 0.999f);
    EXPECT_TRUE(in_unit_interval(hegeman_visibility(e, glm::vec3(0.5f, 0, 1.0f), d, kFloatMax)));
  }
}

TEST(HegemanShells, UsesTheNearestAnchor) {
  Shells shells;
  shells.shells = {as_ellipsoid(Sphere{glm::vec3(-5, 0, 0), 1.0f}),
                   as_ellipsoid(Sphere{glm::vec3(5, 0, 0), 2.0f})};
  shells.anchors = {glm::vec3(-5, 0, 0), glm::vec3(5, 0, 0)};
  const glm::vec3 n(0, 1, 0);
  EXPECT_EQ(hegeman_visibility(shells, glm::vec3(4, 0, 0), n, 0.1f),
            hegeman_visibility(Sphere{glm::vec3(5, 0, 0), 2.0f}, glm::vec3(4, 0, 0), n, 0.1f));
  EXPECT_EQ(hegeman_visibility(shells, glm::vec3(-4, 0, 0), n, 0.1f),
            hegeman_visibility(Sphere{glm::vec3(-5, 0, 0), 1.0f}, glm::vec3(-4, 0, 0), n, 0.1f));
  EXPECT_TRUE(in_unit_interval(hegeman_visibility(shells, glm::vec3(NAN), n, 0.1f)));
}

TEST(HegemanSolidAngle, ModelsAgreeFarAwayAndAreContinuousAtTheBoundary) {
  for (auto model : {SolidAngleModel::Paper, SolidAngleModel::Exact}) {
    const double at = sphere_solid_angle(1.0, 1.0, model);
    EXPECT_NEAR(sphere_solid_angle(1.0, 1.0 + 1e-14, model), at, 1e-5);
    EXPECT_EQ(sphere_solid_angle(1.0, 0.5, model), at);  // clamped inside
    EXPECT_EQ(sphere_solid_angle(1.0, 0.0, model), at);
    EXPECT_EQ(sphere_solid_angle(0.0, 3.0, model), 0.0);
    double last = at;
    for (double dist = 1.01; dist < 100.0; dist *= 1.1) {
      const double a = sphere_solid_angle(1.0, dist, model);
      EXPECT_LT(a, last);
      last = a;
    }
  }
  EXPECT_NEAR(sphere_solid_angle(1.0, 1.0, SolidAngleModel::Paper), kPi, 1e-12);
  EXPECT_NEAR(sphere_solid_angle(1.0, 1.0, SolidAngleModel::Exact), 2.0 * kPi, 1e-12);
  const double ratio = sphere_solid_angle(1.0, 1000.0, SolidAngleModel::Paper) /
                       sphere_solid_angle(1.0, 1000.0, SolidAngleModel::Exact);
  EXPECT_NEAR(ratio, 1.0, 1e-6);
  const double tiny = sphere_solid_angle(1e-30, 1e30, SolidAngleModel::Exact);
  EXPECT_TRUE(std::isfinite(tiny) && tiny > 0.0);
}

// Numerical integral of the cone-hemisphere intersection: for each polar angle theta of
// the cone (axis at angle gamma from n), the azimuths above the horizon.
double quadrature_above_horizon(double beta, double gamma) {
  const int steps = 20000;
  double sum = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double th = (i + 0.5) * beta / steps;
    const double q = -std::cos(gamma) * std::cos(th) / (std::sin(gamma) * std::sin(th));
    sum += std::sin(th) * 2.0 * std::acos(std::clamp(q, -1.0, 1.0));
  }
  return sum * beta / steps;
}

TEST(HegemanSolidAngle, HorizonClipMatchesQuadrature) {
  for (double beta : {0.05, 0.3, 0.8, 1.3, kPi / 2 - 1e-3})
    for (double gamma : {0.1, 0.5, 1.0, 1.4, kPi / 2, 1.9, 2.5, 3.0})
      EXPECT_NEAR(cone_solid_angle_above_horizon(beta, gamma),
                  quadrature_above_horizon(beta, gamma), 2e-4)
          << beta << " " << gamma;
  EXPECT_NEAR(cone_solid_angle_above_horizon(0.4, kPi / 2),
              0.5 * sphere_solid_angle(std::sin(0.4), 1.0, SolidAngleModel::Exact), 1e-12);
}

TEST(HegemanObject, GroundUnderATree) {
  const Sphere crown{glm::vec3(0, 5, 0), 2.0f};
  const glm::vec3 up(0, 1, 0);
  const float v = object_visibility(crown, glm::vec3(0), up);
  EXPECT_NEAR(v, 1.0 - (1.0 - std::sqrt(1.0 - 0.16)), 1e-6);  // cone wholly above the ground
  ObjectOcclusion paper{SolidAngleModel::Paper, false};
  EXPECT_NEAR(object_visibility(crown, glm::vec3(0), up, paper), 1.0 - 0.16 / 2.0, 1e-6);
  // Facing away from the crown: unoccluded with clipping, occluded as printed without.
  EXPECT_EQ(object_visibility(crown, glm::vec3(0), -up), 1.0f);
  EXPECT_LT(object_visibility(crown, glm::vec3(0), -up, paper), 1.0f);
  // Zero normal: no clipping.
  EXPECT_EQ(
      object_visibility(crown, glm::vec3(0), glm::vec3(0)),
      object_visibility(crown, glm::vec3(0), up, ObjectOcclusion{SolidAngleModel::Exact, false}));
}

TEST(HegemanObject, ContinuousAtTheSphereAndInRange) {
  const Sphere crown{glm::vec3(1, 2, 3), 1.5f};
  for (const glm::vec3& dir : random_unit_vectors(30, 31))
    for (const glm::vec3& n : random_unit_vectors(5, 32))
      for (auto model : {SolidAngleModel::Paper, SolidAngleModel::Exact})
        for (bool clip : {false, true}) {
          const ObjectOcclusion o{model, clip};
          const float out = object_visibility(crown, crown.centre + dir * 1.50001f, n, o);
          const float in = object_visibility(crown, crown.centre + dir * 1.49999f, n, o);
          EXPECT_NEAR(out, in, 1e-2);
          EXPECT_TRUE(in_unit_interval(out) && in_unit_interval(in));
          EXPECT_TRUE(in_unit_interval(object_visibility(crown, crown.centre, n, o)));
          EXPECT_TRUE(in_unit_interval(object_visibility(crown, glm::vec3(1e30f), n, o)));
        }
  EXPECT_EQ(object_visibility(Sphere{glm::vec3(0), 0.0f}, glm::vec3(1), glm::vec3(0, 1, 0)), 1.0f);
}

TEST(HegemanGrass, Equation9) {
  const glm::vec3 up(0, 1, 0);
  EXPECT_FLOAT_EQ(grass_visibility(1.0f, 1.0f, up), 1.0f);
  EXPECT_FLOAT_EQ(grass_visibility(0.5f, 1.0f, up), 0.5f);
  EXPECT_FLOAT_EQ(grass_visibility(1.0f, 1.0f, glm::vec3(1, 0, 0)), 0.5f);
  EXPECT_FLOAT_EQ(grass_visibility(1.0f, 1.0f, -up), 0.0f);
  EXPECT_FLOAT_EQ(grass_visibility(2.0f, 1.0f, up), 1.0f);   // P_z clamped to h
  EXPECT_FLOAT_EQ(grass_visibility(-1.0f, 1.0f, up), 0.0f);  // and to 0
  EXPECT_FLOAT_EQ(grass_visibility(0.5f, 0.0f, up), 1.0f);   // no grass
  EXPECT_FLOAT_EQ(grass_visibility(0.5f, -1.0f, up), 1.0f);
  EXPECT_FLOAT_EQ(grass_visibility(0.5f, 1.0f, glm::vec3(0)), 0.25f);  // cos theta = 0
  EXPECT_FLOAT_EQ(grass_visibility(1.0f, 2.0f, glm::vec3(0, 0, 3), glm::vec3(0, 0, 1)), 0.5f);
  for (const glm::vec3& n : random_unit_vectors(100, 41))
    EXPECT_TRUE(in_unit_interval(grass_visibility(0.3f, 0.7f, n)));
}

TEST(HegemanValidate, AlphaRho) {
  EXPECT_NO_THROW(validate_alpha_rho(0.0f));
  EXPECT_NO_THROW(validate_alpha_rho(kFloatMax));
  EXPECT_THROW(validate_alpha_rho(-1e-30f), InputError);
  EXPECT_THROW(validate_alpha_rho(INFINITY), InputError);
  EXPECT_THROW(validate_alpha_rho(NAN), InputError);
}

TEST(HegemanGround, PlaneHidesThetaOverPiOfTheHemisphere) {
  const glm::vec3 up(0, 1, 0);
  EXPECT_EQ(ground_plane_occlusion(1.0f, up), 0.0f);                           // facing up
  EXPECT_NEAR(ground_plane_occlusion(1.0f, glm::vec3(1, 0, 0)), 0.5f, 1e-6f);  // a wall
  EXPECT_NEAR(ground_plane_occlusion(1.0f, -up), 1.0f, 1e-6f);                 // facing down
  EXPECT_NEAR(ground_plane_occlusion(1.0f, glm::vec3(1, 1, 0)), 0.25f, 1e-6f);
  EXPECT_NEAR(ground_plane_occlusion(1.0f, glm::vec3(0, -1, 1)), 0.75f, 1e-6f);
  // Against the lune's solid angle counted by Monte Carlo over the hemisphere.
  std::mt19937 rng(3);
  std::normal_distribution<float> g;
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, -0.2f, 0.9f));
  int in = 0, hidden = 0;
  while (in < 200000) {
    const glm::vec3 w(g(rng), g(rng), g(rng));
    if (glm::dot(w, n) <= 0.0f) continue;
    ++in;
    if (w.y < 0.0f) ++hidden;
  }
  EXPECT_NEAR(ground_plane_occlusion(0.0f, n), double(hidden) / in, 4e-3);
  // Degenerate: on the plane counts, below it or non-finite: nothing; zero normal: 1/2;
  // scale-free in the normal and up; zero up: nothing.
  EXPECT_NEAR(ground_plane_occlusion(0.0f, glm::vec3(1, 0, 0)), 0.5f, 1e-6f);
  EXPECT_EQ(ground_plane_occlusion(-1e-6f, glm::vec3(1, 0, 0)), 0.0f);
  EXPECT_EQ(ground_plane_occlusion(NAN, glm::vec3(1, 0, 0)), 0.0f);
  EXPECT_EQ(ground_plane_occlusion(INFINITY, glm::vec3(1, 0, 0)), 0.0f);
  EXPECT_EQ(ground_plane_occlusion(1.0f, glm::vec3(0.0f)), 0.5f);
  EXPECT_NEAR(ground_plane_occlusion(1.0f, glm::vec3(1e-30f, 0, 0)), 0.5f, 1e-6f);
  EXPECT_NEAR(ground_plane_occlusion(1.0f, glm::vec3(1e30f, 1e30f, 0)), 0.25f, 1e-6f);
  EXPECT_EQ(ground_plane_occlusion(1.0f, glm::vec3(1, 0, 0), glm::vec3(0.0f)), 0.0f);
  EXPECT_NEAR(ground_plane_occlusion(1.0f, glm::vec3(0, 0, 1), glm::vec3(0, 0, 5)), 0.0f, 1e-6f);
}

TEST(AlphaRhoFit, RecoversAKnownValueExactly) {
  std::vector<AlphaRhoSample> samples;
  for (int i = 0; i < 200; ++i) {
    const double x = 0.05 * i;
    samples.push_back({x, std::exp(-0.73 * x)});
  }
  const AlphaRhoFit fit = fit_alpha_rho(samples);
  EXPECT_NEAR(fit.alpha_rho, 0.73, 1e-9);
  EXPECT_LT(fit.rmse, 1e-9);
  // Scale-free: volumes in cubic millimetres instead of metres.
  for (AlphaRhoSample& s : samples)
    s.weighted_volume *= 1e9;
  EXPECT_NEAR(fit_alpha_rho(samples).alpha_rho, 0.73e-9, 1e-18);
}

TEST(AlphaRhoFit, RecoversAKnownValueFromNoisySamples) {
  std::mt19937 rng(5);
  // x up to 1.5 keeps exp(-1.9 x) above the noise, so no sample is clamped at 0.
  std::uniform_real_distribution<double> ux(0.0, 1.5), noise(-0.03, 0.03);
  std::vector<AlphaRhoSample> samples;
  for (int i = 0; i < 5000; ++i) {
    const double x = ux(rng);
    samples.push_back({x, std::clamp(std::exp(-1.9 * x) + noise(rng), 0.0, 1.0)});
  }
  const AlphaRhoFit fit = fit_alpha_rho(samples);
  EXPECT_NEAR(fit.alpha_rho, 1.9, 0.02);
  EXPECT_NEAR(fit.rmse, 0.03 / std::sqrt(3.0), 3e-3);
  // Least squares in V, not in log V: noise on small v biases the log-linear start.
  EXPECT_NE(fit.log_linear_estimate, fit.alpha_rho);
}

TEST(AlphaRhoFit, DegenerateSamples) {
  EXPECT_EQ(fit_alpha_rho({{0.0, 0.5}, {0.0, 0.2}}).alpha_rho, 0.0);   // x = 0 everywhere
  EXPECT_EQ(fit_alpha_rho({{1.0, 1.0}, {2.0, 1.0}}).alpha_rho, 0.0);   // nothing occluded
  const AlphaRhoFit opaque = fit_alpha_rho({{1.0, 0.0}, {2.0, 0.0}});  // v = 0 allowed
  EXPECT_TRUE(std::isfinite(opaque.alpha_rho) && opaque.alpha_rho > 10.0);
  EXPECT_LT(opaque.rmse, 1e-3);
  const AlphaRhoFit one = fit_alpha_rho({{2.0, std::exp(-1.0)}});
  EXPECT_NEAR(one.alpha_rho, 0.5, 1e-9);
  EXPECT_THROW(fit_alpha_rho({}), InputError);
  EXPECT_THROW(fit_alpha_rho({{-1.0, 0.5}}), InputError);
  EXPECT_THROW(fit_alpha_rho({{NAN, 0.5}}), InputError);
  EXPECT_THROW(fit_alpha_rho({{INFINITY, 0.5}}), InputError);
  EXPECT_THROW(fit_alpha_rho({{1.0, 1.5}}), InputError);
  EXPECT_THROW(fit_alpha_rho({{1.0, -0.1}}), InputError);
  EXPECT_THROW(fit_alpha_rho({{1.0, NAN}}), InputError);
}

// Weights choose which samples the fit follows: two groups that want different k, and the
// weighted fit lands on the heavier one's; a zero weight drops a sample; every weight
// scaled by the same factor changes nothing.
TEST(AlphaRhoFit, WeightsChooseWhichSamplesCount) {
  std::vector<AlphaRhoSample> samples;
  for (int i = 1; i <= 50; ++i) {
    const double x = 0.04 * i;
    samples.push_back({x, std::exp(-0.5 * x), 1.0});
    samples.push_back({x, std::exp(-2.0 * x), 1.0});
  }
  const double even = fit_alpha_rho(samples).alpha_rho;
  EXPECT_GT(even, 0.6);
  EXPECT_LT(even, 1.9);
  for (size_t i = 1; i < samples.size(); i += 2)
    samples[i].weight = 0.0;
  EXPECT_NEAR(fit_alpha_rho(samples).alpha_rho, 0.5, 1e-9);
  EXPECT_LT(fit_alpha_rho(samples).rmse, 1e-9);  // the dropped samples' misfit does not count
  for (size_t i = 0; i < samples.size(); ++i)
    samples[i].weight = i % 2 ? 0.01 : 1.0;
  const double lean = fit_alpha_rho(samples).alpha_rho;
  EXPECT_GT(lean, 0.5);
  EXPECT_LT(lean, even);
  for (AlphaRhoSample& p : samples)
    p.weight *= 1e-200;
  EXPECT_NEAR(fit_alpha_rho(samples).alpha_rho, lean, 1e-9 * lean);
  // Bad weights.
  EXPECT_THROW(fit_alpha_rho({{1.0, 0.5, -1e-300}}), InputError);
  EXPECT_THROW(fit_alpha_rho({{1.0, 0.5, NAN}}), InputError);
  EXPECT_THROW(fit_alpha_rho({{1.0, 0.5, INFINITY}}), InputError);
  EXPECT_THROW(fit_alpha_rho({{1.0, 0.5, 0.0}, {2.0, 0.2, 0.0}}), InputError);      // sum 0
  EXPECT_THROW(fit_alpha_rho({{1.0, 0.5, 1e308}, {2.0, 0.2, 1e308}}), InputError);  // overflow
  EXPECT_NO_THROW(fit_alpha_rho({{1.0, 0.5, 1e-300}}));
}

}  // namespace
}  // namespace sylva

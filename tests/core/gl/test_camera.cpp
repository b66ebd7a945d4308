// Orbit camera: eye placement convention, automatic framing, option validation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "core/error.h"
#include "core/gl/camera.h"

namespace sylva {
namespace {

Bounds box(glm::vec3 lo, glm::vec3 hi) {
  Bounds b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

OrbitParams orbit(float az, float el) {
  OrbitParams p;
  p.azimuth_deg = az;
  p.elevation_deg = el;
  return p;
}

std::string where_of(const Bounds& b, const OrbitParams& p, int w, int h) {
  try {
    make_orbit_camera(b, p, w, h);
  } catch (const InputError& e) {
    return e.where();
  }
  return "";
}

// Largest |NDC x| or |NDC y| over points on the bounds' bounding sphere.
float sphere_extent(const Bounds& b, const Camera& c) {
  const float r = 0.5f * b.diagonal();
  float extent = 0.0f;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {  // Fibonacci sphere
    const float z = 1.0f - 2.0f * (i + 0.5f) / n;
    const float phi = 2.39996323f * i;
    const float s = std::sqrt(1.0f - z * z);
    const glm::vec3 p = b.center() + r * glm::vec3(s * std::cos(phi), s * std::sin(phi), z);
    const glm::vec4 clip = c.proj * c.view * glm::vec4(p, 1.0f);
    extent = std::max({extent, std::abs(clip.x / clip.w), std::abs(clip.y / clip.w)});
  }
  return extent;
}

TEST(Camera, AzimuthZeroLooksFromPlusZ) {
  const Bounds b = box({-1, -2, -3}, {3, 2, 1});  // centre (1, 0, -1)
  const Camera c = make_orbit_camera(b, orbit(0, 0), 100, 100);
  const glm::vec3 rel = c.eye - b.center();
  EXPECT_GT(rel.z, 0.0f);
  EXPECT_NEAR(rel.x, 0.0f, 1e-4f);
  EXPECT_NEAR(rel.y, 0.0f, 1e-4f);
  // The centre is straight ahead: view space (0, 0, -distance).
  const glm::vec4 v = c.view * glm::vec4(b.center(), 1.0f);
  EXPECT_NEAR(v.x, 0.0f, 1e-4f);
  EXPECT_NEAR(v.y, 0.0f, 1e-4f);
  EXPECT_NEAR(-v.z, glm::length(rel), 1e-4f);
}

TEST(Camera, Azimuth90IsOnPlusX) {
  const Bounds b = box({-1, -1, -1}, {1, 1, 1});
  const Camera c = make_orbit_camera(b, orbit(90, 0), 100, 100);
  EXPECT_GT(c.eye.x, 0.0f);
  EXPECT_NEAR(c.eye.z, 0.0f, 1e-4f);
  EXPECT_NEAR(c.eye.y, 0.0f, 1e-4f);
}

TEST(Camera, Elevation45IsAbove) {
  const Bounds b = box({-1, -1, -1}, {1, 1, 1});
  const Camera c = make_orbit_camera(b, orbit(0, 45), 100, 100);
  const float d = glm::length(c.eye);
  EXPECT_NEAR(c.eye.y, d * std::sqrt(0.5f), 1e-4f * d);
  EXPECT_NEAR(c.eye.z, d * std::sqrt(0.5f), 1e-4f * d);
  // Up stays up: the world +Y axis projects upward on screen.
  const glm::vec4 up = c.view * glm::vec4(0, 1, 0, 0);
  EXPECT_GT(up.y, 0.0f);
}

TEST(Camera, ExplicitDistanceIsUsed) {
  const Bounds b = box({-1, -1, -1}, {1, 1, 1});
  OrbitParams p = orbit(10, 20);
  p.distance = 7.5f;
  const Camera c = make_orbit_camera(b, p, 64, 64);
  EXPECT_NEAR(glm::length(c.eye - b.center()), 7.5f, 1e-4f);
  EXPECT_GT(c.near_plane, 0.0f);
  EXPECT_LT(c.near_plane, 7.5f - std::sqrt(3.0f));
  EXPECT_GT(c.far_plane, 7.5f + std::sqrt(3.0f));
}

// Every corner of the bounds must land inside NDC for any view direction, fov, aspect and
// projection; the framing is also not wastefully loose.
TEST(Camera, AutoFramingKeepsCornersInside) {
  const Bounds b = box({-0.3f, 0.0f, -2.0f}, {0.7f, 5.0f, 1.0f});
  const int sizes[][2] = {{256, 256}, {640, 240}, {200, 700}};
  for (bool ortho : {false, true}) {
    for (float fov : {10.0f, 35.0f, 90.0f, 150.0f}) {
      for (auto size : sizes) {
        for (float az : {0.0f, 37.0f, 145.0f, -100.0f}) {
          for (float el : {-89.0f, -30.0f, 0.0f, 60.0f, 89.0f}) {
            OrbitParams p = orbit(az, el);
            p.fov_deg = fov;
            p.ortho = ortho;
            const Camera c = make_orbit_camera(b, p, size[0], size[1]);
            float extent = 0.0f;
            for (int i = 0; i < 8; ++i) {
              const glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                                     (i & 4) ? b.max.z : b.min.z);
              const glm::vec4 clip = c.proj * c.view * glm::vec4(corner, 1.0f);
              ASSERT_GT(clip.w, 0.0f);
              const glm::vec3 ndc = glm::vec3(clip) / clip.w;
              for (int k = 0; k < 3; ++k) {
                ASSERT_LE(std::abs(ndc[k]), 1.0f)
                    << "axis " << k << " ortho " << ortho << " fov " << fov << " az " << az
                    << " el " << el << " size " << size[0] << "x" << size[1];
              }
              extent = std::max({extent, std::abs(ndc.x), std::abs(ndc.y)});
            }
            EXPECT_GT(extent, 0.0f);
            // The bounding sphere itself touches the frame (5% margin): tight, not loose.
            const float sphere = sphere_extent(b, c);
            EXPECT_LE(sphere, 1.0f);
            EXPECT_GE(sphere, fov <= 90.0f || ortho ? 0.85f : 0.6f)
                << "fov " << fov << " ortho " << ortho;
          }
        }
      }
    }
  }
}

// The shadow-map camera sees the whole sphere, depth included, from any light direction
// (straight up and down too) and from point lights outside and inside the sphere.
TEST(Camera, LightCameraHoldsTheSphere) {
  const Sphere sphere{{1.0f, 4.0f, -2.0f}, 3.0f};
  struct Case {
    glm::vec3 v;
    bool point;
  } cases[] = {{{0, 1, 0}, false},        {{0, -5, 0}, false}, {{1, 1, 1}, false},
               {{0.3f, 0.2f, -1}, false}, {{1, 30, -2}, true}, {{20, 4, -2}, true}};
  for (const Case& c : cases) {
    const Camera cam = make_light_camera(sphere, c.v, c.point, 256);
    EXPECT_EQ(cam.width, 256);
    EXPECT_EQ(cam.ortho, !c.point);
    float extent = 0.0f;
    for (int i = 0; i < 2000; ++i) {
      const float z = 1.0f - 2.0f * (i + 0.5f) / 2000;
      const float phi = 2.39996323f * i;
      const float s = std::sqrt(1.0f - z * z);
      const glm::vec3 p =
          sphere.centre + sphere.radius * glm::vec3(s * std::cos(phi), s * std::sin(phi), z);
      const glm::vec4 clip = cam.proj * cam.view * glm::vec4(p, 1.0f);
      ASSERT_GT(clip.w, 0.0f);
      const glm::vec3 ndc = glm::vec3(clip) / clip.w;
      for (int k = 0; k < 3; ++k)
        ASSERT_LE(std::abs(ndc[k]), 1.0f) << "axis " << k << " point " << c.point;
      extent = std::max({extent, std::abs(ndc.x), std::abs(ndc.y)});
    }
    EXPECT_GT(extent, 0.85f);  // tight: a texel is not wasted on empty space
  }
  // A directional light looks along -v: the centre lies straight ahead.
  const Camera down = make_light_camera(sphere, {0, 1, 0}, false, 64);
  const glm::vec4 centre = down.view * glm::vec4(sphere.centre, 1.0f);
  EXPECT_NEAR(centre.x, 0.0f, 1e-4f);
  EXPECT_NEAR(centre.y, 0.0f, 1e-4f);
  EXPECT_LT(centre.z, 0.0f);
  EXPECT_GT(down.eye.y, sphere.centre.y);
  // A point light inside the sphere still gets a finite, wide camera.
  const Camera inside = make_light_camera(sphere, sphere.centre + glm::vec3(0.5f, 0, 0), true, 64);
  EXPECT_FALSE(inside.ortho);
  EXPECT_TRUE(std::isfinite(inside.proj[0][0]));
}

TEST(Camera, InvalidValuesThrow) {
  const Bounds b = box({-1, -1, -1}, {1, 1, 1});
  EXPECT_EQ(where_of(b, orbit(0, 89.5f), 64, 64), "--elevation");
  EXPECT_EQ(where_of(b, orbit(0, -90.0f), 64, 64), "--elevation");
  EXPECT_EQ(where_of(b, orbit(0, NAN), 64, 64), "--elevation");
  EXPECT_EQ(where_of(b, orbit(INFINITY, 0), 64, 64), "--azimuth");
  OrbitParams p = orbit(0, 0);
  p.fov_deg = 0.5f;
  EXPECT_EQ(where_of(b, p, 64, 64), "--fov");
  p.fov_deg = 151.0f;
  EXPECT_EQ(where_of(b, p, 64, 64), "--fov");
  p = orbit(0, 0);
  p.distance = -1.0f;
  EXPECT_EQ(where_of(b, p, 64, 64), "--distance");
  p.distance = INFINITY;
  EXPECT_EQ(where_of(b, p, 64, 64), "--distance");
  EXPECT_EQ(where_of(b, orbit(0, 0), 0, 64), "--size");
  EXPECT_EQ(where_of(b, orbit(0, 0), 64, 16385), "--size");
  EXPECT_EQ(where_of(Bounds{}, orbit(0, 0), 64, 64), "scene");
  // The ends of each range are valid.
  EXPECT_EQ(where_of(b, orbit(-720, -89), 1, 16384), "");
  p = orbit(0, 89);
  p.fov_deg = 150.0f;
  EXPECT_EQ(where_of(b, p, 16384, 1), "");
  p.fov_deg = 1.0f;
  EXPECT_EQ(where_of(b, p, 16384, 1), "");
}

TEST(Camera, SinglePointBoundsStaysFinite) {
  const Bounds b = box({2, 3, 4}, {2, 3, 4});
  const Camera c = make_orbit_camera(b, orbit(0, 0), 32, 32);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      EXPECT_TRUE(std::isfinite(c.proj[i][j]));
      EXPECT_TRUE(std::isfinite(c.view[i][j]));
    }
  }
  EXPECT_LT(c.near_plane, c.far_plane);
}

// A tree-like point set (a trunk under a round crown): the framing sphere holds every
// vertex, touches the farthest one, is tighter than the box's circumscribed sphere, and the
// camera built from it keeps every vertex on screen from any side.
TEST(Camera, FramingSphereIsTightAndHoldsEveryVertex) {
  Scene s;
  Mesh m;
  m.positions = {{0, 0, 0}, {0.05f, 0, 0}, {0, 2, 0}};  // trunk
  for (int i = 0; i < 64; ++i) {                        // crown: a ring of radius 1 at y = 3
    const float a = 6.2831853f * float(i) / 64.0f;
    m.positions.push_back({std::cos(a), 3.0f + 0.3f * std::sin(3.0f * a), std::sin(a)});
  }
  for (uint32_t i = 1; i + 1 < m.positions.size(); ++i)
    m.indices.insert(m.indices.end(), {0, i, i + 1});
  s.meshes.push_back(m);
  const Sphere sphere = s.framing_sphere();
  float farthest = 0.0f;
  for (const glm::vec3& p : m.positions)
    farthest = std::max(farthest, glm::length(p - sphere.centre));
  EXPECT_FLOAT_EQ(sphere.radius, farthest);
  EXPECT_LT(sphere.radius, 0.5f * s.bounds().diagonal() * 0.9f);
  for (float az : {0.0f, 45.0f, 180.0f})
    for (float el : {-60.0f, 0.0f, 60.0f}) {
      const Camera c = make_orbit_camera(sphere, orbit(az, el), 200, 100);
      for (const glm::vec3& p : m.positions) {
        const glm::vec4 clip = c.proj * c.view * glm::vec4(p, 1.0f);
        EXPECT_LE(std::abs(clip.x / clip.w), 1.0f);
        EXPECT_LE(std::abs(clip.y / clip.w), 1.0f);
      }
    }
  EXPECT_THROW(make_orbit_camera(Scene{}.framing_sphere(), orbit(0, 0), 8, 8), InputError);
}

TEST(FileCamera, KeepsTheFilesViewFieldAndClippingWithTheImagesAspect) {
  SceneCamera f;
  f.yfov = glm::radians(50.0f);
  f.znear = 0.5f;
  f.zfar = 40.0f;
  f.to_world = glm::inverse(glm::lookAt(glm::vec3(3, 4, 5), glm::vec3(0), glm::vec3(0, 1, 0)));
  const Sphere sphere{glm::vec3(0.0f), 2.0f};
  const Camera c = make_file_camera(f, sphere, 300, 100);
  EXPECT_FALSE(c.ortho);
  EXPECT_NEAR(glm::length(c.eye - glm::vec3(3, 4, 5)), 0.0f, 1e-5f);
  const glm::mat4 want = glm::perspective(f.yfov, 3.0f, 0.5f, 40.0f);
  for (int i = 0; i < 16; ++i)
    EXPECT_NEAR(c.proj[i / 4][i % 4], want[i / 4][i % 4], 1e-6f);
  EXPECT_EQ(c.near_plane, 0.5f);
  EXPECT_EQ(c.far_plane, 40.0f);
  // An infinite far plane reaches past the sphere.
  f.zfar = 0.0f;
  const Camera inf = make_file_camera(f, sphere, 100, 100);
  EXPECT_GT(inf.far_plane, glm::length(glm::vec3(3, 4, 5)) + 2.0f);
  // Orthographic: ymag kept, the width from the image.
  f.orthographic = true;
  f.ymag = 2.0f;
  f.xmag = 7.0f;
  f.znear = 0.0f;
  f.zfar = 10.0f;
  const Camera o = make_file_camera(f, sphere, 200, 100);
  EXPECT_TRUE(o.ortho);
  EXPECT_NEAR(o.proj[1][1], 1.0f / 2.0f, 1e-6f);
  EXPECT_NEAR(o.proj[0][0], 1.0f / 4.0f, 1e-6f);
  EXPECT_THROW(make_file_camera(f, sphere, 0, 100), InputError);
  EXPECT_THROW(make_file_camera(f, sphere, 16385, 100), InputError);
}

TEST(Camera, LightCameraReachesCastersOutsideItsSphere) {
  const Sphere visible{glm::vec3(0.0f), 1.0f};
  const glm::vec3 up(0, 1, 0);
  const Camera plain = make_light_camera(visible, up, false, 64);
  // Without casters: exactly as before the option existed.
  const Camera same = make_light_camera(visible, up, false, 64, Sphere{});
  EXPECT_EQ(plain.view, same.view);
  EXPECT_EQ(plain.proj, same.proj);
  // A caster 10 units up (toward the light) must be in front of the near plane.
  const Sphere casters{glm::vec3(0, 5, 0), 6.0f};
  const Camera c = make_light_camera(visible, up, false, 64, casters);
  const glm::vec4 top = c.view * glm::vec4(0, 10.5f, 0, 1);
  EXPECT_GT(-top.z, c.near_plane);
  const glm::vec4 bottom = c.view * glm::vec4(0, -1, 0, 1);
  EXPECT_LT(-bottom.z, c.far_plane);
  // The covered width is still the visible sphere's.
  EXPECT_EQ(c.proj[0][0], plain.proj[0][0]);
}

}  // namespace
}  // namespace sylva

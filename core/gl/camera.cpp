#include "core/gl/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"

namespace sylva {

namespace {

constexpr float kMargin = 1.05f;      // the framed sphere is this much larger than the bounds'
constexpr int kMaxImageSide = 16384;  // pixels

void validate(const OrbitParams& p, int width, int height) {
  if (!std::isfinite(p.azimuth_deg)) throw InputError("--azimuth", "must be a finite number");
  if (!(p.elevation_deg >= -89.0f && p.elevation_deg <= 89.0f)) {
    throw InputError("--elevation", "must be in [-89, 89] degrees");
  }
  if (!(p.fov_deg >= 1.0f && p.fov_deg <= 150.0f)) {
    throw InputError("--fov", "must be in [1, 150] degrees");
  }
  if (!(std::isfinite(p.distance) && p.distance >= 0.0f)) {
    throw InputError("--distance", "must be 0 (automatic) or a positive distance");
  }
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide) {
    throw InputError(
        "--size", "width and height must be in [1, " + std::to_string(kMaxImageSide) + "] pixels");
  }
}

}  // namespace

Camera make_orbit_camera(const Bounds& bounds, const OrbitParams& params, int width, int height) {
  Sphere s;
  if (!bounds.empty()) s = Sphere{bounds.center(), 0.5f * bounds.diagonal()};
  return make_orbit_camera(s, params, width, height);
}

Camera make_orbit_camera(const Sphere& sphere, const OrbitParams& params, int width, int height) {
  validate(params, width, height);
  if (sphere.empty() || !std::isfinite(sphere.radius)) throw InputError("scene", "no geometry");

  const glm::vec3 centre = sphere.centre;
  // A single point has no extent; give it one so the projection stays well-defined.
  const float radius = std::max(sphere.radius, 1e-6f * (1.0f + glm::length(centre)));
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const float half_vfov = glm::radians(params.fov_deg) * 0.5f;
  const float half_hfov = std::atan(std::tan(half_vfov) * aspect);

  // The sphere's silhouette is a cone of half-angle asin(r / d) around the view axis: it fits
  // when that angle is within both half fields of view.
  float distance = params.distance;
  if (distance == 0.0f) distance = radius * kMargin / std::sin(std::min(half_vfov, half_hfov));

  const float az = glm::radians(params.azimuth_deg);
  const float el = glm::radians(params.elevation_deg);
  const glm::vec3 dir(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));

  Camera cam;
  cam.width = width;
  cam.height = height;
  cam.ortho = params.ortho;
  cam.eye = centre + distance * dir;
  cam.view = glm::lookAt(cam.eye, centre, glm::vec3(0.0f, 1.0f, 0.0f));
  // Near/far hug the bounding sphere; when the eye is inside it, near is kept at 1/1000 of
  // far so the 32-bit float depth buffer keeps its precision.
  cam.far_plane = distance + radius * kMargin;
  cam.near_plane = std::max(distance - radius * kMargin, cam.far_plane * 1e-3f);
  if (params.ortho) {
    // The sphere fits both the height and the width (portrait images too).
    const float half_h = radius * kMargin * std::max(1.0f, 1.0f / aspect);
    const float half_w = half_h * aspect;
    cam.proj = glm::ortho(-half_w, half_w, -half_h, half_h, cam.near_plane, cam.far_plane);
  } else {
    cam.proj = glm::perspective(2.0f * half_vfov, aspect, cam.near_plane, cam.far_plane);
  }
  return cam;
}

Camera make_file_camera(const SceneCamera& file, const Sphere& sphere, int width, int height) {
  validate(OrbitParams{}, width, height);
  Camera cam;
  cam.width = width;
  cam.height = height;
  cam.ortho = file.orthographic;
  cam.view = glm::inverse(file.to_world);
  cam.eye = glm::vec3(file.to_world[3]);
  cam.near_plane = file.znear;
  cam.far_plane = file.zfar;
  if (cam.far_plane <= 0.0f) {
    const float reach =
        sphere.empty() ? 0.0f : glm::length(sphere.centre - cam.eye) + sphere.radius;
    cam.far_plane = std::max(reach * kMargin, 2.0f * cam.near_plane);
  }
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  if (cam.ortho) {
    const float half_h = file.ymag, half_w = half_h * aspect;
    cam.proj = glm::ortho(-half_w, half_w, -half_h, half_h, cam.near_plane, cam.far_plane);
  } else {
    cam.proj = glm::perspective(file.yfov, aspect, cam.near_plane, cam.far_plane);
  }
  return cam;
}

Camera make_light_camera(const Sphere& sphere, const glm::vec3& toward_light, bool point, int size,
                         const Sphere& casters) {
  SYLVA_CHECK(size >= 1 && size <= kMaxImageSide, "make_light_camera: bad size");
  SYLVA_CHECK(!sphere.empty() && std::isfinite(sphere.radius), "make_light_camera: no sphere");
  const glm::vec3 centre = sphere.centre;
  const float radius = std::max(sphere.radius, 1e-6f * (1.0f + glm::length(centre))) * kMargin;
  Camera cam;
  cam.width = cam.height = size;
  glm::vec3 dir;  // from the centre toward the eye
  float distance;
  if (point) {
    dir = toward_light - centre;
    distance = glm::length(dir);
    dir = distance > 1e-6f * radius ? dir / distance : glm::vec3(0, 1, 0);
  } else {
    const float len = glm::length(toward_light);
    SYLVA_CHECK(len > 0.0f && std::isfinite(len), "make_light_camera: no light direction");
    dir = toward_light / len;
    distance = 2.0f * radius;
  }
  // How far toward the light the casters reach beyond the centre.
  float reach = radius;
  if (!point && !casters.empty())
    reach = std::max(reach, glm::dot(casters.centre - centre, dir) + casters.radius * kMargin);
  if (!point) distance = std::max(distance, reach + radius);
  const glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  cam.eye = centre + distance * dir;
  cam.view = glm::lookAt(cam.eye, centre, up);
  cam.far_plane = distance + radius;
  cam.near_plane = std::max(distance - (point ? radius : reach), cam.far_plane * 1e-3f);
  if (point) {
    cam.ortho = false;
    const float half = distance > radius ? std::asin(radius / distance) : glm::radians(75.0f);
    cam.proj = glm::perspective(2.0f * half, 1.0f, cam.near_plane, cam.far_plane);
  } else {
    cam.ortho = true;
    cam.proj = glm::ortho(-radius, radius, -radius, radius, cam.near_plane, cam.far_plane);
  }
  return cam;
}

}  // namespace sylva

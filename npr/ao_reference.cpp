#include "npr/ao_reference.h"

#include <embree3/rtcore.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/random.h"

namespace sylva {
namespace {

// Rays traced per rtcOccluded1M call: a stream long enough for Embree to reorder, short
// enough to live on the stack.
constexpr int kRayChunk = 64;
constexpr double kInvGolden = 0.6180339887498949;  // 1 / golden ratio

bool finite3(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Orthonormal basis around a unit vector (Duff et al. 2017, "Building an orthonormal basis,
// revisited"): branch-free and continuous except at n.z = -0.
void basis(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double c = n.x * n.y * a;
  t = glm::dvec3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::dvec3(c, sign + n.y * n.y * a, -n.y);
}

void occlusion_filter(const RTCFilterFunctionNArguments* args) {
  const AoHitFilter& filter = *static_cast<const AoHitFilter*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
    const float u = RTCHitN_u(args->hit, args->N, i);
    const float v = RTCHitN_v(args->hit, args->N, i);
    bool blocks = true;
    try {
      blocks = filter(prim, u, v);
    } catch (...) {
      blocks = true;  // documented: an exception counts as a blocking hit
    }
    if (!blocks) args->valid[i] = 0;
  }
}

void error_callback(void* user, RTCError code, const char* message) {
  auto* first = static_cast<std::string*>(user);
  if (first->empty())
    *first = "embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
}

}  // namespace

struct AoReferenceScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  AoHitFilter filter;
  std::string error;
  size_t triangles = 0;
  float offset = 0.0f;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

AoHitFilter make_alpha_cutout_filter(std::vector<glm::vec2> uvs, std::vector<uint32_t> indices,
                                     std::function<float(uint32_t triangle, glm::vec2 uv)> alpha,
                                     float cutoff,
                                     std::function<bool(uint32_t triangle)> is_cutout) {
  SYLVA_CHECK(indices.size() % 3 == 0, "alpha cutout: 3 indices per triangle");
  for (uint32_t i : indices)
    SYLVA_CHECK(i < uvs.size(), "alpha cutout: uv index in range");
  SYLVA_CHECK(bool(alpha), "alpha cutout needs an alpha lookup");
  return [uvs = std::move(uvs), indices = std::move(indices), alpha = std::move(alpha), cutoff,
          is_cutout = std::move(is_cutout)](uint32_t t, float u, float v) {
    if (size_t(t) * 3 + 2 >= indices.size()) return true;
    if (is_cutout && !is_cutout(t)) return true;
    const glm::vec2 uv = (1.0f - u - v) * uvs[indices[3 * size_t(t)]] +
                         u * uvs[indices[3 * size_t(t) + 1]] + v * uvs[indices[3 * size_t(t) + 2]];
    return alpha(t, uv) >= cutoff;
  };
}

void validate_ao_reference(const AoReferenceOptions& options) {
  if (options.rays < 1 || options.rays > 4096)
    throw InputError("ao-rays", "must be in [1, 4096], got " + std::to_string(options.rays));
  if (!(std::isfinite(options.origin_offset) && options.origin_offset >= 0.0f)) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", double(options.origin_offset));
    throw InputError("ao-origin-offset",
                     std::string("must be finite and >= 0 (scene units; 0 = auto), got ") + buf);
  }
  if (options.threads < 0 || options.threads > 1024)
    throw InputError("ao-threads", "must be in [0, 1024], got " + std::to_string(options.threads));
}

AoReferenceScene::AoReferenceScene(const std::vector<glm::vec3>& positions,
                                   const std::vector<uint32_t>& indices, AoHitFilter filter)
    : m_impl(std::make_unique<Impl>()) {
  SYLVA_CHECK(indices.size() % 3 == 0, "AoReferenceScene: 3 indices per triangle");
  for (uint32_t i : indices)
    SYLVA_CHECK(i < positions.size(), "AoReferenceScene: index in range");
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  float largest = 0.0f;
  for (size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3& p = positions[i];
    if (!finite3(p)) throw InputError("scene", "vertex " + std::to_string(i) + " is not finite");
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
    largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  }
  const float diagonal = positions.empty() ? 0.0f : glm::length(hi - lo);
  m_impl->offset = 1e-5f * (diagonal + largest);
  m_impl->triangles = indices.size() / 3;
  m_impl->filter = std::move(filter);

  Impl& im = *m_impl;
  im.device = rtcNewDevice(nullptr);
  if (!im.device) throw std::runtime_error("embree: cannot create a device");
  rtcSetDeviceErrorFunction(im.device, error_callback, &im.error);
  im.scene = rtcNewScene(im.device);
  rtcSetSceneBuildQuality(im.scene, RTC_BUILD_QUALITY_MEDIUM);
  if (im.triangles > 0) {
    RTCGeometry geom = rtcNewGeometry(im.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree-allocated buffers come padded (Embree reads 16 bytes at the last vertex).
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), positions.size()));
    auto* t = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), im.triangles));
    if (v && t) {
      for (size_t i = 0; i < positions.size(); ++i)
        for (int c = 0; c < 3; ++c)
          v[3 * i + size_t(c)] = positions[i][c];
      std::copy(indices.begin(), indices.end(), t);
    }
    if (im.filter) {
      rtcSetGeometryUserData(geom, &im.filter);
      rtcSetGeometryOccludedFilterFunction(geom, occlusion_filter);
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(im.scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(im.scene);
  if (!im.error.empty()) throw std::runtime_error(im.error);
}

AoReferenceScene::~AoReferenceScene() = default;
AoReferenceScene::AoReferenceScene(AoReferenceScene&&) noexcept = default;
AoReferenceScene& AoReferenceScene::operator=(AoReferenceScene&&) noexcept = default;

size_t AoReferenceScene::triangle_count() const {
  return m_impl->triangles;
}

float AoReferenceScene::auto_origin_offset() const {
  return m_impl->offset;
}

float AoReferenceScene::visibility_at(const glm::vec3& point, const glm::vec3& normal,
                                      const AoReferenceOptions& options, uint64_t stream) const {
  validate_ao_reference(options);
  if (!finite3(point)) return 1.0f;
  if (m_impl->triangles == 0) return 1.0f;

  const double eps = options.origin_offset > 0.0f ? options.origin_offset : m_impl->offset;
  glm::dvec3 n(normal);
  const double m = finite3(normal) ? std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)}) : 0;
  const bool hemisphere = m > 0.0;
  glm::dvec3 t(1, 0, 0), b(0, 1, 0);
  if (hemisphere) {
    n /= m;
    n /= glm::length(n);
    basis(n, t, b);
  } else {
    n = glm::dvec3(0, 0, 1);
  }
  const glm::dvec3 origin = glm::dvec3(point) + (hemisphere ? eps : 0.0) * n;

  // The point's own random stream: the key mixes the seed and the stream index.
  uint64_t key = options.seed;
  uint64_t mixed = splitmix64(key) ^ (stream * 0xd1b54a32d192ed03ull);
  uint64_t rng = splitmix64(mixed);
  const double shift = uniform01(rng);
  const int rays = options.rays;

  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay chunk[kRayChunk];
  int escaped = 0;
  for (int first = 0; first < rays; first += kRayChunk) {
    const int count = std::min(kRayChunk, rays - first);
    for (int k = 0; k < count; ++k) {
      const int j = first + k;
      const double u1 = (double(j) + uniform01(rng)) / double(rays);
      double u2 = double(j) * kInvGolden + shift;
      u2 -= std::floor(u2);
      const double z = hemisphere ? u1 : 2.0 * u1 - 1.0;
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = 2.0 * std::numbers::pi * u2;
      const glm::dvec3 d = r * std::cos(phi) * t + r * std::sin(phi) * b + z * n;
      RTCRay& ray = chunk[k];
      ray.org_x = float(origin.x);
      ray.org_y = float(origin.y);
      ray.org_z = float(origin.z);
      ray.tnear = float(eps);
      ray.dir_x = float(d.x);
      ray.dir_y = float(d.y);
      ray.dir_z = float(d.z);
      ray.time = 0.0f;
      ray.tfar = std::numeric_limits<float>::infinity();
      ray.mask = 0xffffffffu;
      ray.id = unsigned(j);
      ray.flags = 0;
    }
    rtcOccluded1M(m_impl->scene, &context, chunk, unsigned(count), sizeof(RTCRay));
    for (int k = 0; k < count; ++k)
      if (chunk[k].tfar >= 0.0f) ++escaped;  // occluded rays come back with tfar = -inf
  }
  return float(escaped) / float(rays);
}

std::vector<float> AoReferenceScene::visibility(const std::vector<glm::vec3>& points,
                                                const std::vector<glm::vec3>& normals,
                                                const AoReferenceOptions& options) const {
  validate_ao_reference(options);
  SYLVA_CHECK(points.size() == normals.size(), "one normal per point");
  std::vector<float> out(points.size(), 1.0f);
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  const long long n = (long long)points.size();
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
  for (long long i = 0; i < n; ++i)
    out[size_t(i)] = visibility_at(points[size_t(i)], normals[size_t(i)], options, uint64_t(i));
  return out;
}

}  // namespace sylva

#include "npr/ambient.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"

namespace sylva {

namespace {

// Enough digits to tell 1.0 from 1.0000001 and to show 1e-30 as such.
std::string format_value(float v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.9g", static_cast<double>(v));
  return buf;
}

}  // namespace

void validate_ambient(const AmbientParams& params) {
  // Written as negated acceptance tests so that NaN is rejected too.
  if (!(params.ka_min >= 0.0f && params.ka_min <= 1.0f)) {
    throw InputError("ka-min", "must be in [0, 1], got " + format_value(params.ka_min));
  }
  if (!(std::isfinite(params.d_min) && params.d_min > 0.0f)) {
    throw InputError("d-min", "must be finite and > 0, got " + format_value(params.d_min));
  }
  if (!(std::isfinite(params.exponent) && params.exponent > 0.0f && params.exponent <= 100.0f)) {
    throw InputError("exponent", "must be in (0, 100], got " + format_value(params.exponent));
  }
}

float ambient_transfer(float d, const AmbientParams& params) {
  const float ka_min = params.ka_min;
  // Luft et al. Eq. 4. NaN d counts as 0 (no density: fully lit), which `!(d > 0)` covers;
  // -Inf lands here too.
  if (!(d > 0.0f)) return 1.0f;
  if (d >= params.d_min) return ka_min;  // also +Inf
  // In double: d / d_min stays in (0, 1) even for d_min = 1e-30 (no overflow, no denormal
  // trouble), and pow of a base in (0, 1] with exponent in (0, 100] is in [0, 1].
  const double t = 1.0 - static_cast<double>(d) / static_cast<double>(params.d_min);
  const double p = std::pow(t, static_cast<double>(params.exponent));
  const double ka = ka_min + (1.0 - static_cast<double>(ka_min)) * p;
  // Rounding to float cannot leave [ka_min, 1] (both ends are floats), but the range is a
  // promise to every caller, so it is enforced rather than argued.
  return std::min(1.0f, std::max(ka_min, static_cast<float>(ka)));
}

glm::vec3 encode_ka(const glm::vec3& unit_normal, float ka) {
  const float len = glm::length(unit_normal);
  SYLVA_CHECK(std::isfinite(len) && len > 0.0f, "encode_ka needs a finite, non-zero normal");
  // NaN ka is stored as the floor: the smallest, most conservative ambient term, and it keeps
  // the direction (a zero-length normal would lose it).
  float k = std::isnan(ka) ? kKaFloor : std::clamp(ka, 0.0f, 1.0f);
  k = std::max(k, kKaFloor);
  // Re-normalising makes |result| == k even for slightly non-unit inputs.
  // Luft et al. §3.2: "the normal vector of each vertex is scaled by the corresponding
  // ambient reflection coefficient".
  return unit_normal * (k / len);
}

EncodingBias normal_length_interpolation_bias(const std::vector<glm::vec3>& unit_normals,
                                              const std::vector<float>& ka,
                                              const std::vector<uint32_t>& triangles,
                                              int samples_per_triangle) {
  SYLVA_CHECK(unit_normals.size() == ka.size(), "one ka per normal");
  SYLVA_CHECK(triangles.size() % 3 == 0, "triangles hold 3 indices each");
  SYLVA_CHECK(samples_per_triangle >= 1, "at least one sample per triangle");
  for (uint32_t i : triangles)
    SYLVA_CHECK(i < unit_normals.size(), "triangle index in range");

  // The fixed sample pattern: Roberts' R2 sequence (plastic number), folded into the
  // triangle. Deterministic, exactly samples_per_triangle points, well spread for any count.
  const double g = 1.32471795724474602596;  // plastic number
  const double a1 = 1.0 / g;
  const double a2 = 1.0 / (g * g);
  std::vector<glm::dvec3> bary(static_cast<size_t>(samples_per_triangle));
  for (size_t s = 0; s < bary.size(); ++s) {
    double u = std::fmod(0.5 + a1 * static_cast<double>(s), 1.0);
    double v = std::fmod(0.5 + a2 * static_cast<double>(s), 1.0);
    if (u + v > 1.0) {
      u = 1.0 - u;
      v = 1.0 - v;
    }
    bary[s] = glm::dvec3(1.0 - u - v, u, v);
  }

  EncodingBias out;
  double sum = 0.0;
  double sum_abs = 0.0;
  const size_t tri_count = triangles.size() / 3;
  for (size_t t = 0; t < tri_count; ++t) {
    glm::dvec3 enc[3];
    double k[3];
    for (int c = 0; c < 3; ++c) {
      const uint32_t vi = triangles[3 * t + c];
      enc[c] = glm::dvec3(encode_ka(unit_normals[vi], ka[vi]));
      k[c] = glm::length(enc[c]);  // the ka the encoding represents (clamped, floored)
    }
    for (const glm::dvec3& b : bary) {
      const glm::dvec3 n = b.x * enc[0] + b.y * enc[1] + b.z * enc[2];
      const double decoded = std::clamp(glm::length(n), 0.0, 1.0);
      const double interpolated = b.x * k[0] + b.y * k[1] + b.z * k[2];
      const double err = interpolated - decoded;
      sum += err;
      sum_abs += std::abs(err);
      out.max_abs_error = std::max(out.max_abs_error, std::abs(err));
    }
  }
  out.sample_count = tri_count * bary.size();
  if (out.sample_count > 0) {
    out.mean_error = sum / static_cast<double>(out.sample_count);
    out.mean_abs_error = sum_abs / static_cast<double>(out.sample_count);
  }
  return out;
}

}  // namespace sylva

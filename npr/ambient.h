// The ambient coefficient of Luft et al. §3.2: ka from the density d_v = F(v) by the
// transfer function of Eq. 4, and its encoding in the length of the normal, which the
// renderer decodes (core/gl shaders: ka = |N|, N re-normalised).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace sylva {

struct AmbientParams {
  float ka_min = 0.2f;    // ka for densities >= d_min, [0, 1]
  float d_min = 1.0f;     // density where ka reaches ka_min, > 0 (density units: sum of kernels)
  float exponent = 1.0f;  // n in Eq. 4, > 0 (n < 1 darkens slowly, n > 1 quickly); <= 100
};

// Throws InputError("ka-min" / "d-min" / "exponent", ...) naming the allowed range.
void validate_ambient(const AmbientParams& params);

// Eq. 4: 1 for d <= 0; ka_min + (1 - ka_min) (1 - d / d_min)^n for 0 < d < d_min; ka_min
// above. Always in [ka_min, 1] and finite (NaN d counts as 0).
float ambient_transfer(float d, const AmbientParams& params);

// The smallest normal length written: a ka of 0 keeps the direction. Decoding clamps to
// [0, 1], so ka below the floor reads back as the floor.
inline constexpr float kKaFloor = 1.0f / 1024.0f;

// unit_normal * max(ka, kKaFloor), ka clamped to [0, 1].
glm::vec3 encode_ka(const glm::vec3& unit_normal, float ka);

// What storing ka as |N| costs under interpolation: the rasteriser interpolates the encoded
// normals linearly, so a renderer decoding ka = |N| per fragment reads the length of the
// interpolated vector, while a separate attribute gives the interpolated ka. By the triangle
// inequality decoded <= interpolated; the gap grows with the angle between the normals.
struct EncodingBias {
  double mean_error = 0;      // mean of (interpolated - decoded), >= 0
  double mean_abs_error = 0;  // mean of |interpolated - decoded|
  double max_abs_error = 0;   // largest |interpolated - decoded|
  size_t sample_count = 0;    // triangles x samples_per_triangle
};

// Samples each triangle at samples_per_triangle (>= 1) fixed barycentric points (the same
// deterministic pattern for every triangle; triangles weigh equally, not by area). ka is
// encoded by encode_ka (so clamped and floored) and compared in double precision.
// unit_normals and ka have one entry per vertex; triangles holds vertex indices, 3 per
// triangle. Size mismatches and out-of-range indices are programming errors (SYLVA_CHECK).
EncodingBias normal_length_interpolation_bias(const std::vector<glm::vec3>& unit_normals,
                                              const std::vector<float>& ka,
                                              const std::vector<uint32_t>& triangles,
                                              int samples_per_triangle);

}  // namespace sylva

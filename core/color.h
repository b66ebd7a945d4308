// The sRGB transfer functions (IEC 61966-2-1), shared by the renderer, the image passes and
// colour parameters: images are stored sRGB-encoded, blending happens in linear light.
#pragma once

#include <algorithm>
#include <cmath>

namespace sylva {

inline float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Clamps to [0, 1] first.
inline float linear_to_srgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace sylva

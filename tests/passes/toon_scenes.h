// Synthetic G-buffers for the toon tests (test_toon.cpp, test_toon_lights.cpp): an N·L ramp,
// a shaded sphere, a plane, a square shadow map, and sRGB helpers.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "core/gl/lights.h"
#include "passes/toon.h"

namespace sylva::test {

constexpr float kPi = 3.14159265358979f;
inline const cv::Vec4b kAlbedo(60, 170, 120, 255);  // BGRA sRGB, a leaf green

float decode(uint8_t v);    // sRGB byte -> linear
uint8_t encode(float lin);  // linear (clamped to [0, 1]) -> sRGB byte

// One directional light along view +Z (toward the viewer), camera-fixed.
Lighting headlight();

// Normals sweeping from facing away from +Z (x = 0) to facing it (x = width - 1):
// N·L = cos(theta), theta = pi (1 - (x + 0.5) / width), so N·L rises monotonically.
ToonImages ramp(int width = 400, int height = 4, float ka = 1.0f);

// First pixel where N·L = cos(theta(x)) >= t on the ramp.
int ramp_crossing(float t, int width = 400);

struct BandRun {
  int start;
  cv::Vec4b color;
};

// The runs of equal colour along a row.
std::vector<BandRun> runs(const cv::Mat& img, int row = 0);

// A unit sphere seen head-on, with analytic normals, 4x4-sample coverage (colour
// premultiplied by coverage in linear light, as the raster pass leaves it), view-space
// positions at distance 5 and a ka darkening toward the bottom, as under a crown.
ToonImages sphere(int size = 160, cv::Vec4b albedo = kAlbedo);

// Shadow map of a plane at light depth 10 seen by an orthographic light camera at z = 10
// looking down -Z over [-1, 1]^2, with a square occluder at depth 5 over texels 8..23.
ToonShadowMap square_shadow_map(bool occluder = true);

// The view-space plane z = -slope x over [-1, 1]^2 (64 x 64 px), facing +Z, with the
// identity view so world = view space.
ToonImages plane(float slope = 0.0f);

bool all_finite(const cv::Mat& m);

}  // namespace sylva::test

// Shared arithmetic of the watercolor pass (passes/watercolor.h): the colour curves its parts
// work in (sRGB display values, linear light and optical density, as interpolated tables),
// and two small image helpers. Pure functions; they read only their arguments (the tables are
// built once, on first use, and never change).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <opencv2/core.hpp>
#include <vector>

#include "passes/pass_common.h"

namespace sylva::watercolor_internal {

constexpr float kSqrt2Pi = 2.50662827f;
constexpr int kEncodeSize = 16384;
constexpr int kCurveSize = 4096;
// Optical density of black pigment (transmittance 2^-12), which keeps black finite.
constexpr float kMaxDensity = 12.0f;

struct SrgbTables {
  std::array<float, 256> to_linear;
  std::vector<uint8_t> from_linear;   // kEncodeSize + 1 entries over [0, 1]
  std::vector<float> encode, decode;  // kCurveSize + 2 entries over [0, 1], interpolated
  std::vector<float> density;         // display value -> -log2(linear), <= kMaxDensity
};

const SrgbTables& srgb_tables();

inline uint8_t encode_srgb(const SrgbTables& t, float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return t.from_linear[size_t(c * float(kEncodeSize) + 0.5f)];
}

inline float curve(const std::vector<float>& table, float v) {
  const float x = std::clamp(v, 0.0f, 1.0f) * float(kCurveSize);
  const int i = int(x);
  const float f = x - float(i);
  return table[size_t(i)] + (table[size_t(i) + 1] - table[size_t(i)]) * f;
}
// Bousseau's modulations act on display values (his shaders work on the 8-bit image), where
// they look even across dark and light pigments. Coverage and glazing act on optical density
// (-log2 of the linear transmittance): a half-covered wash has half the density (Beer-Lambert),
// so a dilute wash keeps its hue instead of greying towards the paper, and glazes add.
inline float to_display(const SrgbTables& t, float linear) {
  return curve(t.encode, linear);
}
inline float to_linear(const SrgbTables& t, float display) {
  return curve(t.decode, display);
}
inline float to_density(const SrgbTables& t, float display) {
  return curve(t.density, display);
}

inline float luminance(const cv::Vec3f& bgr) {
  return 0.0722f * bgr[0] + 0.7152f * bgr[1] + 0.2126f * bgr[2];
}

// Bilinear lookup in a single-channel float image, clamped to its border.
inline float sample(const cv::Mat& m, float x, float y) {
  x = std::clamp(x, 0.0f, float(m.cols - 1));
  y = std::clamp(y, 0.0f, float(m.rows - 1));
  const int ix = std::min(int(x), m.cols - 2 < 0 ? 0 : m.cols - 2);
  const int iy = std::min(int(y), m.rows - 2 < 0 ? 0 : m.rows - 2);
  const float fx = x - float(ix), fy = y - float(iy);
  const int ix1 = std::min(ix + 1, m.cols - 1), iy1 = std::min(iy + 1, m.rows - 1);
  const float* r0 = m.ptr<float>(iy);
  const float* r1 = m.ptr<float>(iy1);
  const float a = r0[ix] + (r0[ix1] - r0[ix]) * fx;
  const float b = r1[ix] + (r1[ix1] - r1[ix]) * fx;
  return a + (b - a) * fy;
}

// A field kept at a reduced resolution (`m`, CV_32FC1) read at pixel (x, y) of an image of
// `size`: bilinear, as cv::resize's INTER_LINEAR samples it.
inline float sample_at(const cv::Mat& m, cv::Size size, int x, int y) {
  const float fx = float(m.cols) / float(size.width), fy = float(m.rows) / float(size.height);
  return sample(m, (float(x) + 0.5f) * fx - 0.5f, (float(y) + 0.5f) * fy - 0.5f);
}

// How much a glazed optical density (CV_32FC3 pixel) counts as paint, in [0, 1]: a wash whose
// channels' densities sum to kCoveringDensity or more covers the paper.
constexpr float kCoveringDensity = 1.5f;
inline float wash_cover(const cv::Vec3f& d) {
  return std::min(1.0f, (d[0] + d[1] + d[2]) / kCoveringDensity);
}

// Where a pixel's view-space position comes from: the position buffer (CV_32FC3), or, where it
// is empty, the pixel's centre at its linear view depth (the depth target's meaning: distance
// along -Z) unprojected through the frame's projection `proj` (perspective or orthographic).
// The same point without a full-size buffer of them (at 4096² the position target costs
// 0.45 GB between the GL framebuffer and its read-back).
struct ViewPositions {
  cv::Mat position;  // CV_32FC3 or empty
  cv::Mat depth;     // CV_32FC1, 0 = background
  glm::mat4 proj{1.0f};
};

// The mean view-space position (CV_32FC3) of the covered pixels (depth > 0) of each cell of
// `cell` x `cell` px (the grid rounds up), and the share of the cell they cover (CV_32FC1);
// (0, 0, 0) and 0 where none. Read row by row: no full-size copy is made.
struct CellPositions {
  cv::Mat mean, cover;
};
CellPositions cell_positions(const ViewPositions& view, int cell);

// Gaussian blur with sigma in px (border replicated); below 0.3 px a copy.
cv::Mat blur(const cv::Mat& m, float sigma);

}  // namespace sylva::watercolor_internal

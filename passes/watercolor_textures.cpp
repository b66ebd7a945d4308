#include "passes/watercolor_textures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/io/image_io.h"
#include "core/scene/scene_length.h"
#include "passes/pass_common.h"
#include "passes/watercolor_common.h"

namespace sylva {

namespace watercolor_internal {

namespace {

// Contrast of the normalised textures: standard deviation around 0.5.
constexpr float kTextureStd = 0.18f;

// --- World-space value noise (turbulence) -------------------------------------------------

inline uint32_t hash3(int32_t x, int32_t y, int32_t z, uint32_t seed) {
  uint32_t h = seed * 0x9E3779B9u;
  h ^= uint32_t(x) * 0x85EBCA6Bu;
  h = (h << 13) | (h >> 19);
  h ^= uint32_t(y) * 0xC2B2AE35u;
  h = (h << 13) | (h >> 19);
  h ^= uint32_t(z) * 0x27D4EB2Fu;
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  h *= 0x846CA68Bu;
  h ^= h >> 16;
  return h;
}

inline float lattice(int32_t x, int32_t y, int32_t z, uint32_t seed) {
  return float(hash3(x, y, z, seed) >> 8) * (1.0f / 16777216.0f);
}

inline float fade(float t) {
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

float value_noise3(const glm::vec3& p, uint32_t seed) {
  const glm::vec3 f = glm::floor(p);
  const int32_t x = int32_t(f.x), y = int32_t(f.y), z = int32_t(f.z);
  const float u = fade(p.x - f.x), v = fade(p.y - f.y), w = fade(p.z - f.z);
  auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
  const float c00 = lerp(lattice(x, y, z, seed), lattice(x + 1, y, z, seed), u);
  const float c10 = lerp(lattice(x, y + 1, z, seed), lattice(x + 1, y + 1, z, seed), u);
  const float c01 = lerp(lattice(x, y, z + 1, seed), lattice(x + 1, y, z + 1, seed), u);
  const float c11 = lerp(lattice(x, y + 1, z + 1, seed), lattice(x + 1, y + 1, z + 1, seed), u);
  return lerp(lerp(c00, c10, v), lerp(c01, c11, v), w);
}

// Three fixed octaves, stretched so the result spans [0, 1] with about kTextureStd.
float turbulence_fbm(const glm::vec3& p, uint32_t seed) {
  float sum = 0.0f, amp = 1.0f, total = 0.0f;
  glm::vec3 q = p;
  for (int o = 0; o < 3; ++o) {
    sum += amp * value_noise3(q, seed + uint32_t(o) * 101u);
    total += amp;
    amp *= 0.5f;
    // A rotation-free offset between octaves keeps their lattices from lining up.
    q = q * 2.03f + glm::vec3(17.1f, 5.3f, 11.7f);
  }
  // Measured: the three-octave sum has a standard deviation of about 0.14 around 0.5.
  return std::clamp(0.5f + (sum / total - 0.5f) * (kTextureStd / 0.14f), 0.0f, 1.0f);
}

// --- Paper -------------------------------------------------------------------------------

cv::Mat normalise_texture(const cv::Mat& t) {
  cv::Scalar mean, stddev;
  cv::meanStdDev(t, mean, stddev);
  cv::Mat out;
  const double s = stddev[0] > 1e-9 ? kTextureStd / stddev[0] : 0.0;
  t.convertTo(out, CV_32F, s, 0.5 - mean[0] * s);
  cv::min(cv::max(out, 0.0), 1.0, out);
  return out;
}

// Fine grain dominates, coarser octaves give the mottled sizing of real paper.
constexpr int kOctaves = 5;
constexpr std::array<float, kOctaves> kAmplitude{1.0f, 0.8f, 0.45f, 0.3f, 0.25f};

float value_noise2(float x, float y, uint32_t seed) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int32_t ix = int32_t(fx), iy = int32_t(fy);
  const float u = fade(x - fx), v = fade(y - fy);
  auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
  return lerp(lerp(lattice(ix, iy, 0, seed), lattice(ix + 1, iy, 0, seed), u),
              lerp(lattice(ix, iy + 1, 0, seed), lattice(ix + 1, iy + 1, 0, seed), u), v);
}

// The gradient of value_noise2 at (x, y), analytically (the quintic fade's derivative).
cv::Vec2f value_noise2_gradient(float x, float y, uint32_t seed) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int32_t ix = int32_t(fx), iy = int32_t(fy);
  const float tx = x - fx, ty = y - fy;
  const float u = fade(tx), v = fade(ty);
  auto dfade = [](float t) { return 30.0f * t * t * (t * (t - 2.0f) + 1.0f); };
  const float a = lattice(ix, iy, 0, seed), b = lattice(ix + 1, iy, 0, seed);
  const float c = lattice(ix, iy + 1, 0, seed), d = lattice(ix + 1, iy + 1, 0, seed);
  return {dfade(tx) * ((b - a) + (a - b - c + d) * v), dfade(ty) * ((c - a) + (a - b - c + d) * u)};
}

// The grey-scale paper image at 1 image px per px at 1024 px, in [0, 1].
cv::Mat loaded_tile(const WatercolorParams& p, double scale) {
  cv::Mat img = read_image(p.paper);  // InputError(path, ...) when unreadable
  if (img.empty()) throw InputError(p.paper, "watercolor.paper: the image is empty");
  cv::Mat grey;
  if (img.channels() == 1) {
    grey = img;
  } else if (img.channels() == 3) {
    cv::cvtColor(img, grey, cv::COLOR_BGR2GRAY);
  } else if (img.channels() == 4) {
    cv::cvtColor(img, grey, cv::COLOR_BGRA2GRAY);
  } else {
    throw InputError(p.paper, "watercolor.paper: expected a grey, BGR or BGRA image");
  }
  cv::Mat f;
  const double depth_max = grey.depth() == CV_8U ? 255.0 : grey.depth() == CV_16U ? 65535.0 : 1.0;
  grey.convertTo(f, CV_32F, 1.0 / depth_max);
  if (std::abs(scale - 1.0) > 1e-9) {
    const cv::Size scaled(std::max(1, int(std::lround(f.cols * scale))),
                          std::max(1, int(std::lround(f.rows * scale))));
    cv::resize(f, f, scaled, 0, 0, scale < 1.0 ? cv::INTER_AREA : cv::INTER_CUBIC);
  }
  return normalise_texture(f);
}

// Bilinear in a tiled image at continuous position (x, y).
float tiled(const cv::Mat& m, float x, float y) {
  const float fx = x - 0.5f, fy = y - 0.5f;
  const float x0 = std::floor(fx), y0 = std::floor(fy);
  const float ax = fx - x0, ay = fy - y0;
  auto at = [&m](float xx, float yy) {
    const int i = int(std::fmod(std::fmod(xx, float(m.cols)) + float(m.cols), float(m.cols)));
    const int j = int(std::fmod(std::fmod(yy, float(m.rows)) + float(m.rows), float(m.rows)));
    return m.at<float>(std::min(j, m.rows - 1), std::min(i, m.cols - 1));
  };
  return (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x0 + 1, y0)) +
         ay * ((1 - ax) * at(x0, y0 + 1) + ax * at(x0 + 1, y0 + 1));
}

}  // namespace

PaperField::PaperField(const WatercolorParams& p, double scale)
    : m_period(std::max(1.0, p.grain * scale)), m_seed(uint32_t(p.seed) * 7919u + 1u) {
  if (p.paper != "generated") {
    m_tile = loaded_tile(p, scale);
    // The slope of the tile blurred, wrapping around its edges (padded by a wrapped border,
    // since OpenCV's filters do not wrap).
    const double sigma = std::max(0.3, 0.75 * p.grain * scale);
    const int pad = int(std::ceil(3.0 * sigma)) + 2;
    cv::Mat padded, smooth, gx, gy;
    cv::copyMakeBorder(m_tile, padded, pad, pad, pad, pad, cv::BORDER_WRAP);
    cv::GaussianBlur(padded, smooth, {0, 0}, sigma);
    cv::Sobel(smooth, gx, CV_32F, 1, 0, 3, 0.125);
    cv::Sobel(smooth, gy, CV_32F, 0, 1, 3, 0.125);
    const cv::Rect tile(pad, pad, m_tile.cols, m_tile.rows);
    m_gx = gx(tile).clone();
    m_gy = gy(tile).clone();
    return;
  }
  // The sum's mean and spread, measured once on a fixed grid of 64 x 64 points spread over
  // many lattice cells, so the relief has about kTextureStd whatever the grain.
  double sum = 0, sum2 = 0;
  constexpr int kGrid = 64;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const double v = raw(float((i + 0.37) * 5.3 * m_period), float((j + 0.61) * 5.3 * m_period));
      sum += v;
      sum2 += v * v;
    }
  const double n = kGrid * kGrid, mean = sum / n;
  const double sd = std::sqrt(std::max(1e-12, sum2 / n - mean * mean));
  m_mean = float(mean);
  m_gain = float(kTextureStd / sd);
}

float PaperField::coarse(float x, float y) const {
  float sum = 0.0f;
  for (int o = 1; o < kOctaves; ++o) {
    const float period = float(m_period) * float(1 << o);
    sum +=
        kAmplitude[size_t(o)] * value_noise2(x / period, y / period, m_seed + uint32_t(o) * 101u);
  }
  return sum;
}

float PaperField::raw(float x, float y) const {
  const float fine = kAmplitude[0] * value_noise2(x / float(m_period), y / float(m_period), m_seed);
  float total = 0.0f;
  for (float a : kAmplitude)
    total += a;
  return (fine + coarse(x, y)) / total;
}

float PaperField::relief(float x, float y) const {
  if (!m_tile.empty()) return tiled(m_tile, x, y);
  return std::clamp(0.5f + (raw(x, y) - m_mean) * m_gain, 0.0f, 1.0f);
}

cv::Vec2f PaperField::slope(float x, float y) const {
  if (!m_tile.empty()) return {tiled(m_gx, x, y), tiled(m_gy, x, y)};
  cv::Vec2f g(0.0f, 0.0f);
  for (int o = 1; o < kOctaves; ++o) {
    const float period = float(m_period) * float(1 << o);
    g += kAmplitude[size_t(o)] / period *
         value_noise2_gradient(x / period, y / period, m_seed + uint32_t(o) * 101u);
  }
  return g;
}

cv::Mat paper_relief(const PaperField& paper, const cv::Size& size) {
  SYLVA_CHECK(size.width > 0 && size.height > 0, "watercolor_paper: empty size");
  cv::Mat out(size, CV_32F);
  cv::parallel_for_(cv::Range(0, size.height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      float* o = out.ptr<float>(y);
      for (int x = 0; x < size.width; ++x)
        o[x] = paper.relief(float(x) + 0.5f, float(y) + 0.5f);
    }
  });
  return out;
}

}  // namespace watercolor_internal

cv::Mat watercolor_paper(const cv::Size& size, const WatercolorParams& p) {
  SYLVA_CHECK(size.width > 0 && size.height > 0, "watercolor_paper: empty size");
  return watercolor_internal::paper_relief(
      watercolor_internal::PaperField(p, reference_scale(size)), size);
}

cv::Mat watercolor_turbulence(const cv::Mat& position, const cv::Mat& depth,
                              const glm::mat4& view_to_world, const WatercolorParams& p) {
  expect_image(position, CV_32FC3, cv::Size(), "position");
  if (!depth.empty()) expect_image(depth, CV_32FC1, position.size(), "depth");
  auto covered = [&](int y, int x) {
    if (!depth.empty()) return depth.at<float>(y, x) > 0.0f;
    const cv::Vec3f& v = position.at<cv::Vec3f>(y, x);
    return v[0] != 0.0f || v[1] != 0.0f || v[2] != 0.0f;
  };
  double reference = p.reference_length;
  if (!(reference > 0.0)) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (int y = 0; y < position.rows; ++y)
      for (int x = 0; x < position.cols; ++x) {
        if (!covered(y, x)) continue;
        const cv::Vec3f& v = position.at<cv::Vec3f>(y, x);
        const glm::vec3 w = glm::vec3(view_to_world * glm::vec4(v[0], v[1], v[2], 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
      }
    reference = hi.x >= lo.x ? double(glm::length(hi - lo)) : 1.0;
    if (!(reference > 0.0)) reference = 1.0;
  }
  const double size = SceneLength::parse(p.turbulence_size, "watercolor.turbulence_size")
                          .resolve(reference, 0.06 * reference);
  const float inv = float(1.0 / size);
  const uint32_t seed = uint32_t(p.seed) * 2654435761u + 12345u;
  cv::Mat out(position.size(), CV_32F, cv::Scalar(0.5));
  cv::parallel_for_(cv::Range(0, position.rows), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      const cv::Vec3f* pos = position.ptr<cv::Vec3f>(y);
      float* o = out.ptr<float>(y);
      for (int x = 0; x < position.cols; ++x) {
        if (!covered(y, x)) continue;
        const glm::vec3 w =
            glm::vec3(view_to_world * glm::vec4(pos[x][0], pos[x][1], pos[x][2], 1.0f));
        o[x] = watercolor_internal::turbulence_fbm(w * inv, seed);
      }
    }
  });
  return out;
}

}  // namespace sylva

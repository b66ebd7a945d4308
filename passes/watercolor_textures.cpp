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

// Value-noise fBm: the coarser octaves are summed on the finest octave's lattice (one cell =
// one grain), then one cubic up-sampling takes the sum to pixels; the gradient comes from the
// lattice without the finest octave (the smoothed paper), up-sampled linearly.
Paper generated_paper(const cv::Size& size, const WatercolorParams& p, bool gradient) {
  const double period = std::max(1.0, p.grain * reference_scale(size));
  // Fine grain dominates, coarser octaves give the mottled sizing of real paper.
  constexpr int kOctaves = 5;
  constexpr std::array<float, kOctaves> kAmplitude{1.0f, 0.8f, 0.45f, 0.3f, 0.25f};
  const int gw = int(std::ceil(size.width / period)) + 4;
  const int gh = int(std::ceil(size.height / period)) + 4;
  auto random_grid = [&](int w, int h, int octave) {
    cv::Mat grid(h, w, CV_32F);
    cv::RNG rng(uint64_t(uint32_t(p.seed)) * 7919u + uint64_t(octave) * 104729u + 1u);
    rng.fill(grid, cv::RNG::UNIFORM, 0.0f, 1.0f);
    return grid;
  };
  cv::Mat coarse(gh, gw, CV_32F, cv::Scalar(0));
  for (int o = 1; o < kOctaves; ++o) {
    const int cell = 1 << o;
    const int w = gw / cell + 4, h = gh / cell + 4;
    cv::Mat up;
    cv::resize(random_grid(w, h, o), up, cv::Size(w * cell, h * cell), 0, 0, cv::INTER_CUBIC);
    // Skip the first cells, where the interpolation sees the border.
    coarse += kAmplitude[size_t(o)] * up(cv::Rect(cell, cell, gw, gh));
  }
  const cv::Mat lattice = coarse + kAmplitude[0] * random_grid(gw, gh, 0);
  const int off = int(std::floor(period));
  const cv::Size full(int(std::ceil(gw * period)), int(std::ceil(gh * period)));
  const cv::Rect crop(off, off, size.width, size.height);
  Paper out;
  cv::Mat up;
  cv::resize(lattice, up, full, 0, 0, cv::INTER_CUBIC);
  out.relief = normalise_texture(up(crop));
  if (gradient) {
    cv::Mat gx, gy;
    cv::Sobel(coarse, gx, CV_32F, 1, 0, 3, 0.125, 0, cv::BORDER_REPLICATE);
    cv::Sobel(coarse, gy, CV_32F, 0, 1, 3, 0.125, 0, cv::BORDER_REPLICATE);
    cv::resize(gx, up, full, 0, 0, cv::INTER_LINEAR);
    out.gx = up(crop).clone();
    cv::resize(gy, up, full, 0, 0, cv::INTER_LINEAR);
    out.gy = up(crop).clone();
  }
  return out;
}

cv::Mat loaded_paper(const cv::Size& size, const WatercolorParams& p) {
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
  const double scale = reference_scale(size);
  if (std::abs(scale - 1.0) > 1e-9) {
    const cv::Size scaled(std::max(1, int(std::lround(f.cols * scale))),
                          std::max(1, int(std::lround(f.rows * scale))));
    cv::resize(f, f, scaled, 0, 0, scale < 1.0 ? cv::INTER_AREA : cv::INTER_CUBIC);
  }
  const int nx = (size.width + f.cols - 1) / f.cols, ny = (size.height + f.rows - 1) / f.rows;
  cv::Mat tiled;
  cv::repeat(f, ny, nx, tiled);
  return normalise_texture(tiled(cv::Rect(0, 0, size.width, size.height)));
}

}  // namespace

Paper make_paper(const cv::Size& size, const WatercolorParams& p, bool gradient) {
  SYLVA_CHECK(size.width > 0 && size.height > 0, "watercolor_paper: empty size");
  if (p.paper == "generated") return generated_paper(size, p, gradient);
  Paper out;
  out.relief = loaded_paper(size, p);
  if (gradient) {
    const cv::Mat smooth = blur(out.relief, float(0.75 * p.grain * reference_scale(size)));
    cv::Sobel(smooth, out.gx, CV_32F, 1, 0, 3, 0.125, 0, cv::BORDER_REPLICATE);
    cv::Sobel(smooth, out.gy, CV_32F, 0, 1, 3, 0.125, 0, cv::BORDER_REPLICATE);
  }
  return out;
}

}  // namespace watercolor_internal

cv::Mat watercolor_paper(const cv::Size& size, const WatercolorParams& p) {
  return watercolor_internal::make_paper(size, p, false).relief;
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

#include "passes/watercolor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <unordered_map>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/io/image_io.h"
#include "core/scene/scene_length.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

constexpr float kSqrt2Pi = 2.50662827f;
// How far (as blurred coverage of known pixels) a wash continues under the clusters in front
// of it: the confidence of the normalised convolution reaches 1 at this value, so the wash
// ends about two blur radii under its occluder.
constexpr float kUnderConfidence = 0.06f;
// The share of a wash's pigment that shows where a nearer cluster covers it.
constexpr float kUnderStrength = 0.35f;
// Paper relief shading of the bare paper at paper_strength 1 (light grazing the grain).
constexpr float kPaperRelief = 0.10f;
// Contrast of the normalised textures: standard deviation around 0.5.
constexpr float kTextureStd = 0.18f;
// The blurred depth test's transition: a leaf this far (in standard deviations of its
// cluster's depth) in front of its blurred surroundings shows all its detail, as far behind none.
constexpr float kDetailBand = 0.3f;
constexpr int kEncodeSize = 16384;
constexpr int kCurveSize = 4096;
// Optical density of black pigment (transmittance 2^-12), which keeps black finite.
constexpr float kMaxDensity = 12.0f;

float srgb_encode_exact(float l) {
  return linear_to_srgb(l);
}
float srgb_decode_exact(float c) {
  return srgb_to_linear(c);
}

struct SrgbTables {
  std::array<float, 256> to_linear;
  std::vector<uint8_t> from_linear;   // kEncodeSize + 1 entries over [0, 1]
  std::vector<float> encode, decode;  // kCurveSize + 2 entries over [0, 1], interpolated
  std::vector<float> density;         // display value -> -log2(linear), <= kMaxDensity
};

const SrgbTables& srgb_tables() {
  static const SrgbTables t = [] {
    SrgbTables s;
    for (int i = 0; i < 256; ++i)
      s.to_linear[size_t(i)] = srgb_decode_exact(float(i) / 255.0f);
    s.from_linear.resize(kEncodeSize + 1);
    for (int i = 0; i <= kEncodeSize; ++i) {
      const float c = srgb_encode_exact(float(i) / float(kEncodeSize));
      s.from_linear[size_t(i)] = uint8_t(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f));
    }
    s.encode.resize(kCurveSize + 2);
    s.decode.resize(kCurveSize + 2);
    for (int i = 0; i <= kCurveSize + 1; ++i) {
      const float v = std::min(1.0f, float(i) / float(kCurveSize));
      s.encode[size_t(i)] = srgb_encode_exact(v);
      s.decode[size_t(i)] = srgb_decode_exact(v);
    }
    s.density.resize(kCurveSize + 2);
    for (int i = 0; i <= kCurveSize + 1; ++i) {
      const float l = s.decode[size_t(i)];
      s.density[size_t(i)] = l > 0.0f ? std::min(kMaxDensity, -std::log2(l)) : kMaxDensity;
    }
    return s;
  }();
  return t;
}

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

inline float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

inline float luminance(const cv::Vec3f& bgr) {
  return 0.0722f * bgr[0] + 0.7152f * bgr[1] + 0.2126f * bgr[2];
}

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

// Paper relief in [0, 1] and, when asked for, the gradient of its smoothed relief (any scale;
// the wobble normalises it).
struct Paper {
  cv::Mat relief, gx, gy;
};

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

// --- Layers ------------------------------------------------------------------------------

struct Layer {
  int32_t id = 0;
  int count = 0;
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive bounding box
  double sum_color[3] = {0, 0, 0};       // linear, premultiplied by coverage
  double sum_alpha = 0;
  double sum_pigment[3] = {0, 0, 0};  // albedo (linear, premultiplied) when it is the pigment
  double sum_pigment_alpha = 0;
  double sum_depth = 0, sum_depth2 = 0;
  // derived
  float mean_depth = 0, depth_spread = 0;
  cv::Vec3f mean_color, pigment;  // linear
  cv::Vec3f pigment_display;      // sRGB-encoded
  float mean_luminance = 0;       // display (sRGB-encoded) luminance
};

struct LayerOut {
  cv::Rect roi;
  cv::Mat density;  // CV_32FC3 optical density (-log2 transmittance), 0 = no pigment
};

struct Shared {
  cv::Size size;
  cv::Mat label;      // CV_32SC1: index of the layer (back to front), -1 background
  cv::Mat luminance;  // CV_32FC1 display luminance of the un-premultiplied shaded colour
  cv::Mat depth;
  cv::Mat wobble_x, wobble_y;  // CV_32FC1 displacement in px (empty = none)
  float max_wobble = 0;        // px, bound of |wobble_x|, |wobble_y|
  float sigma = 0;             // px
  float half_width = 0.5f;     // of the threshold smoothstep
  float edge_gain = 0;         // d - 1 at the steepest edge, <= 1 (d = 2: twice the pigment)
  float detail = 0;
  const SrgbTables* srgb = nullptr;
};

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

cv::Mat blur(const cv::Mat& m, float sigma) {
  if (sigma < 0.3f) return m.clone();
  cv::Mat out;
  cv::GaussianBlur(m, out, cv::Size(0, 0), sigma, sigma, cv::BORDER_REPLICATE);
  return out;
}

LayerOut paint_layer(const Shared& s, const Layer& layer, int k) {
  const float sigma = s.sigma;
  const int pad = int(std::ceil(3.0f * sigma + s.max_wobble)) + 2;
  const cv::Rect roi = cv::Rect(cv::Point(layer.x0 - pad, layer.y0 - pad),
                                cv::Point(layer.x1 + 1 + pad, layer.y1 + 1 + pad)) &
                       cv::Rect(cv::Point(0, 0), s.size);
  LayerOut out;
  out.roi = roi;
  const int w = roi.width, h = roi.height;

  // The masks are blurred at 1/f of the resolution (they are smooth after the blur, and this
  // is most of the pass's time): own = this cluster, known = pixels that do not hide it
  // (itself, the background, clusters behind it), each as its share of an f x f block.
  const int f = std::clamp(int(sigma / 2.0f), 1, 4);
  const int sw = (w + f - 1) / f, sh = (h + f - 1) / f;
  const bool detail = s.detail > 0.0f;
  cv::Mat own(sh, sw, CV_32F, cv::Scalar(0)), known(sh, sw, CV_32F, cv::Scalar(0)), own_depth;
  cv::Mat count(sh, sw, CV_32F, cv::Scalar(0));
  if (detail) own_depth = cv::Mat(sh, sw, CV_32F, cv::Scalar(0));
  for (int y = 0; y < h; ++y) {
    const int32_t* lab = s.label.ptr<int32_t>(roi.y + y) + roi.x;
    const float* dep = s.depth.ptr<float>(roi.y + y) + roi.x;
    float* o = own.ptr<float>(y / f);
    float* kn = known.ptr<float>(y / f);
    float* n = count.ptr<float>(y / f);
    float* od = detail ? own_depth.ptr<float>(y / f) : nullptr;
    for (int x = 0; x < w; ++x) {
      const int sx = x / f;
      n[sx] += 1.0f;
      if (lab[x] == k) {
        o[sx] += 1.0f;
        if (od) od[sx] += dep[x];
      }
      if (lab[x] <= k) kn[sx] += 1.0f;
    }
  }
  own /= count;
  known /= count;
  if (detail) own_depth /= count;
  const float small_sigma = sigma / float(f);
  const cv::Mat blurred_own = blur(own, small_sigma);
  const cv::Mat blurred_known = blur(known, small_sigma);
  cv::Mat blurred_depth;
  if (detail) blurred_depth = blur(own_depth, small_sigma);

  // The blurred mask, continued under occluders by normalised convolution (only where enough
  // of the neighbourhood is known, so it stops about two blur radii in); the occluders'
  // coverage; the blurred depth of this cluster.
  cv::Mat mask_s(sh, sw, CV_32F), cover_s(sh, sw, CV_32F), depth_s;
  if (detail) depth_s.create(sh, sw, CV_32F);
  for (int y = 0; y < sh; ++y) {
    const float* bo = blurred_own.ptr<float>(y);
    const float* bk = blurred_known.ptr<float>(y);
    const float* bd = detail ? blurred_depth.ptr<float>(y) : nullptr;
    float* m = mask_s.ptr<float>(y);
    float* c = cover_s.ptr<float>(y);
    float* d = detail ? depth_s.ptr<float>(y) : nullptr;
    for (int x = 0; x < sw; ++x) {
      const float ratio = bk[x] > 1e-6f ? std::min(1.0f, bo[x] / bk[x]) : 0.0f;
      m[x] = ratio * smoothstep(0.0f, kUnderConfidence, bk[x]);
      // The occluders' blurred coverage stands in for their wash (it leads it a little, so
      // the two overlap at the border rather than leave a gap of bare paper).
      c[x] = smoothstep(0.3f, 0.7f, 1.0f - bk[x]);
      if (d) d[x] = bo[x] > 1e-6f ? bd[x] / bo[x] : 0.0f;
    }
  }

  // Full resolution: the mask looked up at a position displaced along the paper gradient
  // (Bousseau's wobbling), bilinear from the small grid.
  const float inv_f = 1.0f / float(f);
  const float half = 0.5f * inv_f - 0.5f;  // pixel centre x + 0.5 maps to (x + 0.5) / f - 0.5
  cv::Mat mask(h, w, CV_32F);
  for (int y = 0; y < h; ++y) {
    const float* dx = s.wobble_x.empty() ? nullptr : s.wobble_x.ptr<float>(roi.y + y) + roi.x;
    const float* dy = s.wobble_y.empty() ? nullptr : s.wobble_y.ptr<float>(roi.y + y) + roi.x;
    float* m = mask.ptr<float>(y);
    const float sy = float(y) * inv_f + half;
    for (int x = 0; x < w; ++x) {
      const float sx = float(x) * inv_f + half;
      m[x] = dx ? sample(mask_s, sx + dx[x] * inv_f, sy + dy[x] * inv_f) : sample(mask_s, sx, sy);
    }
  }

  // Gradient magnitude of a blurred unit step peaks at 1 / (sigma sqrt(2 pi)): normalise by it
  // so edge_darkening means the same at every blur.
  const float grad_norm = 0.5f * std::max(sigma, 0.5f) * kSqrt2Pi;  // 0.5: central difference
  const float lo = 0.5f - s.half_width, hi = 0.5f + s.half_width;
  out.density.create(h, w, CV_32FC3);
  for (int y = 0; y < h; ++y) {
    const float* m = mask.ptr<float>(y);
    const float* mu = mask.ptr<float>(std::max(y - 1, 0));
    const float* md = mask.ptr<float>(std::min(y + 1, h - 1));
    const int32_t* lab = s.label.ptr<int32_t>(roi.y + y) + roi.x;
    const float* lum = s.luminance.ptr<float>(roi.y + y) + roi.x;
    const float* dep = s.depth.ptr<float>(roi.y + y) + roi.x;
    const float sy = float(y) * inv_f + half;
    cv::Vec3f* t = out.density.ptr<cv::Vec3f>(y);
    for (int x = 0; x < w; ++x) {
      const float coverage = smoothstep(lo, hi, m[x]);
      if (coverage <= 0.0f) {
        t[x] = cv::Vec3f(0.0f, 0.0f, 0.0f);
        continue;
      }
      const float sx = float(x) * inv_f + half;
      // Under a nearer cluster only part of this wash shows: the glaze over it darkens less
      // than two full washes, as a painter's dilute overlaps do.
      const float alpha = coverage * (1.0f - (1.0f - kUnderStrength) * sample(cover_s, sx, sy));
      const float gx = m[std::min(x + 1, w - 1)] - m[std::max(x - 1, 0)];
      const float gy = md[x] - mu[x];
      // Cubed: pigment pools in a narrow band at the very rim, not across the whole blur.
      const float g = std::min(1.0f, std::sqrt(gx * gx + gy * gy) * grad_norm);
      const float d = 1.0f + s.edge_gain * g * g * g;
      cv::Vec3f c = layer.pigment_display;
      if (detail && lab[x] == k) {
        // Luft & Deussen's blurred depth test: a leaf in front of its blurred surroundings
        // shows its shading, one behind them melts into the wash, with no popping between.
        const float in_front = (sample(depth_s, sx, sy) - dep[x]) / layer.depth_spread;
        const float show = s.detail * smoothstep(-kDetailBand, kDetailBand, in_front);
        const float ratio = std::min(lum[x] / layer.mean_luminance, 2.0f);
        c *= 1.0f + show * (ratio - 1.0f);
      }
      for (int ch = 0; ch < 3; ++ch)
        t[x][ch] = alpha * to_density(*s.srgb, pigment_density(std::min(c[ch], 1.0f), d));
    }
  }
  return out;
}

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

}  // namespace

cv::Mat watercolor_paper(const cv::Size& size, const WatercolorParams& p) {
  return make_paper(size, p, false).relief;
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
        o[x] = turbulence_fbm(w * inv, seed);
      }
    }
  });
  return out;
}

cv::Mat watercolor(const WatercolorImages& in, const glm::mat4& view_to_world,
                   const WatercolorParams& p) {
  expect_image(in.id, CV_32SC1, cv::Size(), "id");
  const cv::Size size = in.id.size();
  expect_image(in.color, CV_8UC4, size, "color");
  expect_image(in.depth, CV_32FC1, size, "depth");
  const bool use_albedo = p.pigment == "albedo";
  if (use_albedo) {
    if (in.albedo.empty())
      throw InputError("watercolor.pigment",
                       "\"albedo\" needs the albedo buffer, which this style does not provide "
                       "(use \"shaded\")");
    expect_image(in.albedo, CV_8UC4, size, "albedo");
  }
  const bool turbulence = p.turbulence_strength > 0.0f;
  if (turbulence) expect_image(in.position, CV_32FC3, size, "position");
  const SrgbTables& srgb = srgb_tables();
  const double scale = reference_scale(size);

  Shared s;
  s.size = size;
  s.depth = in.depth;
  s.sigma = float(p.blur * scale);
  // A hard edge still spans about a pixel of the blurred mask's slope, so it is antialiased.
  const float hard = std::clamp(0.7f / (std::max(s.sigma, 0.5f) * kSqrt2Pi), 0.02f, 0.5f);
  s.half_width = hard + (0.5f - hard) * p.edge_softness;
  // Pigment pools where a wash dries against dry paper; a wet-on-wet edge diffuses instead.
  s.edge_gain = p.edge_darkening * (1.0f - 0.8f * p.edge_softness);
  s.detail = p.detail;
  s.srgb = &srgb;

  // Clusters: statistics in one pass, labels in first-appearance order.
  std::vector<Layer> layers;
  std::unordered_map<int32_t, int> index_of;
  cv::Mat first_label(size, CV_32S);
  s.luminance.create(size, CV_32F);
  for (int y = 0; y < size.height; ++y) {
    const int32_t* id = in.id.ptr<int32_t>(y);
    const cv::Vec4b* col = in.color.ptr<cv::Vec4b>(y);
    const cv::Vec4b* alb = use_albedo ? in.albedo.ptr<cv::Vec4b>(y) : nullptr;
    const float* dep = in.depth.ptr<float>(y);
    int32_t* lab = first_label.ptr<int32_t>(y);
    float* lum = s.luminance.ptr<float>(y);
    int32_t last_id = 0;
    int last = -1;
    for (int x = 0; x < size.width; ++x) {
      if (id[x] == 0) {
        lab[x] = -1;
        lum[x] = 0;
        continue;
      }
      if (id[x] != last_id || last < 0) {
        auto [it, added] = index_of.try_emplace(id[x], int(layers.size()));
        if (added) {
          layers.emplace_back();
          layers.back().id = id[x];
          layers.back().x0 = x;
          layers.back().y0 = y;
          layers.back().x1 = x;
          layers.back().y1 = y;
        }
        last_id = id[x];
        last = it->second;
      }
      lab[x] = last;
      Layer& L = layers[size_t(last)];
      ++L.count;
      L.x0 = std::min(L.x0, x);
      L.x1 = std::max(L.x1, x);
      L.y1 = y;
      const float a = float(col[x][3]) / 255.0f;
      cv::Vec3f c(srgb.to_linear[col[x][0]], srgb.to_linear[col[x][1]], srgb.to_linear[col[x][2]]);
      for (int ch = 0; ch < 3; ++ch)
        L.sum_color[ch] += c[ch];
      L.sum_alpha += a;
      if (alb) {
        for (int ch = 0; ch < 3; ++ch)
          L.sum_pigment[ch] += srgb.to_linear[alb[x][ch]];
        L.sum_pigment_alpha += float(alb[x][3]) / 255.0f;
      }
      const double z = dep[x];
      L.sum_depth += z;
      L.sum_depth2 += z * z;
      lum[x] = a > 0.0f ? to_display(srgb, luminance(c / a)) : 0.0f;
    }
  }
  for (Layer& L : layers) {
    const double n = double(L.count);
    L.mean_depth = float(L.sum_depth / n);
    const double var = std::max(0.0, L.sum_depth2 / n - (L.sum_depth / n) * (L.sum_depth / n));
    L.depth_spread = float(std::max(std::sqrt(var), 1e-4 * std::abs(L.sum_depth / n) + 1e-12));
    const double a = std::max(L.sum_alpha, 1e-9);
    L.mean_color =
        cv::Vec3f(float(L.sum_color[0] / a), float(L.sum_color[1] / a), float(L.sum_color[2] / a));
    L.mean_luminance = std::max(to_display(srgb, luminance(L.mean_color)), 1e-3f);
    if (use_albedo) {
      const double pa = std::max(L.sum_pigment_alpha, 1e-9);
      L.pigment = cv::Vec3f(float(L.sum_pigment[0] / pa), float(L.sum_pigment[1] / pa),
                            float(L.sum_pigment[2] / pa));
    } else {
      L.pigment = L.mean_color;
    }
    for (int ch = 0; ch < 3; ++ch) {
      L.pigment[ch] = std::clamp(L.pigment[ch], 0.0f, 1.0f);
      L.pigment_display[ch] = to_display(srgb, L.pigment[ch]);
    }
  }
  // Back to front by mean depth (ties by id), so layer k is hidden only by layers > k.
  std::vector<int> order(layers.size());
  for (size_t i = 0; i < order.size(); ++i)
    order[i] = int(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const Layer& A = layers[size_t(a)];
    const Layer& B = layers[size_t(b)];
    if (A.mean_depth != B.mean_depth) return A.mean_depth > B.mean_depth;
    return A.id < B.id;
  });
  std::vector<int> rank(layers.size());
  for (size_t r = 0; r < order.size(); ++r)
    rank[size_t(order[r])] = int(r);
  s.label.create(size, CV_32S);
  for (int y = 0; y < size.height; ++y) {
    const int32_t* a = first_label.ptr<int32_t>(y);
    int32_t* b = s.label.ptr<int32_t>(y);
    for (int x = 0; x < size.width; ++x)
      b[x] = a[x] < 0 ? -1 : rank[size_t(a[x])];
  }
  std::vector<Layer> sorted(layers.size());
  for (size_t r = 0; r < order.size(); ++r)
    sorted[r] = layers[size_t(order[r])];

  const bool wobble = p.wobble > 0.0f && !sorted.empty();
  Paper paper_maps = make_paper(size, p, wobble);
  const cv::Mat paper = paper_maps.relief;
  if (wobble) {
    // The gradient of the smoothed paper, scaled to an RMS length of `wobble` px.
    s.wobble_x = paper_maps.gx;
    s.wobble_y = paper_maps.gy;
    const double rms = std::sqrt(
        (cv::sum(s.wobble_x.mul(s.wobble_x))[0] + cv::sum(s.wobble_y.mul(s.wobble_y))[0]) /
        double(size.area()));
    const double target = p.wobble * scale;
    const double k = rms > 1e-12 ? target / rms : 0.0;
    const double limit = 3.0 * target;
    s.wobble_x.convertTo(s.wobble_x, CV_32F, k);
    s.wobble_y.convertTo(s.wobble_y, CV_32F, k);
    cv::min(cv::max(s.wobble_x, -limit), limit, s.wobble_x);
    cv::min(cv::max(s.wobble_y, -limit), limit, s.wobble_y);
    s.max_wobble = float(limit);
  }

  std::vector<LayerOut> painted(sorted.size());
  cv::parallel_for_(cv::Range(0, int(sorted.size())), [&](const cv::Range& r) {
    for (int k = r.start; k < r.end; ++k)
      painted[size_t(k)] = paint_layer(s, sorted[size_t(k)], k);
  });
  // Glazing: the densities of transparent washes add (their transmittances multiply), back to
  // front (a fixed order keeps the bytes fixed).
  cv::Mat density(size, CV_32FC3, cv::Scalar(0, 0, 0));
  for (const LayerOut& L : painted) {
    cv::Mat dst = density(L.roi);
    cv::add(dst, L.density, dst);
  }

  cv::Mat turb;
  if (turbulence && !sorted.empty()) {
    // Evaluated at half resolution (the noise is low-frequency): each half-size pixel takes
    // the mean position of its covered pixels, which is the same world point whichever way
    // the view turns (the mean commutes with the rigid view_to_world).
    cv::Mat cover, cover3, half_cover, half_pos;
    cv::threshold(in.depth, cover, 0.0, 1.0, cv::THRESH_BINARY);
    cv::merge(std::vector<cv::Mat>{cover, cover, cover}, cover3);
    const cv::Size half((size.width + 1) / 2, (size.height + 1) / 2);
    cv::resize(cover, half_cover, half, 0, 0, cv::INTER_AREA);
    cv::resize(in.position.mul(cover3), half_pos, half, 0, 0, cv::INTER_AREA);
    for (int y = 0; y < half.height; ++y) {
      const float* c = half_cover.ptr<float>(y);
      cv::Vec3f* q = half_pos.ptr<cv::Vec3f>(y);
      for (int x = 0; x < half.width; ++x)
        q[x] = c[x] > 0.0f ? q[x] / c[x] : cv::Vec3f(0, 0, 0);
    }
    cv::Mat half_turb = watercolor_turbulence(half_pos, half_cover, view_to_world, p);
    // Pigment that bled past the silhouette takes the turbulence of the nearest surface
    // (normalised convolution).
    const float fill_sigma = std::max(2.0f, s.sigma / 2.0f);
    const cv::Mat ws = blur(half_turb.mul(half_cover), fill_sigma);
    const cv::Mat cs = blur(half_cover, fill_sigma);
    cv::Mat filled;
    cv::divide(ws, cv::max(cs, 1e-6), filled);
    filled.copyTo(half_turb, half_cover == 0.0f);
    cv::resize(half_turb, turb, size, 0, 0, cv::INTER_LINEAR);
  }

  cv::Mat out(size, CV_8UC4);
  const float beta_paper = p.paper_strength, beta_turb = p.turbulence_strength;
  const glm::vec3 paper_color = glm::clamp(p.paper_color, 0.0f, 1.0f);
  const cv::Vec3f paper_bgr(paper_color.b, paper_color.g, paper_color.r);
  cv::parallel_for_(cv::Range(0, size.height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      const cv::Vec3f* t = density.ptr<cv::Vec3f>(y);
      const float* pp = paper.ptr<float>(y);
      const float* tb = turb.empty() ? nullptr : turb.ptr<float>(y);
      cv::Vec4b* o = out.ptr<cv::Vec4b>(y);
      for (int x = 0; x < size.width; ++x) {
        // Bousseau's density formula with d = 1 + beta (T - 0.5): pigment settles in the paper's
        // hollows (low relief = more pigment) and follows the turbulence.
        const float d_paper = texture_density(1.0f - pp[x], beta_paper);
        const float d_turb = tb ? texture_density(tb[x], beta_turb) : 1.0f;
        const float relief = 1.0f + kPaperRelief * beta_paper * (pp[x] - 0.5f);
        for (int ch = 0; ch < 3; ++ch) {
          float c = 1.0f;
          if (t[x][ch] > 0.0f) {
            const float v = to_display(srgb, std::exp2(-t[x][ch]));
            c = to_linear(srgb, pigment_density(pigment_density(v, d_paper), d_turb));
          }
          o[x][ch] = encode_srgb(srgb, paper_bgr[ch] * relief * c);
        }
        o[x][3] = 255;
      }
    }
  });
  return out;
}

void bind_watercolor_params(ParamSet& set, WatercolorParams& p) {
  set.add_float("watercolor.blur", p.blur, 0.0, 64.0, "px at 1024 px",
                "Gaussian sigma of each leaf cluster's mask before thresholding");
  set.add_float("watercolor.edge_softness", p.edge_softness, 0.0, 1.0, "",
                "threshold width: 0 hard wet-on-dry edges, 1 soft wet-on-wet edges");
  set.add_float("watercolor.edge_darkening", p.edge_darkening, 0.0, 1.0, "",
                "pigment pooling along each wash's rim");
  set.add_float("watercolor.paper_strength", p.paper_strength, 0.0, 1.0, "",
                "pigment density modulation by the paper grain (Bousseau's beta)");
  set.add_float("watercolor.turbulence_strength", p.turbulence_strength, 0.0, 1.0, "",
                "pigment density modulation by world-space turbulence (Bousseau's beta)");
  set.add_text(
      "watercolor.turbulence_size", p.turbulence_size,
      [](const std::string& text, const std::string& where) {
        (void)SceneLength::parse(text, where);
      },
      "\"auto\", a length in scene units (\"0.3\") or a share of the scene (\"6%\")",
      "feature size of the turbulence noise; auto = 6% of the scene");
  set.add_float("watercolor.wobble", p.wobble, 0.0, 8.0, "px at 1024 px",
                "RMS displacement of the wash outlines along the paper gradient");
  set.add_float("watercolor.detail", p.detail, 0.0, 1.0, "",
                "leaf shading kept inside a wash where leaves stand in front (blurred depth test)");
  set.add_float("watercolor.grain", p.grain, 1.0, 16.0, "px at 1024 px",
                "finest period of the generated paper grain");
  set.add_text(
      "watercolor.paper", p.paper,
      [](const std::string& text, const std::string& where) {
        if (text == "generated") return;
        std::error_code ec;
        if (text.empty() || !std::filesystem::is_regular_file(text, ec))
          throw InputError(where, "watercolor.paper: no such image file '" + text +
                                      "' (use \"generated\" or the path of a paper image)");
      },
      "\"generated\" or the path of a grey-scale paper image",
      "paper texture: generated from the seed, or an image tiled at 1 px per px at 1024 px");
  set.add_color("watercolor.paper_color", p.paper_color, "colour of the bare paper");
  set.add_choice("watercolor.pigment", p.pigment, {"shaded", "albedo"},
                 "pigment colour of a wash: the cluster's mean shaded or albedo colour");
  set.add_int("watercolor.seed", p.seed, 0, 2147483647, "",
              "seed of the generated paper and the turbulence noise");
}

int add_watercolor_pass(RenderGraph& graph, const WatercolorResources& res,
                        const glm::mat4& view_to_world, const WatercolorParams& p) {
  SYLVA_CHECK(res.color >= 0 && res.id >= 0 && res.depth >= 0,
              "add_watercolor_pass: color, id and depth are required");
  const bool albedo = p.pigment == "albedo";
  const bool turbulence = p.turbulence_strength > 0.0f;
  SYLVA_CHECK(!turbulence || res.position >= 0,
              "add_watercolor_pass: turbulence needs the position buffer");
  std::vector<int> reads{res.color, res.id, res.depth};
  if (albedo && res.albedo >= 0) reads.push_back(res.albedo);
  if (turbulence) reads.push_back(res.position);
  const int out = graph.resource("watercolor");
  graph.add_pass("watercolor", reads, {out},
                 [res, view_to_world, p, albedo, turbulence, out](PassContext& ctx) {
                   WatercolorImages in;
                   in.color = ctx.read<cv::Mat>(res.color);
                   in.id = ctx.read<cv::Mat>(res.id);
                   in.depth = ctx.read<cv::Mat>(res.depth);
                   if (albedo && res.albedo >= 0) in.albedo = ctx.read<cv::Mat>(res.albedo);
                   if (turbulence) in.position = ctx.read<cv::Mat>(res.position);
                   ctx.write(out, watercolor(in, view_to_world, p));
                 });
  return out;
}

}  // namespace sylva

#include "passes/composite.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

// Brightness swing of the ground at grain = 1.
constexpr float kGrainAmplitude = 0.15f;

const std::array<float, 256>& decode_lut() {
  static const std::array<float, 256> lut = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i)
      t[size_t(i)] = srgb_to_linear(float(i) / 255.0f);
    return t;
  }();
  return lut;
}

// Linear [0, 1] -> 8-bit sRGB through a 16-bit table: exact to the 8-bit level even in the
// darks, where the sRGB curve is steepest.
constexpr int kEncodeSteps = 65535;
const std::vector<uint8_t>& encode_lut() {
  static const std::vector<uint8_t> lut = [] {
    std::vector<uint8_t> t(kEncodeSteps + 1);
    for (int i = 0; i <= kEncodeSteps; ++i)
      t[size_t(i)] = uint8_t(std::lround(linear_to_srgb(float(i) / kEncodeSteps) * 255.0f));
    return t;
  }();
  return lut;
}

// std::lround for a float x in [0, 2^31) without the library call: double(x) + 0.5 is exact
// (or, for tiny x, still below 1), so truncating it rounds half away from zero as lround does.
inline int round_non_negative(float x) {
  return int(double(x) + 0.5);
}

inline uint8_t encode(const std::vector<uint8_t>& lut, float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return lut[size_t(round_non_negative(c * kEncodeSteps))];
}

// One octave of value noise in [-1, 1] (bicubic, may overshoot a little): a seeded lattice
// with one value per `cell` px, enlarged to the image. The lattice has a fixed number of cells
// across the reference-scaled image, so the pattern does not depend on the resolution.
cv::Mat noise_octave(const cv::Size& size, double cell, uint64_t seed) {
  const int gw = int(std::ceil(size.width / cell)) + 4;
  const int gh = int(std::ceil(size.height / cell)) + 4;
  cv::Mat lattice(gh, gw, CV_32FC1);
  cv::RNG rng(seed);  // cv::RNG is a fixed multiply-with-carry generator: same bytes everywhere
  rng.fill(lattice, cv::RNG::UNIFORM, -1.0, 1.0);
  const cv::Size big(int(std::lround(gw * cell)), int(std::lround(gh * cell)));
  cv::Mat up;
  cv::resize(lattice, up, big, 0, 0, cell >= 1.0 ? cv::INTER_CUBIC : cv::INTER_AREA);
  // Skip the first two cells: bicubic needs neighbours on both sides.
  const int off = int(std::lround(2 * cell));
  return up(cv::Rect(off, off, size.width, size.height)).clone();
}

void check_paper(const PaperParams& p) {
  SYLVA_CHECK(std::isfinite(p.grain) && p.grain >= 0.0f && p.grain <= 1.0f, "ink: grain range");
  SYLVA_CHECK(std::isfinite(p.grain_size) && p.grain_size >= 0.5f && p.grain_size <= 32.0f,
              "ink: grain size range");
}

}  // namespace

cv::Mat make_paper(const cv::Size& size, const PaperParams& p) {
  check_paper(p);
  const cv::Scalar bgr(p.color.b, p.color.g, p.color.r);
  cv::Mat paper(size, CV_32FC3);
  if (p.grain <= 0.0f || size.empty()) {
    // A flat sheet; filled by row bands, as this is a large image written once per frame.
    const cv::Vec3f v{float(bgr[0]), float(bgr[1]), float(bgr[2])};
    for_bands(size.height, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y)
        std::fill_n(paper.ptr<cv::Vec3f>(y), size.width, v);
    });
    return paper;
  }

  // Two octaves: fine tooth and broader cloudiness of the sheet.
  const double cell = p.grain_size * reference_scale(size);
  const uint64_t seed = uint64_t(uint32_t(p.seed)) * 2654435761ull + 1ull;
  cv::Mat fine = noise_octave(size, cell, seed);
  cv::Mat broad = noise_octave(size, 4.0 * cell, seed ^ 0x9e3779b97f4a7c15ull);
  cv::Mat n = 0.65 * fine + 0.35 * broad;
  for (int y = 0; y < size.height; ++y) {
    const float* v = n.ptr<float>(y);
    cv::Vec3f* out = paper.ptr<cv::Vec3f>(y);
    for (int x = 0; x < size.width; ++x) {
      const float f = std::max(0.0f, 1.0f + kGrainAmplitude * p.grain * v[x]);
      out[x] = cv::Vec3f(bgr[0] * f, bgr[1] * f, bgr[2] * f);
    }
  }
  return paper;
}

ImageHandle add_paper_pass(RenderGraph& g, cv::Size size, const PaperParams& p) {
  check_paper(p);
  SYLVA_CHECK(size.width > 0 && size.height > 0, "paper: empty size");
  const auto out = g.resource<cv::Mat>("paper");
  g.add_pass(
      "paper", {}, {out},
      [p, size, out](PassContext& ctx) {
        // Without grain the sheet is flat: one pixel, which composite_ink reads everywhere.
        ctx.write(out, make_paper(p.grain > 0.0f ? size : cv::Size(1, 1), p));
      },
      RenderGraph::Threads::Any);
  return out;
}

void bind_ink_params(ParamSet& set, InkParams& p) {
  set.add_color("ink.paper_color", p.paper.color, "colour of the ground (paper)");
  set.add_float("ink.grain", p.paper.grain, 0.0, 1.0, "",
                "paper grain strength (0 = flat; 1 = about +-15% brightness)");
  set.add_float("ink.grain_size", p.paper.grain_size, 0.5, 32.0, "px at 1024 px",
                "size of the finest paper grain");
  set.add_int("ink.seed", p.paper.seed, 0, std::numeric_limits<int>::max(), "",
              "random seed of the paper grain");
  set.add_float("ink.fill", p.fill, 0.0, 1.0, "",
                "wash of the shaded colour under the lines (0 = pure pen drawing)");
  set.add_bool("ink.transparent", p.transparent, "paper only under the drawing, alpha 0 elsewhere");
}

namespace {

// What composite_ink lays on every pixel, and its tables.
struct InkComposite {
  const cv::Mat &lines, &coverage_or_color, &paper;
  float fill;
  cv::Vec3f line;   // linear BGR of the lines
  cv::Vec3f line8;  // the same, sRGB-encoded (0..255)
  const std::array<float, 256>& decode = decode_lut();
  const std::vector<uint8_t>& encode_table = encode_lut();
};

// One row of composite_ink, for a colour (kColor) or a coverage, with a wash (kWash: ink.fill >
// 0) or without (the ground is the paper), on an opaque or a transparent ground.
template <bool kColor, bool kWash, bool kTransparent>
void composite_row(const InkComposite& in, int y, cv::Vec4b* o) {
  const float* l = in.lines.ptr<float>(y);
  // A flat sheet is one pixel, read at every x.
  const bool flat = in.paper.size() != in.lines.size();
  const cv::Vec3f* pp = in.paper.ptr<cv::Vec3f>(flat ? 0 : y);
  const int step = flat ? 0 : 1;
  const cv::Vec4b* c = kColor ? in.coverage_or_color.ptr<cv::Vec4b>(y) : nullptr;
  const float* m = kColor ? nullptr : in.coverage_or_color.ptr<float>(y);
  // The last ground encoded: a flat sheet (no grain, no wash) is encoded once a row.
  cv::Vec3f last(-1.0f, -1.0f, -1.0f);
  cv::Vec3b last8(0, 0, 0);
  for (int x = 0; x < in.lines.cols; ++x) {
    float a = 0.0f;
    if constexpr (kWash || kTransparent)
      a = kColor ? c[x][3] / 255.0f : std::clamp(m[x], 0.0f, 1.0f);
    cv::Vec3f ground = pp[x * step];
    if constexpr (kWash) {
      const cv::Vec3f shaded =
          kColor ? cv::Vec3f(in.decode[c[x][0]], in.decode[c[x][1]], in.decode[c[x][2]]) : in.line;
      const float wash = in.fill * a;
      for (int k = 0; k < 3; ++k)
        ground[k] = pp[x * step][k] * (1.0f - wash + wash * shaded[k]);
    }
    const float ink = std::clamp(l[x], 0.0f, 1.0f);
    // The lines go over the ground in sRGB-encoded values, as SVG and PDF renderers composite,
    // so the raster ink and the vector files look the same.
    float alpha = 1.0f, keep = 1.0f - ink;
    if constexpr (kTransparent) {
      // Straight alpha: lines over the ground, which covers only the drawing.
      alpha = ink + a * (1.0f - ink);
      keep = alpha > 0.0f ? a * (1.0f - ink) / alpha : 1.0f;
    }
    if (ground != last) {
      for (int k = 0; k < 3; ++k)
        last8[k] = encode(in.encode_table, ground[k]);
      last = ground;
    }
    for (int k = 0; k < 3; ++k) {
      // Bare ground (most of the picture) as it is: the blend would give the same byte.
      o[x][k] =
          keep == 1.0f
              ? last8[k]
              : uint8_t(round_non_negative(float(last8[k]) * keep + in.line8[k] * (1.0f - keep)));
    }
    o[x][3] = kTransparent ? uint8_t(round_non_negative(alpha * 255.0f)) : uint8_t(255);
  }
}

template <bool kColor, bool kWash, bool kTransparent>
void composite_rows(const InkComposite& in, cv::Mat& out) {
  // Rows in parallel: every pixel depends only on its inputs.
  for_bands(out.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      composite_row<kColor, kWash, kTransparent>(in, y, out.ptr<cv::Vec4b>(y));
  });
}

using CompositeRows = void (*)(const InkComposite&, cv::Mat&);
// By [colour][wash][transparent].
constexpr CompositeRows kCompositeRows[2][2][2] = {
    {{composite_rows<false, false, false>, composite_rows<false, false, true>},
     {composite_rows<false, true, false>, composite_rows<false, true, true>}},
    {{composite_rows<true, false, false>, composite_rows<true, false, true>},
     {composite_rows<true, true, false>, composite_rows<true, true, true>}}};

}  // namespace

cv::Mat composite_ink(const cv::Mat& lines, const cv::Mat& coverage_or_color, const cv::Mat& paper,
                      const InkParams& p) {
  const cv::Size size = lines.size();
  expect_image(lines, CV_32FC1, size, "lines");
  expect_image(paper, CV_32FC3, paper.size() == cv::Size(1, 1) ? paper.size() : size, "paper");
  const bool has_color = coverage_or_color.type() == CV_8UC4;
  expect_image(coverage_or_color, has_color ? CV_8UC4 : CV_32FC1, size, "coverage or color");
  SYLVA_CHECK(std::isfinite(p.fill) && p.fill >= 0.0f && p.fill <= 1.0f, "ink: fill range");
  InkComposite in{lines, coverage_or_color, paper, p.fill, {}, {}};
  in.line = cv::Vec3f(p.line_color.b, p.line_color.g, p.line_color.r);
  for (int k = 0; k < 3; ++k)
    in.line8[k] = encode(in.encode_table, in.line[k]);
  cv::Mat out(size, CV_8UC4);
  kCompositeRows[has_color][p.fill > 0.0f][p.transparent](in, out);
  return out;
}

ImageHandle add_ink_composite_pass(RenderGraph& g, ImageHandle lines, ImageHandle coverage_or_color,
                                   const InkParams& p, cv::Size size) {
  const ImageHandle paper = add_paper_pass(g, size, p.paper);
  const auto out = g.resource<cv::Mat>("ink");
  g.add_pass(
      "ink-composite", {lines, coverage_or_color, paper}, {out},
      [lines, coverage_or_color, paper, out, p](PassContext& ctx) {
        ctx.write(out, composite_ink(ctx.read<cv::Mat>(lines), ctx.read<cv::Mat>(coverage_or_color),
                                     ctx.read<cv::Mat>(paper), p));
      },
      RenderGraph::Threads::Any);
  return out;
}

cv::Mat lines_over(const cv::Mat& lines, const cv::Mat& picture, const glm::vec3& line_color) {
  const cv::Size size = lines.size();
  expect_image(lines, CV_32FC1, size, "lines");
  expect_image(picture, CV_8UC4, size, "picture");
  const std::vector<uint8_t>& encode_table = encode_lut();
  const cv::Vec3f line8(encode(encode_table, line_color.b), encode(encode_table, line_color.g),
                        encode(encode_table, line_color.r));
  cv::Mat out(size, CV_8UC4);
  for_bands(size.height, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const float* l = lines.ptr<float>(y);
      const cv::Vec4b* p = picture.ptr<cv::Vec4b>(y);
      cv::Vec4b* o = out.ptr<cv::Vec4b>(y);
      for (int x = 0; x < size.width; ++x) {
        const float ink = std::clamp(l[x], 0.0f, 1.0f), a = p[x][3] / 255.0f;
        const float alpha = ink + a * (1.0f - ink);  // straight alpha, lines over the picture
        const float keep = alpha > 0.0f ? a * (1.0f - ink) / alpha : 1.0f;
        for (int k = 0; k < 3; ++k)
          o[x][k] = uint8_t(round_non_negative(p[x][k] * keep + line8[k] * (1.0f - keep)));
        o[x][3] = uint8_t(round_non_negative(alpha * 255.0f));
      }
    }
  });
  return out;
}

ImageHandle add_lines_over_pass(RenderGraph& g, ImageHandle lines, ImageHandle picture,
                                const glm::vec3& line_color) {
  const auto out = g.resource<cv::Mat>("lines-over");
  g.add_pass(
      "lines-over", {lines, picture}, {out},
      [lines, picture, out, line_color](PassContext& ctx) {
        ctx.write(out,
                  lines_over(ctx.read<cv::Mat>(lines), ctx.read<cv::Mat>(picture), line_color));
      },
      RenderGraph::Threads::Any);
  return out;
}

}  // namespace sylva

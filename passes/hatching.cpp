#include "passes/hatching.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/random.h"
#include "passes/ink_abstraction.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {
std::string number_text(float v) {  // a parameter value as the user wrote it ("0.6")
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", double(v));
  return buf;
}
}  // namespace

void bind_pen_params(ParamSet& set, PenParams& p) {
  set.add_choice("pen.tone", p.tone, {"none", "hatching", "stipple"},
                 "tone drawn with strokes where the shaded colour (realigned normals, ka) is "
                 "dark");
  set.add_float("pen.spacing", p.spacing, 2.0, 64.0, "px at 1024 px",
                "distance between neighbouring tone strokes at full darkness");
  set.add_float("pen.length", p.length, 1.0, 128.0, "px at 1024 px", "hatching stroke length");
  set.add_float("pen.width", p.width, 0.25, 8.0, "px at 1024 px",
                "hatching stroke width or stipple dot diameter (at least 1 px)");
  set.add_float("pen.angle", p.angle, -180.0, 180.0, "degrees",
                "hatching direction, counter-clockwise from the image's x axis");
  set.add_float("pen.angle_jitter", p.angle_jitter, 0.0, 90.0, "degrees",
                "how far each crown region's (leaf cluster's) hatching angle may differ");
  set.add_float("pen.lightest", p.lightest, 0.0, 0.99, "share of the plant",
                "the lightest share of the plant (by the colour's smoothed luma) left bare");
  set.add_float("pen.darkest", p.darkest, 0.01, 1.0, "share of the plant",
                "from this quantile of darkness on, the tone is full (strokes pen.spacing "
                "apart); above pen.lightest");
  set.add_float("pen.cross", p.cross, 0.0, 1.0, "",
                "tone from which hatching crosses (1 = only the darkest)", true);
  set.add_float("pen.gamma", p.gamma, 0.1, 10.0, "",
                "exponent from darkness to stroke density (> 1: fewer strokes in mid-tones)");
  set.add_float("pen.opacity", p.opacity, 0.0, 1.0, "", "ink opacity of the tone strokes");
  set.add_int("pen.seed", p.seed, 0, 2147483647, "", "random seed of the anchors and angles");
}

void validate_pen_params(const PenParams& p) {
  if (!(p.darkest > p.lightest))
    throw InputError("pen.darkest", "must be greater than pen.lightest (" +
                                        number_text(p.lightest) + "), not " +
                                        number_text(p.darkest));
}

double units_per_px(const Camera& camera, const Sphere& sphere) {
  if (camera.height <= 0 || camera.proj[1][1] == 0.0f) return 0.0;
  // proj[1][1] = 1 / tan(fov / 2) (perspective) or 1 / half height (orthographic).
  const double half = 1.0 / camera.proj[1][1];
  const double distance =
      camera.ortho || sphere.empty() ? 1.0 : glm::distance(camera.eye, sphere.centre);
  return 2.0 * half * distance / camera.height;
}

namespace {

uint64_t mix(uint64_t a, uint64_t b) {
  uint64_t s = a * 0x9e3779b97f4a7c15ull ^ (b + 0x632be59bd9b4e019ull);
  return splitmix64(s);
}

double hash01(uint64_t key, uint64_t salt) {
  uint64_t s = mix(key, salt);
  return uniform01(s);
}

bool covered(const cv::Mat& color, int x, int y) {
  return color.at<cv::Vec4b>(y, x)[3] >= 128;
}

// A scene-fixed anchor: a cube's seeded point, where the visible surface passes near it; its
// place on screen is the point's projection, so it moves exactly with the scene.
struct Anchor {
  uint64_t key;
  double rank;
  float cx, cy;  // continuous image coordinates of the projected point
  int x, y;      // the pixel it falls in
};

uint64_t cube_key(const glm::vec3& p, double cube) {
  auto q = [&](float v) { return uint64_t(int64_t(std::floor(v / cube)) & 0x1FFFFF); };
  return q(p.x) | (q(p.y) << 21) | (q(p.z) << 42);
}

glm::vec3 cube_point(uint64_t key, double cube, uint64_t seed) {
  auto c = [&](int shift) {
    int64_t v = int64_t((key >> shift) & 0x1FFFFF);
    if (v & 0x100000) v -= 0x200000;  // sign of the 21-bit field
    return v;
  };
  return {float((double(c(0)) + hash01(key, seed * 4 + 1)) * cube),
          float((double(c(21)) + hash01(key, seed * 4 + 2)) * cube),
          float((double(c(42)) + hash01(key, seed * 4 + 3)) * cube)};
}

// The cubes the visible surface passes through (each visible pixel's world point names one),
// kept where the cube's seeded point projects onto a visible pixel whose surface lies within
// two cubes of the point's depth: the surface near the point is in sight.
std::vector<Anchor> scene_anchors(const ToneImages& in, const ToneView& view, double cube,
                                  uint64_t seed) {
  const glm::mat4 to_world = glm::inverse(view.view);
  std::vector<uint64_t> keys;
  for (int y = 0; y < in.color.rows; ++y)
    for (int x = 0; x < in.color.cols; ++x) {
      if (!covered(in.color, x, y)) continue;
      const cv::Vec3f v = in.position.at<cv::Vec3f>(y, x);
      keys.push_back(cube_key(glm::vec3(to_world * glm::vec4(v[0], v[1], v[2], 1.0f)), cube));
    }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<Anchor> anchors;
  const float w = float(in.color.cols), h = float(in.color.rows);
  for (uint64_t key : keys) {
    const glm::vec4 q = view.view * glm::vec4(cube_point(key, cube, seed), 1.0f);
    const glm::vec4 clip = view.proj * q;
    if (clip.w <= 0.0f) continue;
    const float cx = (clip.x / clip.w * 0.5f + 0.5f) * w, cy = (0.5f - clip.y / clip.w * 0.5f) * h;
    const int x = int(std::floor(cx)), y = int(std::floor(cy));
    if (x < 0 || y < 0 || x >= in.color.cols || y >= in.color.rows || !covered(in.color, x, y))
      continue;
    const float surface = in.position.at<cv::Vec3f>(y, x)[2];
    if (std::abs(surface - q.z) > 2.0 * cube) continue;
    anchors.push_back({key, hash01(key, seed * 4), cx, cy, x, y});
  }
  return anchors;  // in key order
}

// How many anchors fall in the spacing-sized screen cells within 4 cells of each anchor, over
// 81: the candidates per cell (averaged widely, so it changes little from frame to frame), so each
// is drawn with the probability that gives one stroke per cell at full tone, whatever the depth
// complexity.
std::vector<double> candidates_per_cell(const std::vector<Anchor>& anchors, cv::Size size,
                                        double cell) {
  const int cols = int(std::ceil(size.width / cell)) + 1,
            rows = int(std::ceil(size.height / cell)) + 1;
  cv::Mat count(rows, cols, CV_32FC1, cv::Scalar(0));
  for (const Anchor& a : anchors)
    count.at<float>(int(a.cy / cell), int(a.cx / cell)) += 1.0f;
  cv::blur(count, count, {9, 9}, {-1, -1}, cv::BORDER_CONSTANT);
  std::vector<double> out;
  out.reserve(anchors.size());
  for (const Anchor& a : anchors)
    out.push_back(std::max(1.0f, count.at<float>(int(a.cy / cell), int(a.cx / cell))));
  return out;
}

// A straight stroke through `centre` along `dir`, `length` long, cut where it leaves `inside`.
bool clipped_line(const cv::Mat& inside, cv::Point2f centre, cv::Point2f dir, double length,
                  Stroke& s) {
  auto reach = [&](float sign) {
    double t = 0;
    for (; t < 0.5 * length; t += 1.0) {
      const cv::Point2f q = centre + float(sign * (t + 1.0)) * dir;
      const int x = int(std::floor(q.x)), y = int(std::floor(q.y));
      if (x < 0 || y < 0 || x >= inside.cols || y >= inside.rows || !inside.at<uint8_t>(y, x))
        break;
    }
    return std::min(t, 0.5 * length);
  };
  const double a = reach(-1.0f), b = reach(1.0f);
  if (a + b < 2.0) return false;
  const cv::Point2f p0 = centre - float(a) * dir, p1 = centre + float(b) * dir;
  s.points = {{p0.x, p0.y}, {p1.x, p1.y}};
  return true;
}

}  // namespace

cv::Mat tone_darkness(const cv::Mat& color) {
  expect_image(color, CV_8UC4, {}, "color");
  cv::Mat dark(color.size(), CV_32FC1, cv::Scalar(0));
  for_bands(color.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < color.cols; ++x) {
        const cv::Vec4b c = color.at<cv::Vec4b>(y, x);
        if (c[3] < 128) continue;
        // Rec. 709 luma of the sRGB-encoded values: the tone as the eye reads it.
        const float luma = (0.0722f * c[0] + 0.7152f * c[1] + 0.2126f * c[2]) / 255.0f;
        dark.at<float>(y, x) = std::clamp(1.0f - luma, 0.0f, 1.0f);
      }
  });
  return dark;
}

StrokeDrawing tone_strokes(const ToneImages& in, const ToneView& view, const PenParams& p,
                           double detail) {
  const cv::Size size = in.color.size();
  const double scale = reference_scale(size);
  StrokeDrawing d;
  d.size = size;
  if (!p.enabled() || view.units_per_px <= 0.0) return d;
  SYLVA_CHECK(p.tone == "hatching" || p.tone == "stipple", "pen.tone: unknown " + p.tone);
  cv::Mat alpha, plant;
  cv::extractChannel(in.color, alpha, 3);
  plant = alpha >= 128;
  // Tone at the picture's scale: darkness averaged over the plant.
  cv::Mat dark = tone_darkness(in.color), weight, mask;
  plant.convertTo(mask, CV_32F, 1.0 / 255.0);
  const double sigma = std::max(1.0, 0.5 * detail * scale);
  cv::GaussianBlur(dark, dark, {0, 0}, sigma);
  cv::GaussianBlur(mask, weight, {0, 0}, sigma);
  // The tone's range: the darkness at the pen.lightest and pen.darkest quantiles of the plant.
  cv::divide(dark, cv::max(weight, 1e-6f), dark);
  std::vector<float> values;
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x)
      if (plant.at<uint8_t>(y, x)) values.push_back(dark.at<float>(y, x));
  if (values.empty()) return d;
  auto quantile = [&](double q) {
    const size_t k = std::min(values.size() - 1, size_t(q * double(values.size() - 1) + 0.5));
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
    return double(values[k]);
  };
  const double lo = quantile(p.lightest), hi = std::max(quantile(p.darkest), lo + 1e-3);
  const CrownShape crown = crown_shape(plant, detail * scale);
  const cv::Mat inside = crown.body | crown.thin | plant;
  // Small renders: strokes no thinner than 1 px, and then no closer than 4 widths (spacing and
  // length grow together), so the tone does not fill in solid.
  const double width = std::max(1.0, p.width * scale);
  const double grow = std::max(1.0, 4.0 * width / (p.spacing * scale));
  const double spacing = p.spacing * scale * grow, length = p.length * scale * grow;
  const uint64_t seed = uint64_t(p.seed);
  // Cubes of half the spacing: enough candidates for the densest tone.
  std::vector<Anchor> anchors = scene_anchors(in, view, 0.5 * spacing * view.units_per_px, seed);
  auto tone_at = [&](const Anchor& a) {
    const double darkness = dark.at<float>(a.y, a.x);
    return std::pow(std::clamp((darkness - lo) / (hi - lo), 0.0, 1.0), double(p.gamma));
  };
  Stroke s;
  s.cls = LineClass::Tone;
  s.opacity = p.opacity;
  s.width = float(width);
  // Each anchor decides alone, by its seeded rank against the tone's share of the candidates
  // around it, so one stroke coming or going never moves another (no cascade from frame to
  // frame). Layer 0 everywhere with tone; layer 1, crossing it, where the tone passes
  // pen.cross, with its own ranks, so the crossing strokes do not sit on the first layer's.
  const std::vector<double> per_cell = candidates_per_cell(anchors, size, spacing);
  for (int layer = 0; layer < (p.tone == "hatching" && p.cross < 1.0f ? 2 : 1); ++layer)
    for (size_t i = 0; i < anchors.size(); ++i) {
      const Anchor& a = anchors[i];
      double t = tone_at(a);
      if (layer == 1) t = (t - p.cross) / (1.0 - p.cross);
      const double rank = layer == 0 ? a.rank : hash01(a.key, seed * 4 + 7);
      if (t <= 0.02 || rank >= t / per_cell[i]) continue;
      const cv::Point2f centre(a.cx, a.cy);
      if (p.tone == "stipple") {
        s.points = {{centre.x, centre.y}};
        d.strokes.push_back(s);
        continue;
      }
      const uint64_t region = in.id.empty() ? 0 : uint64_t(in.id.at<int>(a.y, a.x));
      const double phi =
          (p.angle + p.angle_jitter * (2.0 * hash01(region, seed * 4 + 5) - 1.0) + 90.0 * layer) *
          std::numbers::pi / 180.0;
      const double len = length * (0.75 + 0.5 * hash01(a.key, seed * 4 + 6));
      const cv::Point2f dir(float(std::cos(phi)), float(-std::sin(phi)));  // y points down
      if (clipped_line(inside, centre, dir, len, s)) d.strokes.push_back(s);
    }
  return d;
}

int add_tone_pass(RenderGraph& g, const ToneResources& in, const ToneView& view, const PenParams& p,
                  double detail) {
  SYLVA_CHECK(in.position >= 0 && in.color >= 0,
              "tone pass needs the position and color resources");
  std::vector<int> reads = {in.position, in.color};
  if (in.id >= 0) reads.push_back(in.id);
  const int out = g.resource("tone-strokes");
  g.add_pass("tone-strokes", reads, {out}, [=](PassContext& ctx) {
    ToneImages images;
    images.position = ctx.read<cv::Mat>(in.position);
    images.color = ctx.read<cv::Mat>(in.color);
    if (in.id >= 0) images.id = ctx.read<cv::Mat>(in.id);
    ctx.write(out, tone_strokes(images, view, p, detail));
  });
  return out;
}

}  // namespace sylva

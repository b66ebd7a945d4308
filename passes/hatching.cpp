#include "passes/hatching.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <string>

#include "core/error.h"
#include "core/random.h"
#include "passes/crown_coverage.h"
#include "passes/ink_abstraction.h"
#include "passes/ink_working.h"
#include "passes/pass_common.h"
#include "passes/tone_rank.h"

namespace sylva {

namespace {
std::string number_text(float v) {  // a parameter value as the user wrote it ("0.6")
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", double(v));
  return buf;
}
}  // namespace

void bind_pen_params(ParamSet& set, PenParams& p) {
  set.add_choice(
      "pen.tone", p.tone,
      {{"none", PenTone::None}, {"hatching", PenTone::Hatching}, {"stipple", PenTone::Stipple}},
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
  float cx, cy;    // continuous image coordinates of the projected point
  int x, y;        // the pixel it falls in
  int region = 0;  // the leaf cluster most of the cube's visible pixels show (0 = none)
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

// Each cube of `named` (sorted) once, with the cluster most of its pixels show (ties: the
// smaller id): a region that belongs to the cube, so a stroke's angle does not change as other
// leaves come and go in front of its pixel.
std::vector<std::pair<uint64_t, int>> cube_regions(
    const std::vector<std::pair<uint64_t, int>>& named) {
  std::vector<std::pair<uint64_t, int>> out;
  for (size_t i = 0; i < named.size();) {
    size_t end = i;
    int best = named[i].second, most = 0;
    while (end < named.size() && named[end].first == named[i].first) {
      size_t run = end;
      while (run < named.size() && named[run] == named[end])
        ++run;
      if (int(run - end) > most) {
        most = int(run - end);
        best = named[end].second;
      }
      end = run;
    }
    out.emplace_back(named[i].first, best);
    i = end;
  }
  return out;
}

// Whether what the raster shows within one pixel of (x, y) hides the view depth `z` (view-space
// z, negative in front of the eye): its nearest surface lies more than `tolerance` in front.
// Nothing shown there hides nothing.
bool hidden(const ToneImages& in, int x, int y, float z, float tolerance) {
  float nearest = -1e30f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int u = x + dx, v = y + dy;
      if (u < 0 || v < 0 || u >= in.color.cols || v >= in.color.rows || !covered(in.color, u, v))
        continue;
      nearest = std::max(nearest, in.position.at<cv::Vec3f>(v, u)[2]);
    }
  return z < nearest - tolerance;
}

// The cubes the plant's surface passes through, each once with its region: from the surface
// samples (fixed in the scene), else from the visible pixels' world points.
std::vector<std::pair<uint64_t, int>> surface_cubes(const ToneImages& in, const ToneView& view,
                                                    double cube) {
  std::vector<std::pair<uint64_t, int>> named;  // (cube, the naming point's cluster)
  if (in.samples) {
    const SurfaceSamples& s = *in.samples;
    for (size_t i = 0; i < s.size(); ++i)
      named.emplace_back(cube_key(s.positions[i], cube), int(s.clusters[i]));
  } else {
    const glm::mat4 to_world = glm::inverse(view.view);
    for (int y = 0; y < in.color.rows; ++y)
      for (int x = 0; x < in.color.cols; ++x) {
        if (!covered(in.color, x, y)) continue;
        const cv::Vec3f v = in.position.at<cv::Vec3f>(y, x);
        const glm::vec3 world(to_world * glm::vec4(v[0], v[1], v[2], 1.0f));
        named.emplace_back(cube_key(world, cube), in.id.empty() ? 0 : in.id.at<int>(y, x));
      }
  }
  std::sort(named.begin(), named.end());
  return cube_regions(named);
}

// Without surface samples, anchors within this many cubes behind the nearest surface seen are
// in sight: the crown's front shell, deep enough that a leaf turning in front of an anchor does
// not hide it. With them, anchors at most kMidCubes behind the crown's mean depth (the front
// half of the crown, and a little more): a test that moves with the scene.
constexpr float kShellCubes = 16.0f;
constexpr float kMidCubes = 8.0f;

// The crown's mean view-space z at `size` (a working resolution of the frame of size `out`): the
// surface samples' z, area-weighted and smoothed by a Gaussian of `sigma` px; -inf where no
// sample is near. It moves with the scene, and a leaf turning in front of another does not
// change it.
cv::Mat crown_mid_depth(const SurfaceSamples& s, const ToneView& view, cv::Size size, cv::Size out,
                        double sigma) {
  cv::Mat wz(size, CV_32FC1, cv::Scalar(0)), wa(size, CV_32FC1, cv::Scalar(0));
  const float fx = float(size.width) / float(out.width),
              fy = float(size.height) / float(out.height);
  for (size_t i = 0; i < s.size(); ++i) {
    const glm::vec4 q = view.view * glm::vec4(s.positions[i], 1.0f);
    const glm::vec4 clip = view.proj * q;
    if (!(clip.w > 0.0f)) continue;
    const int x = int(std::floor((clip.x / clip.w * 0.5f + 0.5f) * float(out.width) * fx));
    const int y = int(std::floor((0.5f - clip.y / clip.w * 0.5f) * float(out.height) * fy));
    if (x < 0 || y < 0 || x >= size.width || y >= size.height) continue;
    wz.at<float>(y, x) += s.areas[i] * q.z;
    wa.at<float>(y, x) += s.areas[i];
  }
  cv::GaussianBlur(wz, wz, {0, 0}, sigma);
  cv::GaussianBlur(wa, wa, {0, 0}, sigma);
  cv::Mat mid;
  cv::divide(wz, cv::max(wa, 1e-12f), mid);
  mid.setTo(-1e30f, wa <= 1e-12f);
  return mid;
}

// The cubes the plant's surface passes through whose seeded point projects inside the region
// the strokes are drawn in (`inside`) and is in sight (kMidCubes, kShellCubes): each an anchor
// at the point's projection, which moves exactly with the scene. detail_px: ink.detail in px.
std::vector<Anchor> scene_anchors(const ToneImages& in, const ToneView& view, double cube,
                                  uint64_t seed, const cv::Mat& inside, double detail_px) {
  std::vector<Anchor> anchors;
  const float w = float(in.color.cols), h = float(in.color.rows);
  double f = 1.0;
  cv::Mat mid;
  if (in.samples) {
    const cv::Size size = working_size(in.color.size(), std::max(2.0, detail_px), f);
    mid = crown_mid_depth(*in.samples, view, size, in.color.size(), kWorkingDetail);
  }
  for (const auto& [key, region] : surface_cubes(in, view, cube)) {
    const glm::vec4 q = view.view * glm::vec4(cube_point(key, cube, seed), 1.0f);
    const glm::vec4 clip = view.proj * q;
    if (clip.w <= 0.0f) continue;
    const float cx = (clip.x / clip.w * 0.5f + 0.5f) * w, cy = (0.5f - clip.y / clip.w * 0.5f) * h;
    const int x = int(std::floor(cx)), y = int(std::floor(cy));
    if (x < 0 || y < 0 || x >= in.color.cols || y >= in.color.rows || !inside.at<uint8_t>(y, x))
      continue;
    if (!mid.empty()) {
      const int u = std::min(mid.cols - 1, int(cx / f)), v = std::min(mid.rows - 1, int(cy / f));
      if (q.z < mid.at<float>(v, u) - kMidCubes * float(cube)) continue;
    } else if (hidden(in, x, y, q.z, kShellCubes * float(cube))) {
      continue;
    }
    anchors.push_back({key, hash01(key, seed * 4), cx, cy, x, y, region});
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

namespace {

// The tone at the picture's scale: darkness averaged over the plant with a Gaussian of sigma =
// ink.detail px (the crown's parts, not its leaves, whose shading changes as they turn), and
// its range: the darkness at the pen.lightest and pen.darkest quantiles of the plant.
struct ToneField {
  cv::Mat dark;  // CV_32FC1
  double lo = 0, hi = 1;
  bool empty = true;  // no plant pixel
};

ToneField tone_field(const cv::Mat& color, const cv::Mat& plant, const PenParams& p,
                     double detail_px) {
  ToneField t;
  cv::Mat weight, mask;
  t.dark = tone_darkness(color);
  plant.convertTo(mask, CV_32F, 1.0 / 255.0);
  const double sigma = std::max(1.0, detail_px);
  cv::GaussianBlur(t.dark, t.dark, {0, 0}, sigma);
  cv::GaussianBlur(mask, weight, {0, 0}, sigma);
  cv::divide(t.dark, cv::max(weight, 1e-6f), t.dark);
  std::vector<float> values;
  for (int y = 0; y < plant.rows; ++y)
    for (int x = 0; x < plant.cols; ++x)
      if (plant.at<uint8_t>(y, x)) values.push_back(t.dark.at<float>(y, x));
  if (values.empty()) return t;
  auto quantile = [&](double q) {
    const size_t k = std::min(values.size() - 1, size_t(q * double(values.size() - 1) + 0.5));
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
    return double(values[k]);
  };
  t.lo = quantile(p.lightest);
  t.hi = std::max(quantile(p.darkest), t.lo + 1e-3);
  t.empty = false;
  return t;
}

// Where strokes may be drawn: the plant, and its crown at ink.detail: from the scene as the ink
// outline's (passes/ink_abstraction.h crown_field over passes/crown_coverage.h), else the
// raster's crown_shape with its thin parts.
cv::Mat stroke_region(const ToneImages& in, const ToneView& view, const cv::Mat& plant,
                      double detail_px) {
  if (!in.samples) {
    const CrownShape crown = crown_shape(plant, detail_px);
    return crown.body | crown.thin | plant;
  }
  Camera camera;
  camera.view = view.view;
  camera.proj = view.proj;
  camera.ortho = view.ortho;
  double f = 1.0;
  const cv::Size size = working_size(plant.size(), std::max(2.0, detail_px), f);
  const cv::Mat coverage = crown_coverage(*in.samples, camera, size, 0.25 * kWorkingDetail);
  cv::Mat inside;
  cv::resize(crown_field(coverage, detail_px / f).body, inside, plant.size(), 0, 0,
             cv::INTER_NEAREST);
  return inside | plant;
}

// One hatching stroke or stipple dot at anchor `a` (layer 1 crosses layer 0), clipped to
// `inside`; false when nothing is left.
bool tone_mark(const Anchor& a, int layer, const PenParams& p, double length, const cv::Mat& inside,
               Stroke& s) {
  const cv::Point2f centre(a.cx, a.cy);
  if (p.tone == PenTone::Stipple) {
    s.points = {{centre.x, centre.y}};
    return true;
  }
  const uint64_t seed = uint64_t(p.seed);
  const double phi =
      (p.angle + p.angle_jitter * (2.0 * hash01(uint64_t(a.region), seed * 4 + 5) - 1.0) +
       90.0 * layer) *
      std::numbers::pi / 180.0;
  const double len = length * (0.75 + 0.5 * hash01(a.key, seed * 4 + 6));
  const cv::Point2f dir(float(std::cos(phi)), float(-std::sin(phi)));  // y points down
  return clipped_line(inside, centre, dir, len, s);
}

}  // namespace

StrokeDrawing tone_strokes(const ToneImages& in, const ToneView& view, const PenParams& p,
                           double detail) {
  const cv::Size size = in.color.size();
  const double scale = reference_scale(size);
  StrokeDrawing d;
  d.size = size;
  if (!p.enabled() || view.units_per_px <= 0.0) return d;
  SYLVA_CHECK(p.tone == PenTone::Hatching || p.tone == PenTone::Stipple, "pen.tone: unknown");
  cv::Mat alpha, plant;
  cv::extractChannel(in.color, alpha, 3);
  plant = alpha >= 128;
  const ToneField tone = tone_field(in.color, plant, p, detail * scale);
  if (tone.empty) return d;
  const cv::Mat inside = stroke_region(in, view, plant, detail * scale);
  // Small renders: strokes no thinner than 1 px, and then no closer than 4 widths (spacing and
  // length grow together), so the tone does not fill in solid.
  const double width = std::max(1.0, p.width * scale);
  const double grow = std::max(1.0, 4.0 * width / (p.spacing * scale));
  const double spacing = p.spacing * scale * grow, length = p.length * scale * grow;
  const uint64_t seed = uint64_t(p.seed);
  // Cubes of half the spacing: enough candidates for the densest tone.
  const std::vector<Anchor> anchors =
      scene_anchors(in, view, 0.5 * spacing * view.units_per_px, seed, inside, detail * scale);
  Stroke s;
  s.cls = LineClass::Tone;
  s.opacity = p.opacity;
  s.width = float(width);
  // Each anchor decides alone, by its seeded rank against the tone's share of the candidates
  // around it, so one stroke coming or going never moves another (no cascade from frame to
  // frame). Layer 0 everywhere with tone; layer 1, crossing it, where the tone passes
  // pen.cross, with its own ranks, so the crossing strokes do not sit on the first layer's.
  const std::vector<double> per_cell = candidates_per_cell(anchors, size, spacing);
  for (int layer = 0; layer < (p.tone == PenTone::Hatching && p.cross < 1.0f ? 2 : 1); ++layer)
    for (size_t i = 0; i < anchors.size(); ++i) {
      const Anchor& a = anchors[i];
      const double darkness = tone.dark.at<float>(a.y, a.x);
      double t = std::pow(std::clamp((darkness - tone.lo) / (tone.hi - tone.lo), 0.0, 1.0),
                          double(p.gamma));
      if (layer == 1) t = (t - p.cross) / (1.0 - p.cross);
      const double rank = layer == 0 ? a.rank : hash01(a.key, seed * 4 + 7);
      if (t <= 0.02 || rank >= t / per_cell[i]) continue;
      if (tone_mark(a, layer, p, length, inside, s)) d.strokes.push_back(s);
    }
  return d;
}

Handle<StrokeDrawing> add_tone_pass(RenderGraph& g, const ToneResources& in, const ToneView& view,
                                    const PenParams& p, double detail) {
  SYLVA_CHECK(in.position.valid() && in.color.valid(),
              "tone pass needs the position and color resources");
  std::vector<ResourceRef> reads = {in.position, in.color};
  if (in.id.valid()) reads.push_back(in.id);
  if (in.samples.valid()) reads.push_back(in.samples);
  const auto out = g.resource<StrokeDrawing>("tone-strokes");
  g.add_pass(
      "tone-strokes", reads, {out},
      [=](PassContext& ctx) {
        ToneImages images;
        images.position = ctx.read<cv::Mat>(in.position);
        images.color = ctx.read<cv::Mat>(in.color);
        if (in.id.valid()) images.id = ctx.read<cv::Mat>(in.id);
        if (in.samples.valid())
          images.samples = ctx.read<std::shared_ptr<const SurfaceSamples>>(in.samples);
        ctx.write(out, tone_strokes(images, view, p, detail));
      },
      RenderGraph::Threads::Any);
  return out;
}

}  // namespace sylva

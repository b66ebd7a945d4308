#include "passes/hatch_groups.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/random.h"
#include "passes/ink_abstraction.h"
#include "passes/pass_common.h"
#include "passes/tone_rank.h"

namespace sylva {

namespace {

// One group of parallel lines: its region's label in `regions`, anchor and direction (working
// px, unit, y down) and the box its region spans.
struct Group {
  int label = 0;
  cv::Point2f anchor, dir;
  cv::Rect box;
};

// The tone of a line: lines in an ordered dither of 4 (k = 0, 2, 1, 3 mod 4 get 1/8, 3/8, 5/8,
// 7/8), so every tone has its share of lines, evenly spaced.
float line_level(int64_t k) {
  static constexpr float kLevels[4] = {0.125f, 0.625f, 0.375f, 0.875f};
  return kLevels[((k % 4) + 4) % 4];
}

double group_hash01(uint64_t a, uint64_t b) {
  uint64_t s = a * 0x9e3779b97f4a7c15ull ^ (b + 0x632be59bd9b4e019ull);
  splitmix64(s);
  return uniform01(s);
}

float smooth01(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / std::max(1e-6f, e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

struct HatchStyle {
  double spacing = 4;  // working px between neighbouring lines
  double length = 8;   // working px of a stroke
  float width = 1;     // output px
  float opacity = 1;
  float cross = 1;  // tone from which the crossing layer starts
  uint64_t seed = 1;
  double factor = 1;  // output px per working px
};

// The strokes of group g's layer (0: along dir, 1: across it) where regions == g.label and the
// tone passes each line's level.
void hatch_group(const Group& g, int layer, const cv::Mat& regions, const cv::Mat& tone,
                 const HatchStyle& s, std::vector<Stroke>& out) {
  const cv::Point2f d = layer == 0 ? g.dir : cv::Point2f(-g.dir.y, g.dir.x);
  const cv::Point2f m(-d.y, d.x);
  // The box's extent along d and m, relative to the anchor.
  float u0 = 1e30f, u1 = -1e30f, v0 = 1e30f, v1 = -1e30f;
  for (const cv::Point2f c : {cv::Point2f(float(g.box.x), float(g.box.y)),
                              cv::Point2f(float(g.box.br().x), float(g.box.y)),
                              cv::Point2f(float(g.box.x), float(g.box.br().y)),
                              cv::Point2f(float(g.box.br().x), float(g.box.br().y))}) {
    const cv::Point2f r = c - g.anchor;
    u0 = std::min(u0, r.dot(d)), u1 = std::max(u1, r.dot(d));
    v0 = std::min(v0, r.dot(m)), v1 = std::max(v1, r.dot(m));
  }
  const int64_t k0 = int64_t(std::floor(v0 / s.spacing)), k1 = int64_t(std::ceil(v1 / s.spacing));
  const float from = layer == 0 ? 0.0f : s.cross;
  for (int64_t k = k0; k <= k1; ++k) {
    const float level = from + (1.0f - from) * line_level(k);
    const double stagger =
        s.length * group_hash01(uint64_t(g.label) * 4 + uint64_t(layer), uint64_t(k) ^ s.seed);
    Stroke st;
    st.cls = LineClass::Tone;
    st.opacity = s.opacity;
    st.width = s.width;
    int64_t piece = INT64_MIN;
    auto flush = [&]() {
      if (st.points.size() >= 2 && double(st.points.size()) >= 0.3 * s.length) out.push_back(st);
      st.points.clear();
      st.widths.clear();
    };
    for (double u = std::floor(u0); u <= u1; u += 1.0) {
      const cv::Point2f q = g.anchor + float(k * s.spacing) * m + float(u) * d;
      const int x = int(std::floor(q.x)), y = int(std::floor(q.y));
      const int64_t here = int64_t(std::floor((u - stagger) / s.length));
      // A short gap at each stroke's start, so the strokes read as strokes.
      const bool gap = (u - stagger) - double(here) * s.length < 0.15 * s.length;
      float t = -1.0f;
      if (x >= 0 && y >= 0 && x < regions.cols && y < regions.rows &&
          regions.at<int>(y, x) == g.label)
        t = tone.at<float>(y, x);
      if (t <= level || gap || here != piece) flush();
      piece = here;
      if (t <= level || gap) continue;
      st.points.emplace_back(q.x * float(s.factor), q.y * float(s.factor));
      st.widths.push_back(s.width * smooth01(level, level + 0.1f, t));
    }
    flush();
  }
}

// Tone t in [0, 1] from a rank image (0 off the regions), smoothed over the regions.
cv::Mat tone_of(const cv::Mat& rank, const cv::Mat& inside, double sigma, const PenParams& p) {
  cv::Mat mask, r, w;
  inside.convertTo(mask, CV_32F, 1.0 / 255.0);
  cv::GaussianBlur(rank.mul(mask), r, {0, 0}, std::max(0.5, sigma));
  cv::GaussianBlur(mask, w, {0, 0}, std::max(0.5, sigma));
  cv::divide(r, cv::max(w, 1e-6f), r);
  cv::Mat t(rank.size(), CV_32FC1);
  const float lo = p.lightest, hi = std::max(p.darkest, p.lightest + 1e-3f);
  for (int y = 0; y < r.rows; ++y)
    for (int x = 0; x < r.cols; ++x)
      t.at<float>(y, x) =
          std::pow(std::clamp((r.at<float>(y, x) - lo) / (hi - lo), 0.0f, 1.0f), p.gamma);
  return t;
}

// The foliage groups: one per leaf cluster the front buffer shows, anchored at its primitives'
// area-weighted centre, along the surface's tangent.
std::vector<Group> clump_groups(const LeafLayer& layer, const cv::Mat& normal, const PenParams& p,
                                cv::Mat& regions) {
  const cv::Mat& front = layer.front;
  regions = cv::Mat(front.size(), CV_32SC1, cv::Scalar(0));
  std::map<uint32_t, int> label_of;
  std::vector<Group> groups;
  std::vector<cv::Vec3d> normals;
  // Each primitive's label, found in the map once (0 = not yet).
  std::vector<int> label_of_front(layer.clusters.size(), 0);
  for (int y = 0; y < front.rows; ++y)
    for (int x = 0; x < front.cols; ++x) {
      const int f = front.at<int>(y, x);
      if (f <= 0) continue;
      int& label = label_of_front[size_t(f - 1)];
      if (label == 0) {
        auto [it, fresh] =
            label_of.try_emplace(layer.clusters[size_t(f - 1)], int(groups.size()) + 1);
        if (fresh) {
          groups.push_back({it->second, {}, {}, cv::Rect(x, y, 1, 1)});
          normals.emplace_back(0, 0, 0);
        }
        label = it->second;
      }
      Group& g = groups[size_t(label - 1)];
      g.box |= cv::Rect(x, y, 1, 1);
      regions.at<int>(y, x) = label;
      const int ox = std::min(normal.cols - 1, int((x + 0.5) * layer.factor)),
                oy = std::min(normal.rows - 1, int((y + 0.5) * layer.factor));
      const cv::Vec3f n = normal.at<cv::Vec3f>(oy, ox);
      const double len = cv::norm(n);
      if (len > 0.0) normals[size_t(label - 1)] += cv::Vec3d(n) / len;
    }
  std::vector<double> weight(groups.size(), 0.0);
  std::vector<cv::Point2d> sum(groups.size());
  for (size_t i = 0; i < layer.clusters.size(); ++i) {
    const auto it = label_of.find(layer.clusters[i]);
    if (it == label_of.end()) continue;
    const double a = layer.areas[i];
    weight[size_t(it->second - 1)] += a;
    sum[size_t(it->second - 1)] += a * cv::Point2d(layer.centres[i]);
  }
  const double base = p.angle * std::numbers::pi / 180.0;
  const cv::Point2f along(float(std::cos(base)), float(-std::sin(base)));  // y down
  for (size_t i = 0; i < groups.size(); ++i) {
    Group& g = groups[i];
    g.anchor = weight[i] > 0.0 ? cv::Point2f(sum[i] / weight[i])
                               : cv::Point2f(float(g.box.x + 0.5 * g.box.width),
                                             float(g.box.y + 0.5 * g.box.height));
    // The normal's projection (view y up, image y down); the tangent across it.
    const cv::Vec3d n = normals[i] * (1.0 / std::max(1.0, cv::norm(normals[i])));
    cv::Point2f tangent{static_cast<float>(n[1]), static_cast<float>(n[0])};  // ⟂ (n.x, -n.y)
    const float reach = std::hypot(tangent.x, tangent.y);
    if (tangent.dot(along) < 0.0f) tangent = -tangent;
    const float w = std::clamp(reach / 0.6f, 0.0f, 1.0f) * 0.7f;
    cv::Point2f dir = (1.0f - w) * along + (reach > 0.0f ? w / reach : 0.0f) * tangent;
    const float len = std::hypot(dir.x, dir.y);
    g.dir = len > 1e-6f ? dir * (1.0f / len) : along;
  }
  return groups;
}

// The wood groups: one per connected piece of the wood the front buffer shows, along its
// principal axis; labels after `first`.
std::vector<Group> wood_groups(const LeafLayer& layer, int first, cv::Mat& regions) {
  cv::Mat wood = layer.front == kWoodFront, labels, stats, centres;
  const int n = cv::connectedComponentsWithStats(wood, labels, stats, centres, 8, CV_32S);
  std::vector<Group> groups;
  std::vector<cv::Vec3d> moments(size_t(std::max(0, n)), cv::Vec3d(0, 0, 0));
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x)
      if (const int l = labels.at<int>(y, x); l > 0) {
        const double dx = x - centres.at<double>(l, 0), dy = y - centres.at<double>(l, 1);
        moments[size_t(l)] += cv::Vec3d(dx * dx, dx * dy, dy * dy);
        regions.at<int>(y, x) = first + l;
      }
  for (int l = 1; l < n; ++l) {
    const cv::Vec3d& mo = moments[size_t(l)];
    const double angle = 0.5 * std::atan2(2.0 * mo[1], mo[0] - mo[2]);
    Group g;
    g.label = first + l;
    g.anchor = cv::Point2f(float(centres.at<double>(l, 0)), float(centres.at<double>(l, 1)));
    g.dir = cv::Point2f(float(std::cos(angle)), float(std::sin(angle)));
    g.box = cv::Rect(stats.at<int>(l, cv::CC_STAT_LEFT), stats.at<int>(l, cv::CC_STAT_TOP),
                     stats.at<int>(l, cv::CC_STAT_WIDTH), stats.at<int>(l, cv::CC_STAT_HEIGHT));
    groups.push_back(g);
  }
  return groups;
}

// The wood's tone: its darkness (the bark's shading) ranked among the wood's pixels.
cv::Mat wood_rank(const LeafLayer& layer, const cv::Mat& color) {
  const cv::Mat wood = layer.front == kWoodFront;
  cv::Mat rank(layer.front.size(), CV_32FC1, cv::Scalar(0));
  if (cv::countNonZero(wood) == 0) return rank;
  cv::Mat dark = tone_darkness(color);
  cv::resize(dark, dark, layer.front.size(), 0, 0, cv::INTER_AREA);
  std::vector<float> values;
  for (int y = 0; y < wood.rows; ++y)
    for (int x = 0; x < wood.cols; ++x)
      if (wood.at<uint8_t>(y, x)) values.push_back(dark.at<float>(y, x));
  std::sort(values.begin(), values.end());
  for (int y = 0; y < wood.rows; ++y)
    for (int x = 0; x < wood.cols; ++x)
      if (wood.at<uint8_t>(y, x)) {
        const float v = dark.at<float>(y, x);
        // Mid-rank: ties (an evenly shaded branch) share the middle of their run.
        const auto lo = std::lower_bound(values.begin(), values.end(), v);
        const auto hi = std::upper_bound(lo, values.end(), v);
        rank.at<float>(y, x) =
            float((double(lo - values.begin()) + 0.5 * double(hi - lo)) / double(values.size()));
      }
  return rank;
}

}  // namespace

StrokeDrawing hatch_groups(const LeafLayer& layer, const cv::Mat& normal, const cv::Mat& color,
                           const PenParams& p, double detail, HatchWhat what) {
  StrokeDrawing d;
  d.size = layer.drawing.size;
  d.color = layer.drawing.color;
  if (layer.front.empty()) return d;
  const double scale = reference_scale(d.size), f = layer.factor;
  HatchStyle s;
  s.factor = f;
  s.width = float(std::max(1.0, p.width * scale));
  // Small renders: lines no closer than 4 widths (spacing and length grow together).
  const double grow = std::max(1.0, 4.0 * s.width / (p.spacing * scale));
  s.spacing = p.spacing * scale * grow / f;
  s.length = std::max(2.0, p.length * scale * grow / f);
  s.opacity = p.opacity;
  s.cross = p.cross;
  s.seed = uint64_t(p.seed);
  cv::Mat regions;
  // The clumps are found even when only the wood is hatched: their count numbers the wood's
  // groups (whose labels seed the strokes), so `ink`'s wood hatching is `pen`'s.
  std::vector<Group> groups = clump_groups(layer, normal, p, regions);
  cv::Mat tone(layer.front.size(), CV_32FC1, cv::Scalar(0));
  if (what.foliage) {
    // A clump as the eye groups it: small pieces of other clusters seen through it belong to it.
    regions = majority_labels(regions, std::max(1, int(std::lround(0.5 * detail * scale / f))));
    tone = tone_of(layer.rank, regions > 0, detail * scale / f, p);
  }
  const std::vector<Group> wood = wood_groups(layer, int(groups.size()), regions);
  const cv::Mat wood_tone =
      tone_of(wood_rank(layer, color), layer.front == kWoodFront, 0.5 * detail * scale / f, p);
  wood_tone.copyTo(tone, layer.front == kWoodFront);
  if (!what.foliage) groups.clear();
  if (what.wood) groups.insert(groups.end(), wood.begin(), wood.end());
  // Wood is hatched along its axis only: crossing lines on a branch read as a net.
  const size_t clumps = what.foliage ? groups.size() - (what.wood ? wood.size() : 0) : 0;
  for (int l = 0; l < (p.cross < 1.0f ? 2 : 1); ++l)
    for (size_t i = 0; i < (l == 0 ? groups.size() : clumps); ++i)
      hatch_group(groups[i], l, regions, tone, s, d.strokes);
  return d;
}

Handle<StrokeDrawing> add_hatch_groups_pass(RenderGraph& g, Handle<LeafLayer> layer,
                                            ImageHandle normal, ImageHandle color,
                                            const PenParams& p, double detail, HatchWhat what) {
  SYLVA_CHECK(normal.valid() && color.valid(), "hatching needs the normal and color resources");
  const auto out = g.resource<StrokeDrawing>("hatching");
  g.add_pass("hatching", {layer, normal, color}, {out}, [=](PassContext& ctx) {
    ctx.write(out, hatch_groups(ctx.read<LeafLayer>(layer), ctx.read<cv::Mat>(normal),
                                ctx.read<cv::Mat>(color), p, detail, what));
  });
  return out;
}

}  // namespace sylva

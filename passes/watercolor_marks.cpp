#include "passes/watercolor_marks.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/error.h"
#include "core/random.h"
#include "npr/sample_shadow.h"
#include "passes/leaf_outlines.h"
#include "passes/pass_common.h"
#include "passes/tone_rank.h"
#include "passes/watercolor_common.h"
#include "passes/watercolor_light.h"

namespace sylva {

namespace {

using watercolor_internal::blur;
using watercolor_internal::srgb_tables;
using watercolor_internal::to_density;

// The blurred depth test: a dab this far (a share of the plant's depth extent) in front of the
// crown's blurred depth shows fully, as far behind not at all; the blur is this many dabs wide.
constexpr float kDepthBand = 0.04f;
constexpr double kDepthBlurDabs = 2.0;
// The share of its pigment a dab keeps deep behind the blurred depth.
constexpr float kBehindShare = 0.3f;
// A dab's pigment, as a share of its own colour's density at watercolor.marks = 1: from
// kLitShare of it on the lightest leaves to all of it in the deepest shadow.
constexpr float kGain = 0.9f;
constexpr float kLitShare = 0.15f;
// How much of the darkness is the key light's shadow through the crown (the rest the tone rank).
constexpr float kShadowShare = 0.4f;
// A dab's edge carries this share of its heart's pigment; neighbours differ by up to +-kVary.
constexpr float kEdgeShare = 0.55f;
constexpr float kVary = 0.25f;
// Inside a wash a touch is its difference from the dabs' mean over this many dabs (sigma).
constexpr double kMeanDabs = 1.5;
// On bare paper a touch is the only paint there (a willow's strands, a pine's outer tufts
// beyond the washes): it carries this many times its pigment, so a lit strand still reads.
constexpr float kOnPaper = 2.5f;

struct Dab {
  float weight = 0;  // the share of the colour's density it lays
  cv::Vec3f density;
};

// The wood seen at the working size (the id buffer's wood, a little opened): the dabs' z-buffer
// keeps it in front, as a painter leaves the trunk bare of leaf touches.
void mark_wood(const WatercolorMarkImages& in, double scale, LeafLayer& work) {
  if (in.wood_cluster == 0 || in.id.empty()) return;
  cv::Mat seen;
  cv::resize(watercolor_internal::seen_wood(in.id, in.wood_cluster, scale), seen, work.front.size(),
             0, 0, cv::INTER_AREA);
  for (int y = 0; y < seen.rows; ++y)
    for (int x = 0; x < seen.cols; ++x)
      if (seen.at<uint8_t>(y, x) > 127) work.front.at<int>(y, x) = kWoodFront;
}

// The crown's depth blurred over its own pixels (normalised convolution), at the working size.
cv::Mat blurred_depth(const LeafLayer& work, float sigma) {
  cv::Mat cover(work.depth.size(), CV_32F, cv::Scalar(0)), depth = cover.clone();
  for (int y = 0; y < cover.rows; ++y)
    for (int x = 0; x < cover.cols; ++x)
      if (work.front.at<int>(y, x) > 0) {
        cover.at<float>(y, x) = 1.0f;
        depth.at<float>(y, x) = work.depth.at<float>(y, x);
      }
  cv::Mat d = blur(depth, sigma), c = blur(cover, sigma), out;
  cv::divide(d, cv::max(c, 1e-4), out);
  return out;
}

// A number in [0, 1) fixed to the dab's place in the scene.
float place_hash(const glm::vec3& p) {
  uint32_t bits[3];
  std::memcpy(bits, &p, sizeof bits);
  uint64_t state = (uint64_t(bits[0]) << 32) ^ (uint64_t(bits[1]) << 16) ^ bits[2];
  return float(uniform01(state));
}

// The colour at `c` (working px) of the colour image at the working size, un-premultiplied,
// as display values.
cv::Vec3f colour_at(const cv::Mat& small, cv::Point2f c) {
  const int x = std::clamp(int(c.x), 0, small.cols - 1),
            y = std::clamp(int(c.y), 0, small.rows - 1);
  const cv::Vec4f v = small.at<cv::Vec4f>(y, x);
  if (v[3] < 1e-3f) return {1.0f, 1.0f, 1.0f};
  return {std::min(1.0f, v[0] / v[3]), std::min(1.0f, v[1] / v[3]), std::min(1.0f, v[2] / v[3])};
}

// Each dab's pigment: its colour's density, scaled by the blurred depth test, its darkness
// (tone rank and the key light's shadow) and its seeded variation.
std::vector<Dab> dab_pigments(const WatercolorMarkImages& in, const WatercolorMarkParams& p,
                              const std::vector<Primitive>& prims, const LeafLayer& work,
                              double dab_px) {
  const ToneRank tone = tone_rank(in.color, work.front.size(), std::max(1.0, 2.0 * dab_px));
  SampleShadow shadow;
  if (in.light.on && in.samples && !in.light.sphere.empty())
    shadow = sample_shadow_map(*in.samples, in.light.sphere, in.light.toward, in.light.point,
                               kShadowMapSize, 1.0f);
  const cv::Mat depth = blurred_depth(work, float(kDepthBlurDabs * dab_px));
  cv::Mat small;
  in.color.convertTo(small, CV_32FC4, 1.0 / 255.0);
  cv::resize(small, small, work.front.size(), 0, 0, cv::INTER_AREA);
  const float band = std::max(1e-6f, kDepthBand * (work.far - work.near));
  const auto& srgb = srgb_tables();
  std::vector<Dab> dabs(prims.size());
  for (size_t i = 0; i < prims.size(); ++i) {
    const Primitive& q = prims[i];
    const float behind = watercolor_internal::sample(depth, q.c.x, q.c.y) - q.depth;
    const float show = kBehindShare + (1.0f - kBehindShare) * smoothstep(-band, band, behind);
    const float rank = tone.empty() ? 0.5f : tone.rank_near(q.c);
    const float dark =
        (1.0f - kShadowShare) * rank + kShadowShare * (1.0f - light_reaching(shadow, q.world));
    const float vary = 1.0f + kVary * (2.0f * place_hash(q.world) - 1.0f);
    dabs[i].weight =
        p.strength * kGain * show * vary * (kLitShare + (1.0f - kLitShare) * dark * dark);
    const cv::Vec3f c = colour_at(small, q.c);
    for (int ch = 0; ch < 3; ++ch)
      dabs[i].density[ch] = dabs[i].weight * to_density(srgb, c[ch]);
  }
  return dabs;
}

// The front dab's pigment at every working pixel, lighter towards its edge.
cv::Mat lay_dabs(const std::vector<Primitive>& prims, const std::vector<Dab>& dabs,
                 const LeafLayer& work) {
  cv::Mat out(work.front.size(), CV_32FC3, cv::Scalar::all(0));
  for_bands(out.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const int* front = work.front.ptr<int>(y);
      cv::Vec3f* o = out.ptr<cv::Vec3f>(y);
      for (int x = 0; x < out.cols; ++x) {
        if (front[x] <= 0) continue;
        const size_t i = size_t(front[x] - 1);
        if (dabs[i].weight <= 0.0f) continue;
        const Primitive& q = prims[i];
        const double dx = x + 0.5 - q.c.x, dy = y + 0.5 - q.c.y;
        const double r2 = q.qa() * dx * dx + 2.0 * q.qb() * dx * dy + q.qc() * dy * dy;
        const float heart = 1.0f - (1.0f - kEdgeShare) * float(std::min(1.0, r2));
        o[x] = dabs[i].density * heart;
      }
    }
  });
  return out;
}

// The dabs as touches: on bare paper as they are (a willow's strands beyond its washes), and
// inside a wash as their difference from their own mean over a few dabs, so they give the
// wash its leaves without shifting its value (the light stays the washes').
cv::Mat touches(const cv::Mat& laid, const cv::Mat& density, double dab_px) {
  cv::Mat wash;
  cv::resize(density, wash, laid.size(), 0, 0, cv::INTER_AREA);
  const cv::Mat mean = blur(laid, float(kMeanDabs * dab_px));
  cv::Mat out(laid.size(), CV_32FC3);
  for (int y = 0; y < out.rows; ++y) {
    const cv::Vec3f* l = laid.ptr<cv::Vec3f>(y);
    const cv::Vec3f* m = mean.ptr<cv::Vec3f>(y);
    const cv::Vec3f* w = wash.ptr<cv::Vec3f>(y);
    cv::Vec3f* o = out.ptr<cv::Vec3f>(y);
    for (int x = 0; x < out.cols; ++x) {
      const float cover = watercolor_internal::wash_cover(w[x]);
      o[x] = l[x] * (1.0f + (kOnPaper - 1.0f) * (1.0f - cover)) - cover * m[x];
    }
  }
  return out;
}

// `small` added to `density` at its size, bilinear (no full-size copy of it is made); the sum
// is kept at or above 0 (a touch lighter than its wash lifts pigment, never below the paper).
void add_upsampled(const cv::Mat& small, cv::Mat& density) {
  const float fx = float(small.cols) / float(density.cols);
  const float fy = float(small.rows) / float(density.rows);
  cv::Mat ch[3];
  cv::split(small, ch);
  for_bands(density.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      cv::Vec3f* d = density.ptr<cv::Vec3f>(y);
      const float sy = (float(y) + 0.5f) * fy - 0.5f;
      for (int x = 0; x < density.cols; ++x) {
        const float sx = (float(x) + 0.5f) * fx - 0.5f;
        for (int c = 0; c < 3; ++c)
          d[x][c] = std::max(0.0f, d[x][c] + watercolor_internal::sample(ch[c], sx, sy));
      }
    }
  });
}

}  // namespace

void glaze_marks(const WatercolorMarkImages& in, const WatercolorMarkParams& p, cv::Mat& density) {
  if (!(p.strength > 0.0f) || !in.pieces || in.pieces->size() == 0 || in.color.empty()) return;
  const cv::Size size = in.color.size();
  SYLVA_CHECK(density.size() == size && density.type() == CV_32FC3,
              "glaze_marks: the density is CV_32FC3 of the colour's size");
  const double scale = reference_scale(size);
  const double least_px = p.size * scale;  // the smallest dab's diameter, px
  LeafLayer work;
  work.factor = std::max(1.0, least_px / kPrimitivePx);
  const cv::Size wsize(std::max(1, int(std::lround(size.width / work.factor))),
                       std::max(1, int(std::lround(size.height / work.factor))));
  work.front = cv::Mat(wsize, CV_32SC1, cv::Scalar(0));
  work.depth = cv::Mat(wsize, CV_32FC1, cv::Scalar(std::numeric_limits<float>::infinity()));
  mark_wood(in, scale, work);
  LeafImages li;
  li.pieces = in.pieces;
  li.camera = in.camera;
  li.color = in.color;
  const std::vector<Primitive> prims = project_primitives(
      li, LeafShape::Auto, work.factor, float(std::max(0.5, 0.5 * least_px / work.factor)),
      least_px * in.units_per_px);
  if (prims.empty()) return;
  paint_primitives(prims, work);
  work.near = std::numeric_limits<float>::max();
  for (const Primitive& q : prims)
    work.near = std::min(work.near, q.depth), work.far = std::max(work.far, q.depth);
  const double dab_px = least_px / work.factor;
  const std::vector<Dab> dabs = dab_pigments(in, p, prims, work, dab_px);
  const cv::Mat laid = blur(lay_dabs(prims, dabs, work), 0.6f);
  add_upsampled(touches(laid, density, dab_px), density);
}

void glaze_leaf_marks(const WatercolorImages& in, const WatercolorParams& p, cv::Mat& density) {
  if (!(p.marks > 0.0f) || !in.pieces) return;
  WatercolorMarkImages m;
  m.pieces = in.pieces;
  m.camera = in.camera;
  m.color = in.color;
  m.id = in.id;
  m.wood_cluster = in.wood_cluster;
  m.units_per_px = in.units_per_px;
  m.samples = in.samples;
  m.light = in.light;
  glaze_marks(m, {.strength = p.marks, .size = p.mark_size}, density);
}

}  // namespace sylva

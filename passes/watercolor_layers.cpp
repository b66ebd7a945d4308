#include "passes/watercolor_layers.h"

#include <algorithm>
#include <cmath>

#include "passes/watercolor.h"

namespace sylva::watercolor_internal {

namespace {

// How far (as blurred coverage of known pixels) a wash continues under the clusters in front
// of it: the confidence of the normalised convolution reaches 1 at this value, so the wash
// ends about two blur radii under its occluder.
constexpr float kUnderConfidence = 0.06f;
// The share of a wash's pigment that shows where a nearer cluster covers it.
constexpr float kUnderStrength = 0.35f;
// The blurred depth test's transition: a leaf this far (in standard deviations of its
// cluster's depth) in front of its blurred surroundings shows all its detail, as far behind none.
constexpr float kDetailBand = 0.3f;

// Bilinear in a CV_32FC2 grid at (x, y) in grid cells (cell centres at integer + 0.5 - 0.5).
cv::Vec2f sample2(const cv::Mat& m, float x, float y) {
  x = std::clamp(x, 0.0f, float(m.cols - 1));
  y = std::clamp(y, 0.0f, float(m.rows - 1));
  const int x0 = std::min(int(x), m.cols - 1), y0 = std::min(int(y), m.rows - 1);
  const int x1 = std::min(x0 + 1, m.cols - 1), y1 = std::min(y0 + 1, m.rows - 1);
  const float ax = x - float(x0), ay = y - float(y0);
  const cv::Vec2f a = m.at<cv::Vec2f>(y0, x0), b = m.at<cv::Vec2f>(y0, x1);
  const cv::Vec2f c = m.at<cv::Vec2f>(y1, x0), d = m.at<cv::Vec2f>(y1, x1);
  return (1 - ay) * ((1 - ax) * a + ax * b) + ay * ((1 - ax) * c + ax * d);
}

// The wobble's grid: cells of kWobbleCell px (or the small grid's, if coarser). The paper's slope
// is smooth at that scale (its finest octave is two grains, 6 px at 1024 px), and evaluating it
// at every pixel of every wash was most of the pass's time.
constexpr int kWobbleCell = 2;

// The wobble displacement (px) at the cells of `g` px over `roi`: the slope of the layer's
// paper at the cell centre's canvas position, scaled and bounded.
cv::Mat wobble_grid(const Shared& s, const Layer& layer, const cv::Rect& roi, int g) {
  const int sw = (roi.width + g - 1) / g, sh = (roi.height + g - 1) / g;
  cv::Mat out(sh, sw, CV_32FC2);
  cv::parallel_for_(cv::Range(0, sh), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y)
      for (int x = 0; x < sw; ++x) {
        const float px = float(roi.x) + (float(x) + 0.5f) * float(g) - layer.canvas.x;
        const float py = float(roi.y) + (float(y) + 0.5f) * float(g) - layer.canvas.y;
        const cv::Vec2f g = s.paper->slope(px, py) * s.wobble_gain;
        out.at<cv::Vec2f>(y, x) = {std::clamp(g[0], -s.max_wobble, s.max_wobble),
                                   std::clamp(g[1], -s.max_wobble, s.max_wobble)};
      }
  });
  return out;
}

}  // namespace

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

  // Full resolution: the mask looked up at a position displaced along the slope of the wash's
  // own paper (Bousseau's wobbling), both bilinear from their grids.
  const float inv_f = 1.0f / float(f);
  const float half = 0.5f * inv_f - 0.5f;  // pixel centre x + 0.5 maps to (x + 0.5) / f - 0.5
  const int g = std::max(f, kWobbleCell);
  const cv::Mat wobble = s.wobble_gain > 0.0f ? wobble_grid(s, layer, roi, g) : cv::Mat();
  cv::Mat mask(h, w, CV_32F);
  for (int y = 0; y < h; ++y) {
    float* m = mask.ptr<float>(y);
    const float sy = float(y) * inv_f + half;
    for (int x = 0; x < w; ++x) {
      const float sx = float(x) * inv_f + half;
      if (wobble.empty()) {
        m[x] = sample(mask_s, sx, sy);
        continue;
      }
      // Pixel centre x + 0.5 is at (x + 0.5) / g - 0.5 in the wobble's grid.
      const cv::Vec2f d =
          sample2(wobble, (float(x) + 0.5f) / float(g) - 0.5f, (float(y) + 0.5f) / float(g) - 0.5f);
      m[x] = sample(mask_s, sx + d[0] * inv_f, sy + d[1] * inv_f);
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
    const cv::Mat& seen = s.seen.empty() ? s.label : s.seen;
    const int32_t* lab = seen.ptr<int32_t>(roi.y + y) + roi.x;
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

}  // namespace sylva::watercolor_internal

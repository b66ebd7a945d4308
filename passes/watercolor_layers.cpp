#include "passes/watercolor_layers.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "passes/watercolor.h"

namespace sylva::watercolor_internal {

namespace {

// How far (as blurred coverage of known pixels) a wash continues under the clusters in front
// of it: the confidence of the normalised convolution reaches 1 at this value, so the wash
// ends about two blur radii under its occluder.
constexpr float kUnderConfidence = 0.5f;
// The share of a wash's pigment that shows where a nearer cluster covers it.
constexpr float kUnderStrength = 0.35f;
// The blurred depth test's transition: a leaf this far (in standard deviations of its
// cluster's depth) in front of its blurred surroundings shows all its detail, as far behind none.
constexpr float kDetailBand = 0.3f;
// The largest share by which warm_cool = 1 raises red and lowers blue on a wash's lit side
// (the reverse on its shaded side).
constexpr float kWarmCool = 0.12f;

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

// The layer's bounding box padded by the blur and the wobble, clipped to the image.
cv::Rect layer_roi(const Shared& s, const Layer& layer) {
  const int pad = int(std::ceil(3.0f * s.sigma + s.max_wobble)) + 2;
  return cv::Rect(cv::Point(layer.x0 - pad, layer.y0 - pad),
                  cv::Point(layer.x1 + 1 + pad, layer.y1 + 1 + pad)) &
         cv::Rect(cv::Point(0, 0), s.size);
}

// The small grids' scale: f x f pixels a cell; pixel centre x + 0.5 maps to (x + 0.5) / f - 0.5.
struct BlockScale {
  int f;
  float inv_f;
  float half;
  explicit BlockScale(int f_) : f(f_), inv_f(1.0f / float(f_)), half(0.5f * inv_f - 0.5f) {}
  float at(int x) const { return float(x) * inv_f + half; }
};

// The masks at 1/f of the resolution, each cell a share of its f x f block: own = this cluster,
// known = pixels that do not hide it (itself, the background, clusters behind it), own_depth =
// this cluster's depth summed over the block's pixels and divided by their count (with detail).
struct BlockMasks {
  cv::Mat own, known, own_depth;
  cv::Mat paper;  // the background's share (only when gaps are closed)
};

// Sums the layer's pixels over the roi into blocks of f x f (the masks are smooth after the blur,
// and blurring them is most of the pass's time).
BlockMasks block_masks(const Shared& s, const cv::Rect& roi, int k, int f, bool detail) {
  const int w = roi.width, h = roi.height;
  const int sw = (w + f - 1) / f, sh = (h + f - 1) / f;
  BlockMasks b;
  b.own = cv::Mat(sh, sw, CV_32F, cv::Scalar(0));
  b.known = cv::Mat(sh, sw, CV_32F, cv::Scalar(0));
  cv::Mat count(sh, sw, CV_32F, cv::Scalar(0));
  if (detail) b.own_depth = cv::Mat(sh, sw, CV_32F, cv::Scalar(0));
  const bool paper = s.close > 0.0f;
  if (paper) b.paper = cv::Mat(sh, sw, CV_32F, cv::Scalar(0));
  for (int y = 0; y < h; ++y) {
    const int32_t* lab = s.label.ptr<int32_t>(roi.y + y) + roi.x;
    const float* dep = s.depth.ptr<float>(roi.y + y) + roi.x;
    float* o = b.own.ptr<float>(y / f);
    float* kn = b.known.ptr<float>(y / f);
    float* n = count.ptr<float>(y / f);
    float* od = detail ? b.own_depth.ptr<float>(y / f) : nullptr;
    float* pa = paper ? b.paper.ptr<float>(y / f) : nullptr;
    for (int x = 0; x < w; ++x) {
      const int sx = x / f;
      n[sx] += 1.0f;
      if (pa && lab[x] < 0) pa[sx] += 1.0f;
      if (lab[x] == k) {
        o[sx] += 1.0f;
        if (od) od[sx] += dep[x];
      }
      if (lab[x] <= k) kn[sx] += 1.0f;
    }
  }
  b.own /= count;
  b.known /= count;
  if (detail) b.own_depth /= count;
  if (paper) b.paper /= count;
  return b;
}

// The mask closed over gaps up to `radius` cells, taking only the paper's share of each cell:
// the mass's wash covers the paper between its leaves, not the other washes.
void close_over_paper(BlockMasks& b, float radius) {
  const int r = std::max(1, int(std::lround(radius)));
  cv::Mat closed;
  // Nothing of the mask lies beyond the grid (the layer's box, padded): a constant 0 border, or
  // the erosion would keep the dilation along the grid's edge and the wash end there in a
  // straight cut.
  cv::morphologyEx(b.own, closed, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * r + 1, 2 * r + 1}),
                   cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::Mat gain = cv::max(closed - b.own, 0.0f);
  b.own += cv::min(gain, b.paper);
}

// Each block mask blurred (Gaussian, sigma in cells).
BlockMasks blur_masks(const BlockMasks& m, float small_sigma, bool detail) {
  BlockMasks b;
  b.own = blur(m.own, small_sigma);
  b.known = blur(m.known, small_sigma);
  if (detail) b.own_depth = blur(m.own_depth, small_sigma);
  return b;
}

// What a wash is painted from, on the small grid: mask, the blurred mask continued under
// occluders; depth, this cluster's blurred depth (with detail).
struct SmallFields {
  cv::Mat mask, depth;
};

// The blurred mask continued under occluders by normalised convolution (only where enough of
// the neighbourhood is known, so it stops about two blur radii in); the blurred depth of this
// cluster.
SmallFields continue_under_occluders(const BlockMasks& blurred, bool detail) {
  const int sw = blurred.own.cols, sh = blurred.own.rows;
  SmallFields out;
  out.mask.create(sh, sw, CV_32F);
  if (detail) out.depth.create(sh, sw, CV_32F);
  for (int y = 0; y < sh; ++y) {
    const float* bo = blurred.own.ptr<float>(y);
    const float* bk = blurred.known.ptr<float>(y);
    const float* bd = detail ? blurred.own_depth.ptr<float>(y) : nullptr;
    float* m = out.mask.ptr<float>(y);
    float* d = detail ? out.depth.ptr<float>(y) : nullptr;
    for (int x = 0; x < sw; ++x) {
      const float ratio = bk[x] > 1e-6f ? std::min(1.0f, bo[x] / bk[x]) : 0.0f;
      m[x] = ratio * smoothstep(0.0f, kUnderConfidence, bk[x]);
      if (d) d[x] = bo[x] > 1e-6f ? bd[x] / bo[x] : 0.0f;
    }
  }
  return out;
}

// Full resolution: the mask looked up at a position displaced along the slope of the wash's
// own paper (Bousseau's wobbling), both bilinear from their grids.
cv::Mat wobbled_mask(const Shared& s, const Layer& layer, const cv::Rect& roi, const BlockScale& b,
                     const cv::Mat& mask_s) {
  const int w = roi.width, h = roi.height;
  const int g = std::max(b.f, kWobbleCell);
  const cv::Mat wobble = s.wobble_gain > 0.0f ? wobble_grid(s, layer, roi, g) : cv::Mat();
  cv::Mat mask(h, w, CV_32F);
  for_bands(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      float* m = mask.ptr<float>(y);
      const float sy = b.at(y);
      for (int x = 0; x < w; ++x) {
        const float sx = b.at(x);
        if (wobble.empty()) {
          m[x] = sample(mask_s, sx, sy);
          continue;
        }
        // Pixel centre x + 0.5 is at (x + 0.5) / g - 0.5 in the wobble's grid.
        const cv::Vec2f d = sample2(wobble, (float(x) + 0.5f) / float(g) - 0.5f,
                                    (float(y) + 0.5f) / float(g) - 0.5f);
        m[x] = sample(mask_s, sx + d[0] * b.inv_f, sy + d[1] * b.inv_f);
      }
    }
  });
  return mask;
}

// Pigment pooling at the rim: the factor 1 + edge_gain g^3 on the density, g the mask's gradient
// magnitude at x (rows above, at and below it) normalised by grad_norm. Cubed: pigment pools
// in a narrow band at the very rim, not across the whole blur.
float rim_darkening(const float* mu, const float* m, const float* md, int x, int w, float grad_norm,
                    float edge_gain) {
  const float gx = m[std::min(x + 1, w - 1)] - m[std::max(x - 1, 0)];
  const float gy = md[x] - mu[x];
  const float g = std::min(1.0f, std::sqrt(gx * gx + gy * gy) * grad_norm);
  return 1.0f + edge_gain * g * g * g;
}

// Luft & Deussen's blurred depth test: a leaf in front of its blurred surroundings shows its
// shading (its luminance relative to the layer's mean), one behind them melts into the wash,
// with no popping between.
cv::Vec3f leaf_detail(const Shared& s, const Layer& layer, float blurred_depth, float depth,
                      float luminance) {
  cv::Vec3f c = layer.pigment_display;
  const float in_front = (blurred_depth - depth) / layer.depth_spread;
  const float show = s.detail * smoothstep(-kDetailBand, kDetailBand, in_front);
  const float ratio = std::min(luminance / layer.mean_luminance, 2.0f);
  c *= 1.0f + show * (ratio - 1.0f);
  return c;
}

// Wet-in-wet gradation: the wash's value follows the light smoothed at its own scale (the
// pigment's display colour scaled by the smoothed luminance over the layer's mean, bounded),
// its lit side a little warmer and its shaded side cooler by warm_cool (red up and blue down
// where lit, the reverse in shade).
cv::Vec3f gradation(const Shared& s, const Layer& layer, float soft_luminance, cv::Vec3f c) {
  const float ratio = std::clamp(soft_luminance / layer.mean_luminance, 0.4f, 1.8f);
  c *= 1.0f + s.gradation * (ratio - 1.0f);
  const float t = kWarmCool * s.warm_cool * std::clamp((ratio - 1.0f) / 0.5f, -1.0f, 1.0f);
  c[0] *= 1.0f - t;
  c[2] *= 1.0f + t;
  return c;
}

// Where the foliage thins its wash thins with it: the pigment's share at image pixel (x, y),
// from none where the leaves' coverage (Shared::cover) is kThinCover to all of it from
// kFullCover; the wood's wash, and every wash without the scene's samples, keep all of it.
float thin_wash(const Shared& s, const Layer& layer, int x, int y) {
  if (s.cover.empty() || layer.id == s.wood) return 1.0f;
  return smoothstep(kThinCover, kFullCover, s.cover_at(x, y));
}

// Under a nearer wash only part of what lies behind shows (kUnderStrength where it covers
// fully): the glaze over it darkens less than two full washes, as a painter's dilute overlaps
// do, and weakens exactly where the nearer wash lies, so their borders meet without a band of
// doubled pigment or of bare paper.
inline float under(float coverage) {
  return 1.0f - (1.0f - kUnderStrength) * coverage;
}

// One row of a wash (`wash`, `cover`, w px from image column x0 of row y) glazed into `g`.
void glaze_row(GlazeInto& g, int x0, int y, int w, const cv::Vec3f* wash, const float* cover) {
  cv::Vec3f* d = g.density.ptr<cv::Vec3f>(y - g.origin.y) + (x0 - g.origin.x);
  for (int x = 0; x < w; ++x)
    d[x] = (g.weaken ? d[x] * under(cover[x]) : d[x]) + wash[x];
  const cv::Rect& r = g.bark_roi;
  if (!g.weaken || g.bark.empty() || y < r.y || y >= r.br().y) return;
  cv::Vec3f* b = g.bark.ptr<cv::Vec3f>(y - r.y);
  for (int x = std::max(x0, r.x); x < std::min(x0 + w, r.br().x); ++x)
    b[x - r.x] *= under(cover[x - x0]);
}

// The wash over `roi`, glazed into `into` row by row: its optical density and coverage from the
// wobbled mask thresholded, darkened at its rim, tinted with the layer's pigment and its
// leaves' detail.
void wash_density(const Shared& s, const Layer& layer, int k, const BlockScale& b,
                  const cv::Mat& mask, const SmallFields& small, const cv::Rect& roi,
                  GlazeInto& into) {
  const int w = roi.width, h = roi.height;
  const bool detail = s.detail > 0.0f;
  // Gradient magnitude of a blurred unit step peaks at 1 / (sigma sqrt(2 pi)): normalise by it
  // so edge_darkening means the same at every blur.
  const float grad_norm = 0.5f * std::max(s.sigma, 0.5f) * kSqrt2Pi;  // 0.5: central difference
  const float lo = 0.5f - s.half_width, hi = 0.5f + s.half_width;
  const cv::Mat& seen = s.seen.empty() ? s.label : s.seen;
  for_bands(h, [&](int y0, int y1) {
    std::vector<cv::Vec3f> wash_row(static_cast<size_t>(w));
    std::vector<float> cover_row(static_cast<size_t>(w));
    for (int y = y0; y < y1; ++y) {
      const float* m = mask.ptr<float>(y);
      const float* mu = mask.ptr<float>(std::max(y - 1, 0));
      const float* md = mask.ptr<float>(std::min(y + 1, h - 1));
      const int32_t* lab = seen.ptr<int32_t>(roi.y + y) + roi.x;
      const float* lum = s.luminance.ptr<float>(roi.y + y) + roi.x;
      const float* dep = s.depth.ptr<float>(roi.y + y) + roi.x;
      const uint8_t* rim_ok = s.rim_ok.empty() ? nullptr : s.rim_ok.ptr<uint8_t>(roi.y + y) + roi.x;
      const bool soft = !s.soft_luminance.empty();
      const float sy = b.at(y);
      cv::Vec3f* t = wash_row.data();
      float* cov = cover_row.data();
      for (int x = 0; x < w; ++x) {
        const float alpha = smoothstep(lo, hi, m[x]);
        cov[x] = alpha;
        if (alpha <= 0.0f) {
          t[x] = cv::Vec3f(0.0f, 0.0f, 0.0f);
          continue;
        }
        const float sx = b.at(x);
        const float rim = rim_ok ? float(rim_ok[x]) * (1.0f / 255.0f) : 1.0f;
        const float d = rim_darkening(mu, m, md, x, w, grad_norm, s.edge_gain * rim);
        cv::Vec3f c = detail && lab[x] == k
                          ? leaf_detail(s, layer, sample(small.depth, sx, sy), dep[x], lum[x])
                          : layer.pigment_display;
        if (soft) c = gradation(s, layer, s.soft_at(roi.x + x, roi.y + y), c);
        const float a = thin_wash(s, layer, roi.x + x, roi.y + y) * alpha;
        for (int ch = 0; ch < 3; ++ch)
          t[x][ch] = a * to_density(*s.srgb, pigment_density(std::min(c[ch], 1.0f), d));
      }
      glaze_row(into, roi.x, roi.y + y, w, t, cov);
    }
  });
}

}  // namespace

void paint_layer(const Shared& s, const Layer& layer, int k, GlazeInto& into) {
  const cv::Rect roi = layer_roi(s, layer);
  // The masks are blurred at 1/f of the resolution (they are smooth after the blur).
  const BlockScale scale(mask_factor(s.sigma));
  const bool detail = s.detail > 0.0f;
  BlockMasks blocks = block_masks(s, roi, k, scale.f, detail);
  if (s.close > 0.0f && layer.id != s.wood) close_over_paper(blocks, s.close / float(scale.f));
  const BlockMasks blurred = blur_masks(blocks, s.sigma / float(scale.f), detail);
  const SmallFields small = continue_under_occluders(blurred, detail);
  const cv::Mat mask = wobbled_mask(s, layer, roi, scale, small.mask);
  wash_density(s, layer, k, scale, mask, small, roi, into);
}

// Every layer painted, then glazed: the densities of transparent washes add (their
// transmittances multiply), back to front (a fixed order keeps the bytes fixed). The wood's
// wash (id `wood`, 0 = none) is laid first, under the leaves, and where the id buffer shows
// wood (`wood_seen`, CV_8UC1, 255 = wood; no function = none) the leaves' washes leave it bare: the
// trunk and branches are painted wherever they are seen, through the gaps of the crown.
cv::Mat glaze(const Shared& s, const std::vector<Layer>& sorted, int32_t wood,
              const std::function<cv::Mat()>& wood_seen_of) {
  cv::Mat density(s.size, CV_32FC3, cv::Scalar(0, 0, 0));
  const bool apart = bool(wood_seen_of);  // the wood's wash kept apart, composed at the end
  cv::Mat bark;                           // the wood's wash over bark_roi
  cv::Rect bark_roi;
  const Layer* wood_layer = nullptr;
  // One wash at a time (each painted by all threads), glazed as soon as it is painted: only one
  // wash is held at once, however many layers there are.
  for (size_t k = 0; k < sorted.size(); ++k) {
    const bool is_wood = wood != 0 && sorted[k].id == wood;
    if (is_wood) wood_layer = &sorted[k];
    if (is_wood && apart) {
      bark_roi = layer_roi(s, sorted[k]);
      bark = cv::Mat(bark_roi.size(), CV_32FC3, cv::Scalar(0, 0, 0));
      GlazeInto into{bark, {}, {}, false, bark_roi.tl()};
      paint_layer(s, sorted[k], int(k), into);
      continue;
    }
    GlazeInto into{density, bark, bark_roi, !is_wood};
    paint_layer(s, sorted[k], int(k), into);
  }
  if (!apart) return density;
  const cv::Mat wood_seen = wood_seen_of();
  // Twigs the wood's wash (its trunk and main branches) leaves out are painted in its pigment
  // too, where they are seen: no streak of bare paper through the crown.
  cv::Vec3f twig(0.0f, 0.0f, 0.0f);
  if (wood_layer)
    for (int ch = 0; ch < 3; ++ch)
      twig[ch] = to_density(*s.srgb, std::min(wood_layer->pigment_display[ch], 1.0f));
  const cv::Vec3f bare(0.0f, 0.0f, 0.0f);
  for_bands(s.size.height, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      cv::Vec3f* d = density.ptr<cv::Vec3f>(y);
      const bool row = y >= bark_roi.y && y < bark_roi.br().y;
      const cv::Vec3f* b = row ? bark.ptr<cv::Vec3f>(y - bark_roi.y) : nullptr;
      const uint8_t* seen8 = wood_seen.ptr<uint8_t>(y);
      for (int x = 0; x < s.size.width; ++x) {
        const bool in_bark = b && x >= bark_roi.x && x < bark_roi.br().x;
        cv::Vec3f wood_here = in_bark ? b[x - bark_roi.x] : bare;
        const float seen = float(seen8[x]) * (1.0f / 255.0f);
        for (int ch = 0; ch < 3; ++ch)
          wood_here[ch] = std::max(wood_here[ch], seen * twig[ch]);
        d[x] = wood_here + d[x] * (1.0f - seen);
      }
    }
  });
  return density;
}

}  // namespace sylva::watercolor_internal

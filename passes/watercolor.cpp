#include "passes/watercolor.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <unordered_map>
#include <vector>

#include "core/error.h"
#include "core/random.h"
#include "core/scene/scene_length.h"
#include "passes/crown_coverage.h"
#include "passes/pass_common.h"
#include "passes/watercolor_common.h"
#include "passes/watercolor_layers.h"
#include "passes/watercolor_light.h"
#include "passes/watercolor_marks.h"
#include "passes/watercolor_masses.h"
#include "passes/watercolor_shadow.h"
#include "passes/watercolor_textures.h"

namespace sylva {

namespace {

using watercolor_internal::blur;
using watercolor_internal::encode_srgb;
using watercolor_internal::foliage_cover;
using watercolor_internal::glaze;
using watercolor_internal::glaze_shadow;
using watercolor_internal::key_shadow;
using watercolor_internal::kSqrt2Pi;
using watercolor_internal::Layer;
using watercolor_internal::luminance;
using watercolor_internal::mask_factor;
using watercolor_internal::paper_relief;
using watercolor_internal::PaperField;
using watercolor_internal::rim_allowed;
using watercolor_internal::seen_wood;
using watercolor_internal::Shared;
using watercolor_internal::smoothed_luminance;
using watercolor_internal::srgb_tables;
using watercolor_internal::SrgbTables;
using watercolor_internal::to_display;
using watercolor_internal::to_linear;

// The washes' shapes from the scene: the parts' density smoothed by this share of the wash blur
// (at least 2 px), a part where its coverage reaches kPartLevel (low: thin foliage, a willow's
// curtain, is inside its mass, where its wash thins, watercolor_layers.h kThinCover); the wood
// under the leaves where its own reaches kWoodLevel (the trunk and main branches, not every twig).
constexpr float kPartSigma = 2.0f;
constexpr float kPartLevel = 0.15f;
constexpr float kWoodLevel = 0.6f;
// The wood's part is smoothed by this share of the leaves' parts' width: the trunk and its
// branches, not one patch over the space between them.
constexpr double kWoodSmoothing = 0.5;

// The key light's shadow is evaluated on cells of this many px at 1024 px.
constexpr double kShadowCell = 4.0;

// Paper relief shading of the bare paper at paper_strength 1 (light grazing the grain).
constexpr float kPaperRelief = 0.10f;

// Whether the frame's camera is known, so that positions come from the depth (ViewPositions).
bool has_projection(const WatercolorImages& in) {
  return in.camera.width > 0 && in.camera.height > 0;
}

watercolor_internal::ViewPositions view_positions(const WatercolorImages& in) {
  return {in.position, in.depth, in.camera.proj};
}

// Checks the buffers the parameters need; true when the pigment is the albedo.
bool check_inputs(const WatercolorImages& in, const WatercolorParams& p) {
  expect_image(in.id, CV_32SC1, cv::Size(), "id");
  const cv::Size size = in.id.size();
  expect_image(in.color, CV_8UC4, size, "color");
  expect_image(in.depth, CV_32FC1, size, "depth");
  const bool use_albedo = p.pigment == Pigment::Albedo;
  if (use_albedo) {
    if (in.albedo.empty())
      throw InputError("watercolor.pigment",
                       "\"albedo\" needs the albedo buffer, which this style does not provide "
                       "(use \"shaded\")");
    expect_image(in.albedo, CV_8UC4, size, "albedo");
  }
  if (!in.position.empty() || (p.turbulence_strength > 0.0f && !has_projection(in)))
    expect_image(in.position, CV_32FC3, size, "position");
  return use_albedo;
}

// The edge and blur settings every layer shares, in pixels of this image.
// The gaps a mass's wash covers, as a share of watercolor.mass (the closing's radius).
constexpr double kMassClose = 0.05;

Shared shared_settings(const WatercolorImages& in, const WatercolorParams& p, double scale) {
  Shared s;
  s.size = in.id.size();
  s.depth = in.depth;
  s.sigma = float(p.blur * scale);
  // A hard edge still spans about a pixel of the blurred mask's slope, so it is antialiased.
  const float hard = std::clamp(0.7f / (std::max(s.sigma, 0.5f) * kSqrt2Pi), 0.02f, 0.5f);
  s.half_width = hard + (0.5f - hard) * p.edge_softness;
  // Pigment pools where a wash dries against dry paper; a wet-on-wet edge diffuses instead.
  s.edge_gain = p.edge_darkening * (1.0f - 0.8f * p.edge_softness);
  s.detail = p.detail;
  s.gradation = p.gradation;
  s.warm_cool = p.warm_cool;
  s.srgb = &srgb_tables();
  s.wood = int32_t(in.wood_cluster);
  return s;
}

// The share of the clear colour (linear BGR) in a pixel of coverage alpha: with a transparent
// clear of some colour, (1 - alpha) of it; with an opaque or black one nothing can (or need) be
// taken out.
cv::Vec3f clear_bgr(const glm::vec4& clear) {
  if (clear.a > 0.0f) return {0.0f, 0.0f, 0.0f};
  const glm::vec3 c = glm::clamp(glm::vec3(clear), 0.0f, 1.0f);
  return {c.b, c.g, c.r};
}

// Pixel (x, y) of cluster `L` added to its sums; returns the pixel's display luminance. `clear`
// (clear_bgr) is taken out of the colour: what remains is the leaf's, premultiplied.
float add_pixel(Layer& L, int x, int y, const cv::Vec4b& col, const cv::Vec4b* alb, float depth,
                const cv::Vec3f& clear, const SrgbTables& srgb) {
  ++L.count;
  L.x0 = std::min(L.x0, x);
  L.x1 = std::max(L.x1, x);
  L.y1 = y;
  const float a = float(col[3]) / 255.0f;
  cv::Vec3f c(srgb.to_linear[col[0]], srgb.to_linear[col[1]], srgb.to_linear[col[2]]);
  for (int ch = 0; ch < 3; ++ch) {
    c[ch] = std::max(0.0f, c[ch] - (1.0f - a) * clear[ch]);
    L.sum_color[ch] += c[ch];
  }
  L.sum_alpha += a;
  if (alb) {
    for (int ch = 0; ch < 3; ++ch)
      L.sum_pigment[ch] += srgb.to_linear[(*alb)[ch]];
    L.sum_pigment_alpha += float((*alb)[3]) / 255.0f;
  }
  const double z = depth;
  L.sum_depth += z;
  L.sum_depth2 += z * z;
  return a > 0.0f ? to_display(srgb, luminance(c / a)) : 0.0f;
}

// Clusters: statistics in one pass, labels (into `first_label`) in first-appearance order;
// fills s.luminance.
std::vector<Layer> gather_layers(const WatercolorImages& in, bool use_albedo, Shared& s,
                                 cv::Mat& first_label) {
  const cv::Size size = s.size;
  std::vector<Layer> layers;
  std::unordered_map<int32_t, int> index_of;
  first_label.create(size, CV_32S);
  s.luminance.create(size, CV_32F);
  const cv::Vec3f clear = clear_bgr(in.clear);
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
          layers.back().x0 = layers.back().x1 = x;
          layers.back().y0 = layers.back().y1 = y;
        }
        last_id = id[x];
        last = it->second;
      }
      lab[x] = last;
      lum[x] = add_pixel(layers[size_t(last)], x, y, col[x], alb ? &alb[x] : nullptr, dep[x], clear,
                         *s.srgb);
    }
  }
  return layers;
}

// Each layer's means from its sums: depth and spread, colour, luminance and pigment.
void finish_layers(std::vector<Layer>& layers, bool use_albedo, const SrgbTables& srgb) {
  for (Layer& L : layers) {
    const double n = double(L.count);
    L.mean_depth = float(L.sum_depth / n);
    L.order_depth = L.mean_depth;
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
}

// `labels` (CV_32SC1 indices into `layers` or cluster ids, by `index`) as ranks; -1 where
// there is no layer.
template <class Index>
cv::Mat ranks_of(const cv::Mat& labels, const std::vector<int>& rank, Index index) {
  cv::Mat out(labels.size(), CV_32S);
  for (int y = 0; y < labels.rows; ++y) {
    const int32_t* a = labels.ptr<int32_t>(y);
    int32_t* b = out.ptr<int32_t>(y);
    for (int x = 0; x < labels.cols; ++x) {
      const int i = index(a[x]);
      b[x] = i < 0 ? -1 : rank[size_t(i)];
    }
  }
  return out;
}

// The layers back to front by order_depth (ties by id), so layer k is hidden only by layers
// > k; s.label holds each pixel's rank, from `first_label` (indices into `layers`) or, with
// `parts`, from the scene's parts (cluster ids), s.seen then the id buffer's.
std::vector<Layer> back_to_front(const std::vector<Layer>& layers, const cv::Mat& first_label,
                                 const CrownParts* parts, Shared& s) {
  std::vector<int> order(layers.size());
  for (size_t i = 0; i < order.size(); ++i)
    order[i] = int(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const Layer& A = layers[size_t(a)];
    const Layer& B = layers[size_t(b)];
    if (A.order_depth != B.order_depth) return A.order_depth > B.order_depth;
    return A.id < B.id;
  });
  std::vector<int> rank(layers.size());
  for (size_t r = 0; r < order.size(); ++r)
    rank[size_t(order[r])] = int(r);
  const auto same = [](int32_t i) { return int(i); };
  if (parts) {
    std::unordered_map<int32_t, int> index_of;
    for (size_t i = 0; i < layers.size(); ++i)
      index_of[layers[i].id] = int(i);
    s.label = ranks_of(parts->label, rank, [&](int32_t id) {
      const auto it = index_of.find(id);
      return it == index_of.end() ? -1 : it->second;
    });
    s.seen = ranks_of(first_label, rank, same);
  } else {
    s.label = ranks_of(first_label, rank, same);
  }
  std::vector<Layer> sorted(layers.size());
  for (size_t r = 0; r < order.size(); ++r)
    sorted[r] = layers[size_t(order[r])];
  return sorted;
}

// The washes' shapes from the scene (issue "Temporal coherence"): the crown's parts projected
// from the surface samples (passes/crown_coverage.h), a little smoothed, so a wash moves with
// its cluster instead of flickering with the leaves that land on pixel centres. Each layer is
// ordered by its part's mean depth and its box grown to the part's region.
CrownParts scene_parts(const WatercolorImages& in, const Shared& s, std::vector<Layer>& layers) {
  const double smoothing = large_leaved(in.pieces.get()) ? kLargeLeafSmoothing : 1.0;
  // At the resolution the washes' masks are blurred at (paint_layer's), then up-sampled: the
  // parts are smooth at that scale.
  const int f = mask_factor(s.sigma);
  Camera camera = in.camera;
  camera.width = (s.size.width + f - 1) / f;
  camera.height = (s.size.height + f - 1) / f;
  const double sigma = smoothing * kPartSigma * std::max(s.sigma, 2.0f) / float(f);
  CrownParts parts = project_crown_parts(*in.samples, camera, sigma, kPartLevel, in.wood_cluster,
                                         kWoodLevel, kWoodSmoothing * sigma);
  if (f > 1) {
    const cv::Rect crop(0, 0, s.size.width, s.size.height);
    cv::resize(parts.label, parts.label, {camera.width * f, camera.height * f}, 0, 0,
               cv::INTER_NEAREST);
    cv::resize(parts.depth, parts.depth, {camera.width * f, camera.height * f}, 0, 0,
               cv::INTER_NEAREST);
    parts.label = parts.label(crop).clone();
    parts.depth = parts.depth(crop).clone();
    for (CrownParts::Part& part : parts.order)
      part.centre *= float(f);
  }
  std::unordered_map<int32_t, Layer*> layer_of;
  for (Layer& L : layers)
    layer_of[L.id] = &L;
  for (const CrownParts::Part& part : parts.order) {
    const auto it = layer_of.find(int32_t(part.cluster));
    if (it == layer_of.end()) continue;
    it->second->order_depth = part.depth;
    // The wash's paper moves with the part, from a seeded place of its own.
    uint64_t h = uint64_t(part.cluster) * 0x9E3779B97F4A7C15ull + 0x6A09E667F3BCC909ull;
    h = splitmix64(h);
    it->second->canvas = part.centre - cv::Point2f(float(h % 4096u), float((h >> 20) % 4096u));
  }
  for (int y = 0; y < parts.label.rows; ++y) {
    const int32_t* l = parts.label.ptr<int32_t>(y);
    for (int x = 0; x < parts.label.cols; ++x) {
      if (l[x] == 0) continue;
      const auto it = layer_of.find(l[x]);
      if (it == layer_of.end()) continue;
      Layer& L = *it->second;
      L.x0 = std::min(L.x0, x), L.x1 = std::max(L.x1, x);
      L.y0 = std::min(L.y0, y), L.y1 = std::max(L.y1, y);
    }
  }
  return parts;
}

// The wobble: the slope of the paper, scaled so its RMS length over the frame (sampled every
// 4 px) is `wobble` px, and bounded by three times that.
void set_wobble(const PaperField& paper, const WatercolorParams& p, double scale, Shared& s) {
  double sum = 0;
  size_t n = 0;
  for (int y = 2; y < s.size.height; y += 4)
    for (int x = 2; x < s.size.width; x += 4) {
      const cv::Vec2f g = paper.slope(float(x), float(y));
      sum += double(g.dot(g));
      ++n;
    }
  const double rms = n > 0 ? std::sqrt(sum / double(n)) : 0.0;
  const double target = p.wobble * scale;
  s.paper = &paper;
  s.wobble_gain = rms > 1e-12 ? float(target / rms) : 0.0f;
  s.max_wobble = float(3.0 * target);
}

// The paper grain each pixel's pigment settles in: the front wash's own paper (its canvas), the
// paper itself (`relief`) where there is no wash or the wash's paper is the paper's.
cv::Mat granules(const PaperField& paper, const cv::Mat& relief, const Shared& s,
                 const std::vector<Layer>& sorted) {
  cv::Mat out = relief.clone();
  cv::parallel_for_(cv::Range(0, s.size.height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      const int32_t* lab = s.label.ptr<int32_t>(y);
      float* o = out.ptr<float>(y);
      for (int x = 0; x < s.size.width; ++x) {
        if (lab[x] < 0) continue;
        const cv::Point2f c = sorted[size_t(lab[x])].canvas;
        if (c.x != 0.0f || c.y != 0.0f)
          o[x] = paper.relief(float(x) + 0.5f - c.x, float(y) + 0.5f - c.y);
      }
    }
  });
  return out;
}

// The world-space turbulence texture over the image. Evaluated at half resolution (the noise is
// low-frequency): each half-size pixel takes the mean position of its covered pixels, which is
// the same world point whichever way the view turns (the mean commutes with the rigid
// view_to_world).
cv::Mat turbulence_map(const WatercolorImages& in, const glm::mat4& view_to_world,
                       const WatercolorParams& p, float sigma) {
  const cv::Size size = in.depth.size();
  const watercolor_internal::CellPositions half =
      watercolor_internal::cell_positions(view_positions(in), 2);
  const cv::Mat &half_pos = half.mean, &half_cover = half.cover;
  cv::Mat half_turb = watercolor_turbulence(half_pos, half_cover, view_to_world, p);
  // Pigment that bled past the silhouette takes the turbulence of the nearest surface
  // (normalised convolution).
  const float fill_sigma = std::max(2.0f, sigma / 2.0f);
  const cv::Mat ws = blur(half_turb.mul(half_cover), fill_sigma);
  const cv::Mat cs = blur(half_cover, fill_sigma);
  cv::Mat filled;
  cv::divide(ws, cv::max(cs, 1e-6), filled);
  filled.copyTo(half_turb, half_cover == 0.0f);
  cv::Mat turb;
  cv::resize(half_turb, turb, size, 0, 0, cv::INTER_LINEAR);
  return turb;
}

// The glazed density over the paper, its pigment modulated by the paper grain it settles in
// (`grain`) and the turbulence (empty = none), the paper shaded by its relief; encoded as opaque
// 8-bit BGRA sRGB.
cv::Mat on_paper(const cv::Mat& density, const cv::Mat& paper, const cv::Mat& grain,
                 const cv::Mat& turb, const WatercolorParams& p, const SrgbTables& srgb) {
  cv::Mat out(density.size(), CV_8UC4);
  const float beta_paper = p.paper_strength, beta_turb = p.turbulence_strength;
  const glm::vec3 paper_color = glm::clamp(p.paper_color, 0.0f, 1.0f);
  const cv::Vec3f paper_bgr(paper_color.b, paper_color.g, paper_color.r);
  cv::parallel_for_(cv::Range(0, density.rows), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      const cv::Vec3f* t = density.ptr<cv::Vec3f>(y);
      const float* pp = paper.ptr<float>(y);
      const float* gr = grain.ptr<float>(y);
      const float* tb = turb.empty() ? nullptr : turb.ptr<float>(y);
      cv::Vec4b* o = out.ptr<cv::Vec4b>(y);
      for (int x = 0; x < density.cols; ++x) {
        // Bousseau's density formula with d = 1 + beta (T - 0.5): pigment settles in the paper's
        // hollows (low relief = more pigment) and follows the turbulence.
        const float d_paper = texture_density(1.0f - gr[x], beta_paper);
        const float d_turb = tb ? texture_density(tb[x], beta_turb) : 1.0f;
        const float relief = 1.0f + kPaperRelief * beta_paper * (pp[x] - 0.5f);
        for (int ch = 0; ch < 3; ++ch) {
          float c = 1.0f;
          if (t[x][ch] > 0.0f) {
            const float v = to_display(srgb, std::exp2(-p.strength * t[x][ch]));
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

// The washes back to front, their labels in s.label (s.seen); the full-size labels and parts
// they are ordered by are freed on return.
std::vector<Layer> ordered_layers(const WatercolorImages& in, bool use_albedo, Shared& s) {
  cv::Mat first_label;
  std::vector<Layer> layers = gather_layers(in, use_albedo, s, first_label);
  finish_layers(layers, use_albedo, *s.srgb);
  CrownParts parts;
  if (in.samples) parts = scene_parts(in, s, layers);
  return back_to_front(layers, first_label, in.samples ? &parts : nullptr, s);
}

// The images with the leaf clusters gathered into the crown's masses (watercolor.mass); `used`
// says whether they were (with the scene's samples, a mass size and one plant).
WatercolorImages with_masses(const WatercolorImages& in, const WatercolorParams& p, double scale,
                             bool& used) {
  WatercolorImages out = in;
  used = false;
  if (!(p.mass > 0.0f) || !in.samples || !(in.units_per_px > 0.0)) return out;
  const auto mass_of =
      crown_masses(*in.samples, in.wood_cluster, 0.5 * p.mass * scale * in.units_per_px);
  if (mass_of.empty()) return out;
  out.id = mass_ids(in.id, mass_of);
  out.samples = mass_samples(*in.samples, mass_of);
  used = true;
  return out;
}

}  // namespace

cv::Mat watercolor(const WatercolorImages& input, const glm::mat4& view_to_world,
                   const WatercolorParams& p) {
  const bool use_albedo = check_inputs(input, p);
  const double scale = reference_scale(input.id.size());
  bool masses = false;
  WatercolorImages in = with_masses(input, p, scale, masses);
  Shared s = shared_settings(in, p, scale);
  // A mass is laid in one wash: gaps up to kMassClose of its size are painted over (not between
  // large leaves: kLargeLeaf).
  if (masses && !large_leaved(in.pieces.get())) s.close = float(kMassClose * p.mass * scale);
  const std::vector<Layer> sorted = ordered_layers(in, use_albedo, s);
  // The masses' ids are read only to order the washes: the plant's pixels and the wood's are
  // the id buffer's own.
  in.id = input.id;
  const PaperField paper(p, scale);
  if (p.wobble > 0.0f && !sorted.empty()) set_wobble(paper, p, scale, s);
  s.rim_ok = rim_allowed(s, sorted, p.rim_step);
  if (in.samples && has_projection(in))
    s.cover = foliage_cover(*in.samples, in.camera, s.size, mask_factor(s.sigma),
                            kPartSigma * std::max(s.sigma, 2.0f), in.wood_cluster);
  if (p.gradation > 0.0f || p.warm_cool > 0.0f)
    s.soft_luminance = smoothed_luminance(s, in.id != 0);
  const bool wood = in.wood_cluster != 0;
  std::function<cv::Mat()> wood_seen;
  if (wood) wood_seen = [&] { return seen_wood(in.id, in.wood_cluster, scale); };
  cv::Mat density = glaze(s, sorted, wood ? int32_t(in.wood_cluster) : 0, wood_seen);
  // Only the labels (the paper's grain per wash) are read after the glaze.
  s.rim_ok.release();
  s.soft_luminance.release();
  s.luminance.release();
  s.seen.release();
  if (p.shadow > 0.0f && input.samples && (!in.position.empty() || has_projection(in))) {
    const int cell = std::max(1, int(std::lround(kShadowCell * scale)));
    glaze_shadow(key_shadow(view_positions(in), view_to_world, *input.samples, input.light, cell,
                            2.0f * std::max(s.sigma, 1.0f)),
                 p.shadow, p.warm_cool, density);
  }
  glaze_leaf_marks(input, p, density);
  const bool turbulence = p.turbulence_strength > 0.0f && !sorted.empty();
  const cv::Mat turb = turbulence ? turbulence_map(in, view_to_world, p, s.sigma) : cv::Mat();
  const cv::Mat relief = paper_relief(paper, s.size);
  return on_paper(density, relief, granules(paper, relief, s, sorted), turb, p, *s.srgb);
}

}  // namespace sylva

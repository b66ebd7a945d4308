#include "passes/seen_wood.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/error.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

cv::Mat round_kernel(double diameter) {
  const int k = std::max(1, int(std::lround(diameter)) | 1);
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k});
}

// A wood sample's disc in the frame: centre and radius (px), view depth.
struct Disc {
  float cx, cy, r, d;
};

// No wood there (the splat's clear value).
constexpr float kNone = std::numeric_limits<float>::infinity();

// A wood sample's disc's largest radius, px.
constexpr float kMostDiscRadius = 8.0f;

// The wood samples' discs in the frame (those in front of the camera), projected in parallel by
// kDiscRuns runs of the samples, each run's in order.
constexpr int kDiscRuns = 64;

std::vector<std::vector<Disc>> wood_discs(const SurfaceSamples& s, const Camera& camera,
                                          cv::Size size, uint32_t wood) {
  const glm::mat4 view_proj = camera.proj * camera.view;
  // px per scene unit at view depth d: proj[1][1] * h / 2 / d (perspective), without / d (ortho).
  const float focal = camera.proj[1][1] * 0.5f * float(size.height);
  std::vector<std::vector<Disc>> runs(kDiscRuns);
  cv::parallel_for_(cv::Range(0, kDiscRuns), [&](const cv::Range& range) {
    for (int run = range.start; run < range.end; ++run) {
      const size_t end = s.size() * size_t(run + 1) / kDiscRuns;
      for (size_t i = s.size() * size_t(run) / kDiscRuns; i < end; ++i) {
        if (s.clusters[i] != wood) continue;
        const glm::vec4 clip = view_proj * glm::vec4(s.positions[i], 1.0f);
        if (!(clip.w > 0.0f)) continue;
        const float d = -(camera.view * glm::vec4(s.positions[i], 1.0f)).z;
        const float cx = (clip.x / clip.w * 0.5f + 0.5f) * float(size.width);
        const float cy = (0.5f - clip.y / clip.w * 0.5f) * float(size.height);
        const float r = std::clamp(0.6f * s.spacing * (camera.ortho ? focal : focal / d), 0.5f,
                                   kMostDiscRadius);
        if (!std::isfinite(cx) || !std::isfinite(cy) || !(d > 0.0f)) continue;
        runs[size_t(run)].push_back({cx, cy, r, d});
      }
    }
  });
  return runs;
}

// The discs that reach the frame by the row of their centre (a counting sort): discs[first[y],
// first[y + 1]) are those centred on row y.
struct DiscRows {
  std::vector<Disc> discs;
  std::vector<size_t> first;
};

DiscRows by_row(const std::vector<std::vector<Disc>>& runs, cv::Size size) {
  DiscRows out;
  out.first.assign(size_t(size.height) + 1, 0);
  auto row_of = [&](const Disc& c) {
    if (c.cy + c.r < 0.0f || c.cy - c.r > float(size.height) || c.cx + c.r < 0.0f ||
        c.cx - c.r > float(size.width))
      return -1;
    return std::clamp(int(std::floor(c.cy)), 0, size.height - 1);
  };
  for (const std::vector<Disc>& discs : runs)
    for (const Disc& c : discs)
      if (const int y = row_of(c); y >= 0) ++out.first[size_t(y) + 1];
  for (size_t y = 1; y < out.first.size(); ++y)
    out.first[y] += out.first[y - 1];
  std::vector<size_t> next(out.first.begin(), out.first.end() - 1);
  out.discs.resize(out.first.back());
  for (const std::vector<Disc>& discs : runs)
    for (const Disc& c : discs)
      if (const int y = row_of(c); y >= 0) out.discs[next[size_t(y)]++] = c;
  return out;
}

// The wood samples splatted at the frame's resolution: each a disc of about its spacing, the
// nearest kept; +inf where none. Splatted by bands of rows, each band visiting the discs centred
// within a disc's largest radius of it (the nearest is the same in any order).
cv::Mat splat_wood(const SurfaceSamples& s, const Camera& camera, cv::Size size, uint32_t wood) {
  const float inf = std::numeric_limits<float>::infinity();
  cv::Mat z(size, CV_32FC1, cv::Scalar(inf));
  const DiscRows rows = by_row(wood_discs(s, camera, size, wood), size);
  for_bands(size.height, [&](int band0, int band1) {
    const int reach = int(std::ceil(kMostDiscRadius)) + 1;
    const size_t from = rows.first[size_t(std::max(0, band0 - reach))];
    const size_t to = rows.first[size_t(std::min(size.height, band1 + reach))];
    for (size_t i = from; i < to; ++i) {
      const Disc& c = rows.discs[i];
      const int x0 = std::max(0, int(std::ceil(c.cx - c.r - 0.5f))),
                x1 = std::min(size.width - 1, int(std::floor(c.cx + c.r - 0.5f)));
      const int y0 = std::max(band0, int(std::ceil(c.cy - c.r - 0.5f))),
                y1 = std::min(band1 - 1, int(std::floor(c.cy + c.r - 0.5f)));
      for (int y = y0; y <= y1; ++y) {
        // The row's pixels within the disc: a span, its ends found by the test itself.
        const float dy = float(y) + 0.5f - c.cy;
        auto inside = [&](int x) {
          const float dx = float(x) + 0.5f - c.cx;
          return dx * dx + dy * dy <= c.r * c.r;
        };
        int from = x0, to = x1;
        while (from <= to && !inside(from))
          ++from;
        while (to >= from && !inside(to))
          --to;
        float* t = z.ptr<float>(y);
        for (int x = from; x <= to; ++x)
          t[x] = std::min(t[x], c.d);
      }
    }
  });
  return z;
}

// The wood the raster shows (w.mask: where `id` is the wood's and `depth` covered; w.depth: a
// copy of `depth`), in one pass; returns the plant's depth extent in the raster (the covered
// pixels' nearest and farthest).
float raster_wood(const cv::Mat& id, const cv::Mat& depth, uint32_t wood, SeenWood& w) {
  // New images (w.depth may share the raster's).
  w.mask = cv::Mat(depth.size(), CV_8UC1);
  w.depth = cv::Mat(depth.size(), CV_32FC1);
  std::mutex mutex;
  float lo = kNone, hi = -kNone;
  for_bands(depth.rows, [&](int y0, int y1) {
    float band_lo = kNone, band_hi = -kNone;
    for (int y = y0; y < y1; ++y) {
      const int* ids = id.ptr<int>(y);
      const float* z = depth.ptr<float>(y);
      uint8_t* mask = w.mask.ptr<uint8_t>(y);
      float* out = w.depth.ptr<float>(y);
      for (int x = 0; x < depth.cols; ++x) {
        const bool covered = z[x] > 0.0f;
        mask[x] = covered && ids[x] == int(wood) ? 255 : 0;
        out[x] = z[x];
        if (!covered) continue;
        band_lo = std::min(band_lo, z[x]);
        band_hi = std::max(band_hi, z[x]);
      }
    }
    const std::lock_guard<std::mutex> lock(mutex);
    lo = std::min(lo, band_lo);
    hi = std::max(hi, band_hi);
  });
  return hi > lo ? float(double(hi) - double(lo)) : 0.0f;
}

// Without samples: gaps up to `gap` px that the plant fills, closed; their depth the farthest
// wood around.
void close_gaps(const cv::Mat& depth, double gap, SeenWood& w) {
  cv::Mat closed, far;
  cv::morphologyEx(w.mask, closed, cv::MORPH_CLOSE, round_kernel(gap));
  const cv::Mat fill = closed & ~w.mask & (depth > 0.0f);
  cv::Mat only(depth.size(), CV_32FC1, cv::Scalar(0));
  depth.copyTo(only, w.mask);
  cv::dilate(only, far, round_kernel(gap + 2.0));
  far.copyTo(w.depth, fill);
  w.mask |= fill;
}

}  // namespace

WoodSplat wood_splat(const SurfaceSamples& s, const Camera& camera, uint32_t wood) {
  if (wood == 0 || s.clusters.size() != s.size() || camera.width < 1 || camera.height < 1)
    return {};
  return {splat_wood(s, camera, {camera.width, camera.height}, wood)};
}

SeenWood seen_wood(const WoodImages& in, uint32_t wood, double detail) {
  SeenWood w;
  w.depth = in.depth;
  if (wood == 0 || in.id.empty()) return w;
  expect_image(in.depth, CV_32FC1, {}, "depth");
  expect_image(in.id, CV_32SC1, in.depth.size(), "id");
  w.cover = kWoodCover * raster_wood(in.id, in.depth, wood, w);
  if (!in.samples || in.samples->clusters.size() != in.samples->size()) {
    close_gaps(in.depth, std::max(2.0, 0.3 * detail * reference_scale(in.depth.size())), w);
    return w;
  }
  // The splat made beforehand, unless there is none of the raster's size.
  const cv::Mat z = in.splat.z.size() == in.depth.size()
                        ? in.splat.z
                        : splat_wood(*in.samples, in.camera, in.depth.size(), wood);
  const float cover = w.cover;
  for_bands(in.depth.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const float *shown = in.depth.ptr<float>(y), *under = z.ptr<float>(y);
      uint8_t* mask = w.mask.ptr<uint8_t>(y);
      float* depth = w.depth.ptr<float>(y);
      for (int x = 0; x < in.depth.cols; ++x) {
        if (!(under[x] < kNone) || mask[x] || !(shown[x] > 0.0f)) continue;  // most: no splat
        if (shown[x] < under[x] - cover) continue;  // foliage clearly in front
        mask[x] = 255;
        depth[x] = under[x];
      }
    }
  });
  return w;
}

Handle<SeenWood> add_seen_wood_pass(RenderGraph& g, const WoodResources& in, uint32_t wood,
                                    double detail) {
  SYLVA_CHECK(in.id.valid() && in.depth.valid(), "seen wood needs the id and depth resources");
  std::vector<ResourceRef> reads = {in.id, in.depth};
  Handle<WoodSplat> splat;
  if (in.samples.valid()) {
    splat = g.resource<WoodSplat>("wood-splat");
    g.add_pass(
        "wood-splat", {in.samples}, {splat},
        [=](PassContext& ctx) {
          const auto& samples = ctx.read<std::shared_ptr<const SurfaceSamples>>(in.samples);
          ctx.write(splat, samples ? wood_splat(*samples, in.camera, wood) : WoodSplat{});
        },
        RenderGraph::Threads::Any);
    reads.push_back(in.samples);
    reads.push_back(splat);
  }
  const auto out = g.resource<SeenWood>("seen-wood");
  g.add_pass(
      "seen-wood", reads, {out},
      [=](PassContext& ctx) {
        WoodImages images;
        images.id = ctx.read<cv::Mat>(in.id);
        images.depth = ctx.read<cv::Mat>(in.depth);
        if (in.samples.valid()) {
          images.samples = ctx.read<std::shared_ptr<const SurfaceSamples>>(in.samples);
          images.splat = ctx.read<WoodSplat>(splat);
        }
        images.camera = in.camera;
        ctx.write(out, seen_wood(images, wood, detail));
      },
      RenderGraph::Threads::Any);
  return out;
}

}  // namespace sylva

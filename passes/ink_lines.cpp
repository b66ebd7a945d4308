#include "passes/ink_lines.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/stroke_render.h"
#include "passes/ink_abstraction.h"
#include "passes/ink_marks.h"
#include "passes/pass_common.h"
#include "passes/skeleton_chains.h"

namespace sylva {

const LineClassParams& InkLineParams::of(LineClass c) const {
  switch (c) {
    case LineClass::Silhouette:
      return silhouette;
    case LineClass::Interior:
      return interior;
    case LineClass::Wood:
      return wood;
    case LineClass::Foliage:
      return foliage;
    default:
      return detail_lines;
  }
}

namespace {

void bind_class(ParamSet& set, const std::string& name, const std::string& what,
                LineClassParams& c) {
  const std::string k = "lines." + name;
  set.add_bool(k, c.on, "draw " + what);
  set.add_float(k + "_width", c.width, 0.25, 16.0, "px at 1024 px", "width of " + what);
  set.add_float(k + "_tone", c.tone, 0.0, 1.0, "", "ink opacity of " + what + " (1 = full)");
  set.add_float(k + "_taper", c.taper, 0.0, 256.0, "px at 1024 px",
                "length over which open strokes of " + what + " narrow to a point (0 = none)");
  set.add_float(k + "_depth_width", c.depth_width, 1.0, 8.0, "ratio",
                "nearest " + what + " this many times wider than the farthest (1 = even)");
}

// Depth at a polyline point (a pixel corner, or between): the nearest covered pixel among the
// four around it; 0 when none is covered.
float depth_at(const cv::Mat& depth, cv::Point2f pt) {
  const int x0 = static_cast<int>(std::floor(pt.x - 0.5f)),
            y0 = static_cast<int>(std::floor(pt.y - 0.5f));
  float best = 0.0f;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const int x = std::clamp(x0 + dx, 0, depth.cols - 1),
                y = std::clamp(y0 + dy, 0, depth.rows - 1);
      const float z = depth.at<float>(y, x);
      if (z > 0.0f && (best == 0.0f || z < best)) best = z;
    }
  return best;
}

// Per-point widths: narrower with depth (depth_width) and toward open ends (taper).
std::vector<float> width_profile(const Polyline& line, float width, const LineClassParams& c,
                                 const cv::Mat& depth, float near, float far, double scale) {
  const size_t n = line.points.size();
  std::vector<float> w(n, width);
  if (c.depth_width > 1.0f && far > near)
    for (size_t i = 0; i < n; ++i) {
      const float z = depth_at(depth, line.points[i]);
      const float t = z > 0.0f ? std::clamp((z - near) / (far - near), 0.0f, 1.0f) : 1.0f;
      w[i] *= 1.0f + t * (1.0f / c.depth_width - 1.0f);
    }
  if (c.taper > 0.0f && !line.closed && n > 1) {
    std::vector<double> s(n, 0.0);
    for (size_t i = 1; i < n; ++i)
      s[i] = s[i - 1] + cv::norm(line.points[i] - line.points[i - 1]);
    const double taper = std::min(c.taper * scale, 0.5 * s.back());
    for (size_t i = 0; i < n && taper > 0; ++i) {
      const double from_end = std::min(s[i], s.back() - s[i]);
      w[i] *= static_cast<float>(std::min(1.0, 0.1 + 0.9 * from_end / taper));
    }
  }
  return w;
}

// Moves each point of `line` (output px) across the line toward the side whose depth (`depth`,
// working px = output px / f, 0 = none) is nearer, by `offset` px: an interior contour is drawn
// on the part in front, whose edge it is, not over the part behind.
void to_nearer_side(Polyline& line, const cv::Mat& depth, double f, float offset) {
  const size_t n = line.points.size();
  if (n < 2 || depth.empty()) return;
  auto z = [&](cv::Point2f q) {
    const int x = std::clamp(int(std::floor(q.x / f)), 0, depth.cols - 1);
    const int y = std::clamp(int(std::floor(q.y / f)), 0, depth.rows - 1);
    return depth.at<float>(y, x);
  };
  std::vector<cv::Point2f> moved(n);
  for (size_t i = 0; i < n; ++i) {
    const cv::Point2f a = line.points[i == 0 ? 0 : i - 1], b = line.points[std::min(n - 1, i + 1)];
    cv::Point2f t = b - a;
    const float length = std::hypot(t.x, t.y);
    moved[i] = line.points[i];
    if (length <= 0.0f) continue;
    const cv::Point2f normal(-t.y / length, t.x / length), probe = float(1.5 * f) * normal;
    const float left = z(line.points[i] + probe), right = z(line.points[i] - probe);
    if (left <= 0.0f || right <= 0.0f) continue;
    moved[i] += (left < right ? offset : -offset) * normal;
  }
  line.points = moved;
}

Stroke make_stroke(const Polyline& line, LineClass cls, const LineClassParams& c, float width,
                   const InkMarks& marks, const cv::Mat& depth, double scale) {
  Stroke s;
  s.cls = cls;
  s.closed = line.closed;
  s.opacity = c.tone;
  s.width = width;
  s.points.reserve(line.points.size());
  for (const cv::Point2f& q : line.points)
    s.points.emplace_back(q.x, q.y);
  if (c.depth_width > 1.0f || (c.taper > 0.0f && !line.closed))
    s.widths = width_profile(line, width, c, depth, marks.near, marks.far, scale);
  return s;
}

}  // namespace

void bind_ink_line_params(ParamSet& set, InkLineParams& p) {
  set.add_float("ink.detail", p.detail, 0.0, 64.0, "px at 1024 px",
                "smallest feature the lines draw: the outline, crown parts and depth steps are "
                "simplified below it (0 = leaf-exact lines)");
  bind_class(set, "silhouette", "the plant's outer silhouette", p.silhouette);
  bind_class(set, "interior", "interior crown contours", p.interior);
  bind_class(set, "wood", "trunk and branch outlines", p.wood);
  bind_class(set, "detail", "leaf-level detail lines", p.detail_lines);
  bind_class(set, "foliage", "the foliage primitives' outlines inside the crown", p.foliage);
  set.add_bool("lines.outline", p.outline,
               "the plant's outline as one contour enclosing the crown (off: the foliage "
               "primitives draw the silhouette)");
  set.add_bool("lines.wood_shade", p.wood_shade,
               "hatching along the trunk and branches on their shadow side (with the foliage "
               "primitives)");
  set.add_bool("lines.plants", p.plants,
               "in a scene of many plants, outline each plant where its crown stands in front of "
               "another's (as silhouette lines)");
}

StrokeDrawing ink_line_strokes(const InkLineImages& in, const EdgeParams& edges,
                               const InkLineParams& p, uint32_t branch_cluster) {
  const cv::Size size = in.color.size();
  const double scale = reference_scale(size);
  const InkMarks marks = mark_ink_lines(in, edges, p, branch_cluster, scale);
  const double detail = p.detail * scale;
  StrokeDrawing d;
  d.size = size;
  d.color = edges.color;
  // Lighter classes first, so the outline is drawn over what it meets.
  for (LineClass cls :
       {LineClass::Detail, LineClass::Wood, LineClass::Interior, LineClass::Silhouette}) {
    const LineClassParams& c = p.of(cls);
    if (!c.on || c.tone <= 0.0f || (cls == LineClass::Silhouette && !p.outline)) continue;
    const bool crown = cls == LineClass::Silhouette || cls == LineClass::Interior;
    const bool abstracted = crown && detail >= 2.0;
    // All but the detail lines come at the marks' working resolution: `f` output px per point.
    const double f = cls != LineClass::Detail ? marks.crown_scale : 1.0;
    // Smoothing: the picture's scale for the crown, else just the pixel staircase.
    const double sigma = abstracted ? detail / 3.0 : 0.7 * f;
    // Shortest stroke kept: 2 x detail on the crown, 6 x detail for wood (the trunk and the
    // main branches, not every twig seen through a gap), 1 x detail for leaf-level lines.
    const double relative = cls == LineClass::Wood ? 6.0 : (crown ? 2.0 : 1.0);
    const double min_length =
        std::max(edges.min_length * scale, detail >= 2.0 || !crown ? relative * detail : 0.0);
    const float width = static_cast<float>(std::max<double>(edges.min_width, c.width * scale));
    // side: the depth image an interior or plant line keeps to the nearer side of (or null).
    auto add = [&](Polyline chain, double min, float w, bool outline, const cv::Mat* side) {
      if (f * polyline_length(chain) < std::max(min, 1.0)) return;
      // The outline onto the crown field's level set, between the pixels' corners.
      if (outline && !marks.field.empty())
        snap_to_level(chain.points, marks.field, kCrownLevel, 1.0f);
      Polyline line = smooth_polyline(chain, sigma / f);
      for (cv::Point2f& q : line.points)
        q *= float(f);
      if (side != nullptr) to_nearer_side(line, *side, f, 0.5f * w + 0.5f);
      line = simplify_polyline(line, 0.5);
      d.strokes.push_back(make_stroke(line, cls, c, w, marks, in.depth, scale));
    };
    for (const Polyline& chain : chain_cracks(marks.of[size_t(cls)]))
      add(chain, min_length, width, cls == LineClass::Silhouette,
          cls == LineClass::Interior ? &marks.part_depth : nullptr);
    if (cls != LineClass::Silhouette) continue;
    // The plants' outlines inside the crown, on the nearer plant's side.
    if (!marks.plant_depth.empty())
      for (const Polyline& chain : chain_cracks(marks.plants))
        add(chain, min_length, width, false, &marks.plant_depth);
    // Thin parts of the plant: one centre line each, of the silhouette's width.
    for (const Polyline& chain : skeleton_chains(marks.thin, detail / f))
      add(chain, detail, width, false, nullptr);
  }
  return d;
}

Handle<StrokeDrawing> add_ink_lines_pass(RenderGraph& g, const InkLineResources& in,
                                         const EdgeParams& edges, const InkLineParams& p,
                                         uint32_t branch_cluster) {
  SYLVA_CHECK(in.color.valid() && in.depth.valid(), "ink lines need the color and depth resources");
  const bool normals = edges.normal && (p.detail <= 0.0f || p.detail_lines.on) && in.normal.valid();
  std::vector<ResourceRef> reads = {in.color, in.depth};
  if (normals) reads.push_back(in.normal);
  if (in.id.valid()) reads.push_back(in.id);
  if (in.samples.valid()) reads.push_back(in.samples);
  const auto out = g.resource<StrokeDrawing>("ink-strokes");
  g.add_pass(
      "ink-strokes", reads, {out},
      [=](PassContext& ctx) {
        InkLineImages images;
        images.color = ctx.read<cv::Mat>(in.color);
        images.depth = ctx.read<cv::Mat>(in.depth);
        if (normals) images.normal = ctx.read<cv::Mat>(in.normal);
        if (in.id.valid()) images.id = ctx.read<cv::Mat>(in.id);
        if (in.samples.valid()) {
          images.samples = ctx.read<std::shared_ptr<const SurfaceSamples>>(in.samples);
          images.camera = in.camera;
        }
        EdgeParams e = edges;
        e.normal = normals;
        ctx.write(out, ink_line_strokes(images, e, p, branch_cluster));
      },
      RenderGraph::Threads::Any);
  return out;
}

Handle<StrokeDrawing> add_merge_strokes_pass(RenderGraph& g, Handle<StrokeDrawing> first,
                                             Handle<StrokeDrawing> second,
                                             const std::string& name) {
  const auto out = g.resource<StrokeDrawing>(name);
  g.add_pass(
      name, {first, second}, {out},
      [=](PassContext& ctx) {
        StrokeDrawing d = ctx.read<StrokeDrawing>(first);
        const StrokeDrawing& b = ctx.read<StrokeDrawing>(second);
        d.color = b.color;
        append_strokes(d, b);
        ctx.write(out, std::move(d));
      },
      RenderGraph::Threads::Any);
  return out;
}

ImageHandle add_stroke_raster_pass(RenderGraph& g, Handle<StrokeDrawing> strokes) {
  const auto out = g.resource<cv::Mat>("lines");
  g.add_pass(
      "stroke-raster", {strokes}, {out},
      [=](PassContext& ctx) {
        ctx.write(out, rasterize_strokes(ctx.read<StrokeDrawing>(strokes)));
      },
      RenderGraph::Threads::Any);
  return out;
}

namespace {

// 1 - the product of each coverage's 1 - coverage (CV_32FC1, one size).
cv::Mat union_coverage(const std::vector<const cv::Mat*>& parts) {
  cv::Mat out(parts.front()->size(), CV_32FC1);
  for_bands(out.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      float* o = out.ptr<float>(y);
      std::fill(o, o + out.cols, 1.0f);
      for (const cv::Mat* m : parts) {
        const float* c = m->ptr<float>(y);
        for (int x = 0; x < out.cols; ++x)
          o[x] *= 1.0f - c[x];
      }
      for (int x = 0; x < out.cols; ++x)
        o[x] = 1.0f - o[x];
    }
  });
  return out;
}

}  // namespace

ImageHandle add_stroke_parts_raster_pass(RenderGraph& g, const std::vector<StrokePart>& parts) {
  std::vector<StrokePart> valid;
  for (const StrokePart& part : parts)
    if (part.strokes.valid()) valid.push_back(part);
  SYLVA_CHECK(!valid.empty(), "add_stroke_parts_raster_pass: no drawing");
  if (valid.size() == 1) return add_stroke_raster_pass(g, valid.front().strokes);
  std::vector<ImageHandle> coverage;
  for (const StrokePart& part : valid) {
    const auto out = g.resource<cv::Mat>("lines-" + part.name);
    const Handle<StrokeDrawing> strokes = part.strokes;
    g.add_pass(
        "stroke-raster-" + part.name, {strokes}, {out},
        [=](PassContext& ctx) {
          ctx.write(out, rasterize_strokes(ctx.read<StrokeDrawing>(strokes)));
        },
        RenderGraph::Threads::Any);
    coverage.push_back(out);
  }
  const auto out = g.resource<cv::Mat>("lines");
  g.add_pass(
      "stroke-union", std::vector<ResourceRef>(coverage.begin(), coverage.end()), {out},
      [=](PassContext& ctx) {
        std::vector<const cv::Mat*> images;
        for (const ImageHandle& c : coverage)
          images.push_back(&ctx.read<cv::Mat>(c));
        ctx.write(out, union_coverage(images));
      },
      RenderGraph::Threads::Any);
  return out;
}

}  // namespace sylva

// The blobs passes' parameters (blobs.* keys, ranges, checks) and their wiring into the render
// graph (passes/blobs.h); the painting itself is passes/blobs.cpp.
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "passes/blobs.h"
#include "passes/crown_coverage.h"
#include "passes/pass_common.h"

namespace sylva {

void bind_blob_params(ParamSet& set, BlobParams& p) {
  set.add_int("blobs.control_points", p.control_points, 3, 512, "",
              "control points of each blob's shrink-wrapped outline (Dudley §4.2.1)");
  set.add_float("blobs.step", p.step, 0.0, 1.0, "",
                "fraction of the way to the centre a control point moves per shrink-wrap step",
                true);
  set.add_float("blobs.gap", p.gap, 0.0, 128.0, "px at 1024 px",
                "gaps between a cluster's leaves closed before shrink-wrapping; 0 = none");
  set.add_choice("blobs.outlines", p.outlines,
                 {{"scene", BlobOutlineSource::Scene},
                  {"visible", BlobOutlineSource::Visible},
                  {"alone", BlobOutlineSource::Alone}},
                 "outline each cluster's part of the crown projected from the scene (holds "
                 "still in a turntable), its visible leaves (one raster pass), or the cluster "
                 "rasterised alone, hidden leaves included (one pass per cluster)");
  set.add_int("blobs.peaks", p.peaks, 1, 16, "", "Gaussian peaks of each blob's height field");
  set.add_float("blobs.peak_height", p.peak_height, 0.0, 2.0, "of the blob width",
                "peak height: 0 flat, 1 as high as the blob is wide");
  set.add_choice("blobs.blend_light", p.blend_light,
                 {{"directional", BlendLight::Directional}, {"point", BlendLight::Point}},
                 "the blend light whose brightness mixes wash (bright) and leaf detail (dark)");
  set.add_float("blobs.blend_right", p.blend_right, -10.0, 10.0, "of the view distance",
                "blend light position along the camera's right vector");
  set.add_float("blobs.blend_up", p.blend_up, -10.0, 10.0, "of the view distance",
                "blend light position along the camera's up vector");
  set.add_float("blobs.blend_ambient", p.blend_ambient, 0.0, 1.0, "",
                "blend light ambient strength (more = less detail everywhere)");
  set.add_float("blobs.blend_diffuse", p.blend_diffuse, 0.0, 2.0, "",
                "blend light diffuse strength (more = less detail on the lit side)");
  set.add_bool("blobs.silhouettes", p.silhouettes,
               "leaf silhouettes in the detail, found by the edges.* settings");
  set.add_float("blobs.silhouette_tone", p.silhouette_tone, 0.0, 10.0, "x unlit blob colour",
                "leaf silhouette colour: 0 black, 1 the blob colour, 10 white");
  set.add_float("blobs.edge_width", p.edge_width, 0.0, 32.0, "px at 1024 px",
                "width of the outline inside each blob; 0 = none");
  set.add_float("blobs.edge_left", p.edge_left, 0.0, 4.0, "",
                "extra outline width where the edge lies to the left (x (1 + edge_left))");
  set.add_float("blobs.edge_tone", p.edge_tone, 0.0, 10.0, "x lit wash",
                "outline colour: 0 black, 1 the lit wash");
  set.add_float("blobs.translucency", p.translucency, 0.0, 1.0, "",
                "how much of what lies behind shows through a blob");
  set.add_float("blobs.variation", p.variation, 0.0, 0.5, "",
                "per-blob brightness variation (wash x (1 +- variation)), seeded");
  set.add_int("blobs.seed", p.seed, 0, 2147483647, "", "seed of the per-blob variation");
}

void validate_blob_params(const BlobParams& p) {
  ParamSet set;
  BlobParams copy;  // bound at the defaults (binding checks them), then given p's values
  bind_blob_params(set, copy);
  copy = p;
  set.check_values();  // the same range checks as a preset, each error naming its key
}

bool blob_needs_position(const Lighting& lighting, const BlobParams& p) {
  if (p.blend_light == BlendLight::Point) return true;
  for (const Light& l : lighting.lights)
    if (l.type == Light::Type::Point) return true;
  return false;
}

ShrinkWrapParams blob_shrink_wrap(const BlobParams& p) {
  ShrinkWrapParams sw;
  sw.control_points = p.control_points;
  sw.step = p.step;
  return sw;
}

float blob_gap_radius(const BlobParams& p, const cv::Size& size) {
  // blobs.gap is a diameter at the reference size; close_gaps takes a radius.
  return static_cast<float>(0.5 * p.gap * reference_scale(size));
}

std::vector<BlobOutline> scene_blob_outlines(const SurfaceSamples& samples, const Camera& camera,
                                             uint32_t branch_cluster, const BlobParams& p) {
  const cv::Size size(camera.width, camera.height);
  // Parts a little smoothed (2 px at 1024 px, no less than a pixel) where their leaves cover a
  // third of the pixel: the leaves' extent, which blobs.gap then closes.
  const double sigma = std::max(1.0, 2.0 * reference_scale(size));
  const ShrinkWrapParams sw = blob_shrink_wrap(p);
  const float gap = blob_gap_radius(p, size);
  std::vector<BlobOutline> out;
  for (const PartMask& m : project_part_masks(samples, camera, sigma, 0.3f, branch_cluster)) {
    if (m.box.empty() || cv::countNonZero(m.mask) == 0) continue;
    out.push_back(blob_outline(m.mask, m.box, m.cluster, m.depth, sw, gap));
  }
  std::sort(out.begin(), out.end(),
            [](const BlobOutline& a, const BlobOutline& b) { return a.cluster < b.cluster; });
  return out;
}

Handle<BlobSet> add_blob_outlines_pass(RenderGraph& graph, ImageHandle id, ImageHandle depth,
                                       uint32_t branch_cluster, const BlobParams& p,
                                       SamplesHandle samples, const Camera& camera) {
  validate_blob_params(p);
  const auto out = graph.resource<BlobSet>("blob-outlines");
  if (samples.valid()) {
    graph.add_pass("blob-outlines", {samples}, {out}, [=](PassContext& ctx) {
      const auto& s = ctx.read(samples);
      ctx.write(out, still_blob_set(scene_blob_outlines(*s, camera, branch_cluster, p)));
    });
    return out;
  }
  graph.add_pass("blob-outlines", {id, depth}, {out}, [=](PassContext& ctx) {
    const cv::Mat& ids = ctx.read<cv::Mat>(id);
    ctx.write(out, still_blob_set(find_blob_outlines(ids, ctx.read<cv::Mat>(depth), branch_cluster,
                                                     blob_shrink_wrap(p),
                                                     blob_gap_radius(p, ids.size()))));
  });
  return out;
}

ImageHandle add_blobs_pass(RenderGraph& graph, Handle<BlobSet> outlines, const BlobResources& r,
                           const BlobFrame& frame, const BlobParams& p) {
  validate_blob_params(p);
  const auto out = graph.resource<cv::Mat>("blobs");
  std::vector<ResourceRef> reads = {outlines, r.color, r.albedo, r.id};
  const bool position = blob_needs_position(frame.lighting, p);
  SYLVA_CHECK(!position || r.position.valid(), "blobs: a point light needs the position buffer");
  if (position) reads.push_back(r.position);
  if (r.lines.valid()) reads.push_back(r.lines);
  graph.add_pass("blobs", reads, {out}, [=](PassContext& ctx) {
    BlobImages in;
    in.color = ctx.read<cv::Mat>(r.color);
    in.albedo = ctx.read<cv::Mat>(r.albedo);
    in.id = ctx.read<cv::Mat>(r.id);
    if (position) in.position = ctx.read<cv::Mat>(r.position);
    if (r.lines.valid()) in.lines = ctx.read(r.lines);
    ctx.write(out, paint_blobs(in, ctx.read(outlines), frame, p));
  });
  return out;
}

}  // namespace sylva

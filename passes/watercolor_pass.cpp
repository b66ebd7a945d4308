// The watercolor's render-graph pass (passes/watercolor.h add_watercolor_pass): which buffers
// it reads for the parameters it is given, and the images it hands to watercolor().
#include <memory>
#include <vector>

#include "core/error.h"
#include "passes/watercolor.h"

namespace sylva {

ImageHandle add_watercolor_pass(RenderGraph& graph, const WatercolorResources& res,
                                const glm::mat4& view_to_world, const WatercolorParams& p) {
  SYLVA_CHECK(res.color.valid() && res.id.valid() && res.depth.valid(),
              "add_watercolor_pass: color, id and depth are required");
  const bool albedo = p.pigment == Pigment::Albedo;
  const bool turbulence = p.turbulence_strength > 0.0f;
  // With the frame's camera the positions come from the depth (ViewPositions).
  const bool position =
      (turbulence || (p.shadow > 0.0f && res.samples.valid())) && res.camera.width <= 0;
  SYLVA_CHECK(!position || res.position.valid(),
              "add_watercolor_pass: turbulence and the shadow glaze need the position buffer or "
              "the camera");
  std::vector<ResourceRef> reads{res.color, res.id, res.depth};
  if (albedo && res.albedo.valid()) reads.push_back(res.albedo);
  if (position) reads.push_back(res.position);
  if (res.samples.valid()) reads.push_back(res.samples);
  // The pieces give the marks, and the leaves' size the washes follow (passes/watercolor_masses.h
  // large_leaved).
  const bool pieces = res.pieces.valid();
  if (pieces) reads.push_back(res.pieces);
  const auto out = graph.resource<cv::Mat>("watercolor");
  graph.add_pass("watercolor", reads, {out},
                 [res, view_to_world, p, albedo, position, pieces, out](PassContext& ctx) {
                   WatercolorImages in;
                   in.color = ctx.read<cv::Mat>(res.color);
                   in.id = ctx.read<cv::Mat>(res.id);
                   in.depth = ctx.read<cv::Mat>(res.depth);
                   if (albedo && res.albedo.valid()) in.albedo = ctx.read<cv::Mat>(res.albedo);
                   if (position) in.position = ctx.read<cv::Mat>(res.position);
                   in.camera = res.camera;
                   if (res.samples.valid())
                     in.samples = ctx.read<std::shared_ptr<const SurfaceSamples>>(res.samples);
                   in.wood_cluster = res.wood_cluster;
                   in.units_per_px = res.units_per_px;
                   in.light = res.light;
                   in.clear = res.clear;
                   if (pieces) in.pieces = ctx.read<std::shared_ptr<const LeafPieces>>(res.pieces);
                   ctx.write(out, watercolor(in, view_to_world, p));
                 });
  return out;
}

}  // namespace sylva

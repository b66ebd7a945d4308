// The render graph's passes of the foliage primitives (passes/leaf_primitives.h): the
// primitives while the raster draws, then their tone beside the wood and their painting, then
// the layer.
#include <memory>
#include <vector>

#include "core/error.h"
#include "passes/leaf_outlines.h"
#include "passes/leaf_primitives.h"

namespace sylva {

namespace {

// "leaf-primitives": the primitives and their light, which need no raster.
Handle<LeafFrame> add_primitives_pass(RenderGraph& g, const LeafResources& in, const LeafParams& p,
                                      const InkLineParams& lines) {
  std::vector<ResourceRef> reads = {in.pieces};
  if (in.samples.valid()) reads.push_back(in.samples);
  const auto primitives = g.resource<LeafFrame>("leaf-primitives");
  g.add_pass(
      "leaf-primitives", reads, {primitives},
      [=](PassContext& ctx) {
        LeafImages images;
        images.pieces = ctx.read<std::shared_ptr<const LeafPieces>>(in.pieces);
        images.camera = in.camera;
        images.units_per_px = in.units_per_px;
        if (in.samples.valid())
          images.samples = ctx.read<std::shared_ptr<const SurfaceSamples>>(in.samples);
        images.light = in.light;
        ctx.write(primitives, leaf_frame(images, p, lines));
      },
      RenderGraph::Threads::Any);
  return primitives;
}

}  // namespace

LeafLayers add_leaf_layer_pass(RenderGraph& g, const LeafResources& in, const LeafParams& p,
                               const InkLineParams& lines, const EdgeParams& edges) {
  SYLVA_CHECK(in.pieces.valid() && in.color.valid(),
              "the leaf layer needs the leaf pieces and color resources");
  const Handle<LeafFrame> primitives = add_primitives_pass(g, in, p, lines);
  LeafLayers out;
  out.tone = g.resource<LeafTone>("leaf-tone");
  g.add_pass(
      "leaf-tone", {primitives, in.color}, {out.tone},
      [=](PassContext& ctx) {
        ctx.write(out.tone,
                  leaf_tone(ctx.read<LeafFrame>(primitives), ctx.read<cv::Mat>(in.color)));
      },
      RenderGraph::Threads::Any);
  // The wood and the primitives painted over it, beside the tone.
  std::vector<ResourceRef> wood_reads = {primitives};
  if (in.wood.valid()) wood_reads.push_back(in.wood);
  out.wood = g.resource<LeafLayer>("wood-layer");
  g.add_pass(
      "wood-layer", wood_reads, {out.wood},
      [=](PassContext& ctx) {
        const SeenWood none;
        const SeenWood& wood = in.wood.valid() ? ctx.read<SeenWood>(in.wood) : none;
        ctx.write(out.wood, wood_layer(ctx.read<LeafFrame>(primitives), wood, edges));
      },
      RenderGraph::Threads::Any);
  const auto paint = g.resource<LeafPaint>("leaf-paint");
  g.add_pass(
      "leaf-paint", {primitives, out.wood}, {paint},
      [=](PassContext& ctx) {
        ctx.write(paint,
                  leaf_paint(ctx.read<LeafFrame>(primitives), ctx.read<LeafLayer>(out.wood)));
      },
      RenderGraph::Threads::Any);
  out.layer = g.resource<LeafLayer>("leaf-layer");
  g.add_pass(
      "leaf-layer", {paint, out.tone}, {out.layer},
      [=](PassContext& ctx) {
        ctx.write(out.layer, leaf_layer(ctx.read<LeafPaint>(paint), ctx.read<LeafTone>(out.tone), p,
                                        lines, edges));
      },
      RenderGraph::Threads::Any);
  return out;
}

Handle<StrokeDrawing> add_leaf_strokes_pass(RenderGraph& g, Handle<LeafLayer> layer) {
  const auto out = g.resource<StrokeDrawing>("leaf-strokes");
  g.add_pass(
      "leaf-strokes", {layer}, {out},
      [=](PassContext& ctx) { ctx.write(out, ctx.read<LeafLayer>(layer).drawing); },
      RenderGraph::Threads::Any);
  return out;
}

}  // namespace sylva

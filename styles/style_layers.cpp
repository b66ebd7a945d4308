// A stacked preset's layers composited (styles/style.h, build_layers).
#include "core/error.h"
#include "passes/composite.h"
#include "passes/ink_lines.h"
#include "styles/style.h"

namespace sylva {

namespace {

// The strokes with the paint under them (StrokeDrawing::paint), for the vector files.
Handle<StrokeDrawing> add_paint_under_pass(RenderGraph& graph, Handle<StrokeDrawing> strokes,
                                           ImageHandle paint) {
  const auto out = graph.resource<StrokeDrawing>("painted-drawing");
  graph.add_pass("paint-under-lines", {strokes, paint}, {out},
                 [strokes, paint, out](PassContext& ctx) {
                   StrokeDrawing d = ctx.read<StrokeDrawing>(strokes);
                   d.paint = ctx.read<cv::Mat>(paint);
                   SYLVA_CHECK(d.paint.type() == CV_8UC4 && d.paint.size() == d.size,
                               "layers: the paint and the lines differ in size");
                   ctx.write(out, std::move(d));
                 });
  return out;
}

}  // namespace

StyleOutput build_layers(RenderGraph& graph, const GBufferHandles& gbuffer,
                         const std::vector<std::unique_ptr<Style>>& layers,
                         const StyleContext& context) {
  SYLVA_CHECK(!layers.empty(), "build_layers: no layers");
  StyleOutput out;
  ImageHandle paint;  // the first layer's picture
  for (size_t i = 0; i < layers.size(); ++i) {
    const Style& layer = *layers[i];
    GraphScope scope(graph, layer.info().name);
    const StyleOutput drawn = layer.build(graph, gbuffer, context);
    if (i == 0) {
      out = drawn;
      paint = drawn.image;
      continue;
    }
    SYLVA_CHECK(drawn.lines.valid() && drawn.strokes.valid(), "layers: a later layer draws lines");
    out.image = add_lines_over_pass(graph, drawn.lines, out.image, layer.params().edges.color);
    out.strokes = out.strokes.valid()
                      ? add_merge_strokes_pass(graph, out.strokes, drawn.strokes, "drawing")
                      : drawn.strokes;
  }
  if (!layers[0]->has_strokes() && out.strokes.valid())
    out.strokes = add_paint_under_pass(graph, out.strokes, paint);
  out.lines = {};
  return out;
}

}  // namespace sylva

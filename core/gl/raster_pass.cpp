#include "core/gl/raster_pass.h"

#include <memory>

namespace sylva {

ImageHandle GBufferHandles::of(Target t) const {
  switch (t) {
    case Target::Color:
      return color;
    case Target::Normal:
      return normal;
    case Target::Depth:
      return depth;
    case Target::Position:
      return position;
    case Target::Id:
      return id;
    case Target::Ka:
      return ka;
    case Target::Albedo:
      return albedo;
    case Target::Ao:
      return ao;
  }
  return {};
}

namespace {
cv::Mat& slot(GBuffer& b, Target t) {
  switch (t) {
    case Target::Color:
      return b.color;
    case Target::Normal:
      return b.normal;
    case Target::Depth:
      return b.depth;
    case Target::Position:
      return b.position;
    case Target::Id:
      return b.id;
    case Target::Ka:
      return b.ka;
    case Target::Albedo:
      return b.albedo;
    case Target::Ao:
      return b.ao;
  }
  return b.color;
}
}  // namespace

GBufferHandles add_raster_pass(RenderGraph& graph, const RasterSetup& setup) {
  SYLVA_CHECK(setup.rasterizer != nullptr, "raster pass needs a rasterizer");
  GBufferHandles h;
  h.color = graph.resource<cv::Mat>("color");
  h.normal = graph.resource<cv::Mat>("normal");
  h.depth = graph.resource<cv::Mat>("depth");
  h.position = graph.resource<cv::Mat>("position");
  h.id = graph.resource<cv::Mat>("id");
  h.ka = graph.resource<cv::Mat>("ka");
  h.albedo = graph.resource<cv::Mat>("albedo");
  h.ao = graph.resource<cv::Mat>("ao");
  std::vector<ResourceRef> reads;
  if (setup.shading.valid()) reads.push_back(setup.shading);
  if (setup.ao.valid()) reads.push_back(setup.ao);
  graph.add_pass(
      "raster", reads, {h.color, h.normal, h.depth, h.position, h.id, h.ka, h.albedo, h.ao},
      [h, setup](PassContext& ctx) {
        if (setup.shading.valid())
          setup.rasterizer->set_vertex_shading(ctx.read(setup.shading));
        else if (setup.own_shading)
          setup.rasterizer->restore_vertex_shading();
        RasterRequest request = setup.request;
        if (setup.ao.valid()) request.ao = *ctx.read(setup.ao);
        request.targets = 0;
        for (Target t : kAllTargets)
          if (ctx.wanted(h.of(t))) request.targets |= static_cast<TargetMask>(t);
        GBuffer buffers = setup.rasterizer->render(setup.camera, setup.lighting, request);
        for (Target t : kAllTargets)
          if (has(request.targets, t)) ctx.write(h.of(t), slot(buffers, t));
      });
  return h;
}

}  // namespace sylva

#include "core/gl/raster_pass.h"

#include <memory>

namespace sylva {

int GBufferHandles::of(Target t) const {
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
  return -1;
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
  h.color = graph.resource("color");
  h.normal = graph.resource("normal");
  h.depth = graph.resource("depth");
  h.position = graph.resource("position");
  h.id = graph.resource("id");
  h.ka = graph.resource("ka");
  h.albedo = graph.resource("albedo");
  h.ao = graph.resource("ao");
  std::vector<int> reads;
  if (setup.shading >= 0) reads.push_back(setup.shading);
  if (setup.ao >= 0) reads.push_back(setup.ao);
  graph.add_pass(
      "raster", reads, {h.color, h.normal, h.depth, h.position, h.id, h.ka, h.albedo, h.ao},
      [h, setup](PassContext& ctx) {
        if (setup.shading >= 0)
          setup.rasterizer->set_vertex_shading(
              *ctx.read<std::shared_ptr<const VertexShading>>(setup.shading));
        else if (setup.own_shading)
          setup.rasterizer->restore_vertex_shading();
        RasterRequest request = setup.request;
        if (setup.ao >= 0) request.ao = *ctx.read<std::shared_ptr<const AoShading>>(setup.ao);
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

// The raster pass as a render-graph node: writes the eight G-buffer resources ("color",
// "normal", "depth", "position", "id", "ka", "albedo", "ao", each a cv::Mat as described in
// gbuffer.h) and,
// when run, asks the rasteriser for only the targets some live pass reads or the caller
// presents.
#pragma once

#include "core/gl/rasterizer.h"
#include "core/graph/render_graph.h"

namespace sylva {

using ShadingHandle = Handle<std::shared_ptr<const VertexShading>>;
using AoShadingHandle = Handle<std::shared_ptr<const AoShading>>;

struct GBufferHandles {
  ImageHandle color{}, normal{}, depth{}, position{}, id{}, ka{}, albedo{}, ao{};
  ImageHandle of(Target t) const;
};

struct RasterSetup {
  Rasterizer* rasterizer = nullptr;  // uploaded with the scene; outlives the graph's execute()
  Camera camera;
  Lighting lighting;
  RasterRequest request;  // request.targets is ignored: the graph decides
  // A resource holding std::shared_ptr<const VertexShading> (the Luft preprocessing) the
  // pass reads and applies before drawing; none = draw the uploaded normals.
  ShadingHandle shading{};
  // Without shading: put the scene's own normals and ka back first, which an earlier raster
  // pass on the same rasterizer may have replaced (the cells of a contact sheet).
  bool own_shading = false;
  // A resource holding std::shared_ptr<const AoShading> (the fitted AO shells, e.g.
  // npr/ao_pass.h) that replaces request.ao when the pass runs; none = request.ao as given.
  AoShadingHandle ao{};
};

GBufferHandles add_raster_pass(RenderGraph& graph, const RasterSetup& setup);

}  // namespace sylva

// The style table: each style wires passes onto the G-buffer resources of a render graph
// and returns the resource holding its final image (CV_8UC4 BGRA). Later styles (ink, toon,
// watercolor, blobs) add passes here without changing the graph.
#pragma once

#include <string>
#include <vector>

#include "core/gl/raster_pass.h"
#include "core/graph/render_graph.h"
#include "npr/illumination_pass.h"

namespace sylva {

struct StyleInfo {
  std::string name;
  std::string description;
  int (*build)(RenderGraph& graph, const GBufferHandles& gbuffer);
  NormalMode normals = NormalMode::Original;  // what the raster pass draws with
};

const std::vector<StyleInfo>& style_table();

// Throws InputError("--style", "unknown style 'x' (available: standard)").
const StyleInfo& find_style(const std::string& name);

// Standard: Luft et al. Eq. 1 local illumination with the original normals, straight from
// the raster pass's colour target.
int build_standard(RenderGraph& graph, const GBufferHandles& gbuffer);
// Expressive (Luft et al.): the same Eq. 1 colour, drawn with realigned normals and the
// density ambient coefficient (the style's NormalMode::Realigned does the work).
int build_expressive(RenderGraph& graph, const GBufferHandles& gbuffer);

}  // namespace sylva

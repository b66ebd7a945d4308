// Background: puts a style's image (CV_8UC4 BGRA sRGB, colour premultiplied by alpha =
// coverage, as the albedo-based passes write it) over the frame's background colour, in linear
// light: C = C_image + (1 - alpha) B. A transparent background (alpha 0) keeps the image as
// it is. Reads the image resource, writes "<name>" (CV_8UC4 BGRA sRGB).
#pragma once

#include <glm/glm.hpp>
#include <opencv2/core.hpp>
#include <string>

#include "core/graph/render_graph.h"

namespace sylva {

// background: linear RGBA in [0, 1] (RasterRequest::background).
cv::Mat over_background(const cv::Mat& premultiplied_bgra, const glm::vec4& background);

ImageHandle add_background_pass(RenderGraph& graph, ImageHandle image, const glm::vec4& background,
                                const std::string& name = "final");

}  // namespace sylva

// Ink compositing (issue "Styles"): the "ink" look, dark lines on white or paper-coloured
// ground like a pen drawing, optionally over a light wash of the shaded colour.
//
// Paper pass: reads one image only for its size; writes "paper", CV_32FC3 linear BGR: the
//   paper colour, optionally with seeded grain (deterministic; the grain is laid out in
//   reference pixels, so the same seed gives the same sheet at any resolution).
// Ink composite pass: reads "edges"-like line coverage (CV_32FC1 in [0, 1]), the coverage or
//   colour image (CV_32FC1 coverage, or CV_8UC4 BGRA sRGB with alpha = coverage, as the raster
//   pass's "color") and "paper"; writes "ink", the final CV_8UC4 BGRA sRGB image. The wash
//   is blended in linear light, the lines over it in sRGB-encoded values (as SVG and PDF
//   renderers composite strokes, so the raster ink and the vector files look alike):
//     ground = paper * mix(1, shaded, fill * coverage)      (a wash multiplies, like pigment)
//     out    = mix(srgb(ground), srgb(line colour), lines)
//   With a plain coverage mask there is no shaded colour: the wash is the line colour (a flat
//   silhouette fill). Opaque unless `transparent`.
#pragma once

#include <glm/glm.hpp>
#include <opencv2/core.hpp>

#include "core/graph/render_graph.h"
#include "core/params.h"

namespace sylva {

struct PaperParams {
  // ink.paper_color: the ground, linear RGB ("#RRGGBB" sRGB in presets). Default white.
  glm::vec3 color{1.0f, 1.0f, 1.0f};
  // ink.grain: paper grain strength, [0, 1]: 0 = flat colour, 1 = the ground's brightness
  // varies by about +-15%. Default 0.
  float grain = 0.0f;
  // ink.grain_size: size of the finest grain in px at the 1024 px reference, [0.5, 32].
  // Default 2.
  float grain_size = 2.0f;
  // ink.seed: the grain's random seed, [0, 2147483647]. Default 1.
  int seed = 1;
};

// The paper at `size`: CV_32FC3 linear BGR, finite and >= 0.
cv::Mat make_paper(const cv::Size& size, const PaperParams& p);

// Adds the pass "paper" at `size` and returns "paper". It reads nothing, so it runs while the
// raster draws.
ImageHandle add_paper_pass(RenderGraph& g, cv::Size size, const PaperParams& p);

struct InkParams {
  PaperParams paper;  // ink.paper_color, ink.grain, ink.grain_size, ink.seed
  // ink.fill: strength of the wash of the shaded colour under the lines, [0, 1]: 0 = pure pen
  // drawing, 1 = the full shaded colour. Default 0.
  float fill = 0.0f;
  // ink.transparent: paper only under the drawing; elsewhere alpha 0 (straight alpha), for
  // compositing over another background. Default false (opaque sheet).
  bool transparent = false;
  // The lines' colour, linear RGB. Not an ink.* key: the style copies EdgeParams::color
  // (edges.color) here. Default black.
  glm::vec3 line_color{0.0f, 0.0f, 0.0f};
};

// Binds ink.paper_color, ink.grain, ink.grain_size, ink.seed, ink.fill, ink.transparent.
// `set` refers into `p`.
void bind_ink_params(ParamSet& set, InkParams& p);

// The composite itself (see the header comment). lines: CV_32FC1; coverage_or_color: CV_32FC1
// or CV_8UC4; paper: CV_32FC3 linear BGR; all the same size, or the paper 1 x 1 for a flat
// sheet. Returns CV_8UC4 BGRA sRGB.
cv::Mat composite_ink(const cv::Mat& lines, const cv::Mat& coverage_or_color, const cv::Mat& paper,
                      const InkParams& p);

// Adds the paper pass and the pass "ink-composite"; returns its output "ink" (cv::Mat
// CV_8UC4 BGRA sRGB). size: the frame's, which the lines and coverage_or_color have (the paper
// is made at it without waiting for them; a flat sheet, without grain, as one pixel).
ImageHandle add_ink_composite_pass(RenderGraph& g, ImageHandle lines, ImageHandle coverage_or_color,
                                   const InkParams& p, cv::Size size);

// A stacked preset's lines over the picture below them (styles/style.h, build_layers): the
// line colour (linear RGB) laid over `picture` (CV_8UC4 BGRA sRGB, straight alpha) with the
// coverage `lines` (CV_32FC1 in [0, 1]), in sRGB-encoded values as composite_ink lays them
// over paper, so a line pixel over white paint is the line style's pixel. Where the picture is
// transparent the lines keep their coverage as alpha. Returns CV_8UC4 BGRA sRGB.
cv::Mat lines_over(const cv::Mat& lines, const cv::Mat& picture, const glm::vec3& line_color);

// Adds the pass "lines-over" and returns its output "lines-over".
ImageHandle add_lines_over_pass(RenderGraph& g, ImageHandle lines, ImageHandle picture,
                                const glm::vec3& line_color);

}  // namespace sylva

// Ink lines as strokes (issue "Ink for illustrators"; DESIGN.md §6): the G-buffer's feature
// lines, abstracted to the picture's scale, sorted into the line hierarchy and chained into
// strokes (core/strokes.h) from which the raster ink and the vector files are drawn.
//
// Abstraction (Deussen & Strothotte 2000: draw a tree at the level of detail the picture can
// hold). ink.detail is the smallest feature drawn, in px at the 1024 px reference. The crown's
// lines are found at a working resolution where the detail is 5 px (passes/ink_working.h), so
// every image size draws the same lines. Coherence (issue "Temporal coherence"): what decides
// the silhouette and the interior lines comes from the scene where there are surface samples
// (npr/surface_samples.h, projected by passes/crown_coverage.h), so it moves with the scene
// from one frame of a turntable to the next instead of flickering with the leaves that land
// on pixel centres:
//   - silhouette: the crown's coverage (projected from the scene, else the raster's) smoothed
//     at the detail, its level set enclosing the leaves (passes/ink_abstraction.h crown_field:
//     small holes filled, small separate pieces dropped), traced as closed contours and moved
//     onto the level set between the pixels' corners; and the centre lines of the thin parts
//     outside it that are long (a hanging strand, a twig: extent >= 2 x detail);
//   - interior crown contours: with surface samples, the crown's parts (leaf clusters) painted
//     back to front by their mean depth (passes/crown_coverage.h project_crown_parts) outline
//     where the part in front is nearer by more than a share of the plant's depth extent that
//     grows with the detail (detail / 256, Deussen & Strothotte's depth threshold relative to
//     the picture), drawn on the nearer part's side; without, steps of the depth
//     median-filtered over the detail between the id buffer's parts;
//   - wood: trunk and branch outlines on the raw buffers where the wood is the nearer side;
//   - detail: leaf-level depth jumps on the raw buffers (off in the built-in presets).
// Each chain is smoothed along its length (Gaussian, sigma = detail / 3 px for silhouettes and
// interior lines, 0.7 px for wood and detail, which removes the pixel staircase), simplified
// (Douglas-Peucker, 0.5 px) and dropped when shorter than 2 x detail (silhouette, interior),
// 6 x detail (wood: the trunk and main branches, not every branch seen through a gap) or 1 x
// detail (detail), and than edges.min_length. ink.detail = 0 keeps the leaf-exact lines:
// silhouette = coverage, interior = the raw depth, normal and id discontinuities of edges.*.
//
// Reads (render graph): "color" (CV_8UC4, alpha = coverage), "depth" (CV_32FC1 linear view
// depth, 0 = background), "normal" (CV_32FC3, only with edges.normal at ink.detail = 0), "id"
// (CV_32SC1 cluster ids: wood = the scene's branch cluster) and, when given,
// "surface-samples". Writes "ink-strokes", a StrokeDrawing at the frame's size.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "core/gl/camera.h"
#include "core/graph/render_graph.h"
#include "core/params.h"
#include "core/strokes.h"
#include "npr/surface_samples.h"
#include "passes/edges.h"

namespace sylva {

// One class of the line hierarchy: lines.<class>, lines.<class>_width, _tone, _taper,
// _depth_width.
struct LineClassParams {
  bool on = true;
  // px at the 1024 px reference (x reference_scale), no thinner than edges.min_width px.
  // Range [0.25, 16].
  float width = 1.5f;
  // opacity of the class's ink, [0, 1]: 1 = full ink, 0.5 = a grey line on white.
  float tone = 1.0f;
  // px at 1024 px over which an open stroke narrows to nothing at each end (at most half its
  // length); 0 = blunt round ends. Range [0, 256].
  float taper = 0.0f;
  // nearest lines this many times wider than the farthest (linear in depth over the plant's
  // depth range); 1 = even. Range [1, 8].
  float depth_width = 1.0f;
};

struct InkLineParams {
  // ink.detail: the smallest feature drawn, px at the 1024 px reference (scales with the image
  // like edges.width). 0 = leaf-exact lines. Range [0, 64]; default 10.
  float detail = 10.0f;
  LineClassParams silhouette{true, 2.0f, 1.0f, 0.0f, 1.0f};
  LineClassParams interior{true, 1.3f, 1.0f, 0.0f, 1.0f};
  LineClassParams wood{true, 1.3f, 1.0f, 0.0f, 1.0f};
  LineClassParams detail_lines{false, 0.8f, 0.6f, 0.0f, 1.0f};
  // The foliage primitives' outlines inside the crown (passes/leaf_primitives.h); their
  // outlines against the paper are silhouette lines.
  LineClassParams foliage{true, 1.0f, 1.0f, 0.0f, 1.0f};
  // lines.outline: the plant's outline as one contour enclosing the crown (the crown field's
  // level set, with the thin parts' centre lines), as the `outline` preset draws it; off when
  // the foliage primitives draw the silhouette. Default false.
  bool outline = false;
  // lines.wood_shade: hatching along the trunk and branches on their shadow side
  // (passes/hatch_groups.h; with the foliage primitives). Default true.
  bool wood_shade = true;
  // lines.plants: in a scene of many plants, outline each plant where it stands in front of
  // another (silhouette lines). Default true.
  bool plants = true;
  const LineClassParams& of(LineClass c) const;
};

// Binds ink.detail and lines.* with ranges, units and docs. `set` refers into `p`.
void bind_ink_line_params(ParamSet& set, InkLineParams& p);

struct InkLineImages {
  cv::Mat color;   // CV_8UC4, alpha = coverage
  cv::Mat depth;   // CV_32FC1
  cv::Mat normal;  // CV_32FC3 or empty (needed only for edges.normal at detail 0)
  cv::Mat id;      // CV_32SC1 cluster ids, or empty (no wood class then)
  // The scene's surface samples (npr/surface_samples.h) and the frame's camera: the outline and
  // the crown parts are projected from them (passes/crown_coverage.h). Null: the outline
  // follows the colour's alpha, the parts the id buffer.
  std::shared_ptr<const SurfaceSamples> samples;
  Camera camera;
};

// The strokes of one frame. branch_cluster: the cluster id of trunk and branches (0 = none).
// edges: the kinds and thresholds of the leaf-level lines, edges.min_width, edges.min_length
// and edges.color (the drawing's colour).
StrokeDrawing ink_line_strokes(const InkLineImages& in, const EdgeParams& edges,
                               const InkLineParams& p, uint32_t branch_cluster);

struct InkLineResources {
  ImageHandle color{}, depth{}, normal{}, id{};
  SamplesHandle samples{};  // "surface-samples" (npr/surface_samples.h), or none
  Camera camera;            // the frame's, with samples
};

// Adds the pass "ink-strokes" and returns its output "ink-strokes" (StrokeDrawing).
Handle<StrokeDrawing> add_ink_lines_pass(RenderGraph& g, const InkLineResources& in,
                                         const EdgeParams& edges, const InkLineParams& p,
                                         uint32_t branch_cluster);

// Adds the pass `name` and returns its output `name`: the StrokeDrawing `first` with the
// strokes of `second` drawn after (over) them.
Handle<StrokeDrawing> add_merge_strokes_pass(RenderGraph& g, Handle<StrokeDrawing> first,
                                             Handle<StrokeDrawing> second,
                                             const std::string& name = "drawing");

// Adds the pass "stroke-raster" reading a StrokeDrawing resource and returns "lines", its ink
// coverage (CV_32FC1 in [0, 1], core/stroke_render.h).
ImageHandle add_stroke_raster_pass(RenderGraph& g, Handle<StrokeDrawing> strokes);

// The lines of a drawing made of parts (the foliage's, the wood's, the hatching's, ...; invalid
// handles skipped), each part rasterised in its own pass "stroke-raster-NAME" (coverage
// "lines-NAME") as soon as it is drawn, beside the passes still drawing the others, and joined by
// the pass "stroke-union" into "lines": 1 - the product of each part's 1 - coverage, which is
// what drawing every stroke on one surface gives (cairo rounds to 8 bits after each stroke, the
// join does not: they differ by a level at most here and there). One valid part:
// add_stroke_raster_pass.
struct StrokePart {
  std::string name;
  Handle<StrokeDrawing> strokes;
};
ImageHandle add_stroke_parts_raster_pass(RenderGraph& g, const std::vector<StrokePart>& parts);

}  // namespace sylva

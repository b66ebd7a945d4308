// Styles: a preset (styles/presets.h) names a builder and sets parameters (styles/
// style_params.h); the builder wires image passes onto the G-buffer resources of a render
// graph and returns the resource holding the final image (CV_8UC4 BGRA sRGB). The graph culls
// every buffer and pass the style does not read (DESIGN.md §3).
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/gl/lights.h"
#include "core/gl/raster_pass.h"
#include "core/graph/render_graph.h"
#include "core/params.h"
#include "npr/illumination_pass.h"
#include "npr/leaf_pieces.h"
#include "styles/presets.h"
#include "styles/style_params.h"

namespace sylva {

// What a builder may need besides the G-buffers: the frame's lights and camera.
struct StyleContext {
  Lighting lighting;
  glm::mat4 view{1.0f};              // world -> view
  glm::vec4 background{1, 1, 1, 0};  // linear RGBA (RasterRequest::background)
  // The raster pass's colour clear for this style (RasterRequest::background as
  // Style::configure set it; a stack shares its line layer's): what the colour's edge pixels
  // are mixed with. Transparent black = premultiplied colour.
  glm::vec4 clear{0.0f};
  float foliage_diagonal = 0;  // scene units; 0 = unknown (scale of object-space noise)
  // For styles that render extra views (toon's shadow map from the key light): the uploaded
  // scene and a sphere around it. May be null/empty when no such style is built.
  Rasterizer* rasterizer = nullptr;
  Sphere scene_sphere;
  // What the key light's shadow map covers: in a scene of many plants the instances the camera
  // sees (visible_instances_sphere), the whole scene_sphere still casting into it; empty = the
  // scene_sphere (a flat scene).
  Sphere shadow_sphere;
  Camera camera;  // the frame's camera (blobs.outlines = alone renders it once per cluster)
  // The cluster id of trunk and branches (Scene::branch_cluster_id), 0 = none: the blobs
  // style paints them as its base layer rather than as a blob.
  uint32_t branch_cluster = 0;
  // The frame's blobs when an animation interpolates them between keyframes
  // (npr/blob_keyframes.h); null = shrink-wrap this frame's own clusters.
  std::shared_ptr<const BlobSet> blobs;
  // The scene-level "surface-samples" node (npr/surface_samples.h) the ink lines' crown
  // coverage is projected from; none = the outline follows the raster's coverage.
  SamplesHandle surface_samples{};
  // The scene-level "leaf-pieces" node (npr/leaf_pieces.h) the ink styles' foliage primitives
  // are projected from; none = no foliage primitives.
  LeafPiecesHandle leaf_pieces{};
};

// What a style adds to the graph: its final image (CV_8UC4 BGRA sRGB) and, for styles made of
// lines, the StrokeDrawing (core/strokes.h) the image's lines are drawn from (none = no lines).
struct StyleOutput {
  ImageHandle image{};
  Handle<StrokeDrawing> strokes{};
  // For styles made of lines: the lines' coverage (CV_32FC1 in [0, 1]) the image composites,
  // so a stacked preset can lay the same lines over another layer's paint.
  ImageHandle lines{};
};

// What the code around a builder needs to know of it, declared in the table instead of tested
// by name.
struct BuilderTraits {
  bool coverage_alpha = false;  // reads the colour's alpha as coverage (background alpha 0)
  bool strokes = false;         // build() gives a StrokeDrawing (lines; SVG and PDF output)
  bool blob_outlines = false;   // draws blob outlines, which turntables can keyframe
  // Reads the colour premultiplied over black (a transparent black clear): supersampled edge
  // pixels then carry the leaf's colour times its coverage, not the view's background mixed in
  // (a stack keeps its line layer's clear).
  bool premultiplied_color = false;
};

struct StyleBuilder {
  std::string name;
  std::string description;
  StyleOutput (*build)(RenderGraph& graph, const GBufferHandles& gbuffer, const StyleParams& params,
                       const StyleContext& context);
  IdKind ids = IdKind::Primitive;  // what the id buffer holds for this builder
  BuilderTraits traits;
};

const std::vector<StyleBuilder>& builder_table();
// Throws InputError(where, "unknown builder 'x' (available: ...)").
const StyleBuilder& find_builder(const std::string& name, const std::string& where);

// shaded: Luft et al. Eq. 1 local illumination straight from the raster pass's colour
// target, with whatever normals style.normals selects (standard, expressive).
StyleOutput build_shaded(RenderGraph& graph, const GBufferHandles& gbuffer,
                         const StyleParams& params, const StyleContext& context);

// toon: Decaudin's cartoon shading of the albedo in k bands of N.L (passes/toon.h); with
// toon.cast_shadows, a depth-only raster pass from the key light (graph scope "key-shadow")
// makes the shadow map.
StyleOutput build_toon(RenderGraph& graph, const GBufferHandles& gbuffer, const StyleParams& params,
                       const StyleContext& context);

// ink: the line hierarchy as strokes (passes/ink_lines.h: silhouette, interior crown contours,
// wood, detail, abstracted to ink.detail), rasterised and drawn over paper
// (passes/composite.h), optionally over a wash of the shaded colour; the id buffer holds
// cluster ids (wood = the branch cluster).
StyleOutput build_ink(RenderGraph& graph, const GBufferHandles& gbuffer, const StyleParams& params,
                      const StyleContext& context);

// watercolor: a glazed wash per leaf cluster (Bousseau et al. 2006; Luft & Deussen 2006),
// passes/watercolor.h; the id buffer holds cluster ids.
StyleOutput build_watercolor(RenderGraph& graph, const GBufferHandles& gbuffer,
                             const StyleParams& params, const StyleContext& context);

// blobs: Dudley's shrink-wrapped blob billboards (passes/blobs.h), one per leaf cluster, over
// the trunk and branches; the id buffer holds cluster ids.
StyleOutput build_blobs(RenderGraph& graph, const GBufferHandles& gbuffer,
                        const StyleParams& params, const StyleContext& context);

// A preset resolved into parameters. Not copyable: `set` refers into `params`.
//
// A stacked preset (`layers = ["watercolor", "ink"]`, styles/presets.h) holds one Style per
// layer, each its own preset with the stacked preset's keys and the overrides applied on top.
// Every layer after the first must draw lines; build() draws the layers from one set of
// G-buffers and lays each line layer's lines over the picture below, as the line style lays
// them over paper. The G-buffers are rendered as the line layer asks (its normals, foliage
// and AO settings: params() is the line layer's), so the lines are that style's lines.
class Style {
 public:
  // Applies the preset (built-in name or .toml path), then each "key=value" of `overrides`
  // (where = "--set"). Throws InputError.
  Style(const std::string& name_or_path, const std::vector<std::string>& overrides = {});
  Style(const Style&) = delete;
  Style& operator=(const Style&) = delete;

  const PresetInfo& info() const { return m_info; }
  // The builder, or a stack's layers' builders: "watercolor+ink".
  std::string builder_text() const;
  const BuilderTraits& traits() const;  // the traits of the preset's builder
  StyleParams& params() { return m_params; }
  const StyleParams& params() const { return m_params; }
  ParamSet& set() { return m_set; }
  const ParamSet& set() const { return m_set; }
  NormalMode normals() const;
  // foliage.* for a frame of `camera` framing `sphere`: with ink.detail > 0 (line styles), rho
  // = auto takes its radius from the picture's scale, 3 x ink.detail px at the sphere's
  // centre (FoliageSettings::picture_rho), so the realigned normals are smooth at the scale
  // the lines draw.
  FoliageSettings foliage_settings(const Camera& camera, const Sphere& sphere) const;
  // What this style needs of the raster pass besides the targets it reads: the id kind and
  // flat albedo.
  void configure(RasterRequest& request) const;
  StyleOutput build(RenderGraph& graph, const GBufferHandles& gbuffer,
                    const StyleContext& context) const;
  bool has_strokes() const;  // whether build() gives a StrokeDrawing (styles made of lines)
  // The layers of a stacked preset, in drawing order; empty for a plain one.
  const std::vector<std::unique_ptr<Style>>& layers() const { return m_layers; }

 private:
  void add_layers(const std::string& name_or_path, const std::vector<std::string>& overrides);
  const Style& primary() const;  // the layer whose G-buffer settings a stack uses
  IdKind id_kind() const;

  StyleParams m_params;
  ParamSet m_set;
  PresetInfo m_info;
  std::vector<std::unique_ptr<Style>> m_layers;
  BuilderTraits m_traits;  // the builder's, or for layers their union
};

// The picture of a stacked preset's layers (Style::layers): the first layer's image with each
// later layer's lines laid over it (passes/composite.h, lines_over), and their strokes, whose
// vector files carry the first layer's image as the paint under the lines when it draws none.
StyleOutput build_layers(RenderGraph& graph, const GBufferHandles& gbuffer,
                         const std::vector<std::unique_ptr<Style>>& layers,
                         const StyleContext& context);

}  // namespace sylva

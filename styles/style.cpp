#include "styles/style.h"

#include "core/error.h"
#include "passes/background.h"
#include "passes/blobs.h"
#include "passes/hatch_groups.h"
#include "passes/pass_common.h"
#include "passes/wood_lines.h"
#include "styles/blob_raster.h"

namespace sylva {

StyleOutput build_shaded(RenderGraph&, const GBufferHandles& gbuffer, const StyleParams&,
                         const StyleContext&) {
  return {gbuffer.color};
}

namespace {

// The key light in world space (a headlight, no lights, has none): a direction toward it or
// its place.
KeyLight key_light_of(const StyleContext& context) {
  KeyLight k;
  const int key = toon_key_light(context.lighting);
  if (key < 0) return k;
  const Light& light = context.lighting.lights[static_cast<size_t>(key)];
  k.on = true;
  k.point = light.type == Light::Type::Point;
  k.toward = light.vector;
  if (light.camera_fixed) {  // view space -> world space
    const glm::mat4 to_world = glm::inverse(context.view);
    k.toward =
        k.point ? glm::vec3(to_world * glm::vec4(k.toward, 1.0f)) : glm::mat3(to_world) * k.toward;
  }
  k.sphere = context.shadow_sphere.empty() ? context.scene_sphere : context.shadow_sphere;
  return k;
}

// The key light's shadow map: the scene's depth seen from the light (toon_key_light), as a
// resource holding a ToonShadowMap. A headlight (no lights) casts no visible shadow, so it
// gets an empty map.
Handle<ToonShadowMap> add_key_shadow_pass(RenderGraph& graph, const StyleContext& context,
                                          int size) {
  SYLVA_CHECK(context.rasterizer != nullptr && !context.scene_sphere.empty(),
              "toon.cast_shadows: the style context has no scene to render the shadow map from");
  GraphScope scope(graph, "key-shadow");
  const auto out = graph.resource<ToonShadowMap>("shadow-map");
  const KeyLight key = key_light_of(context);
  if (!key.on) {
    graph.add_pass("shadow-map", {}, {out},
                   [out](PassContext& ctx) { ctx.write(out, ToonShadowMap{}); });
    return out;
  }
  RasterSetup rs;
  rs.rasterizer = context.rasterizer;
  rs.camera = context.shadow_sphere.empty()
                  ? make_light_camera(context.scene_sphere, key.toward, key.point, size)
                  : make_light_camera(context.shadow_sphere, key.toward, key.point, size,
                                      context.scene_sphere);
  rs.lighting = context.lighting;
  const GBufferHandles g = add_raster_pass(graph, rs);
  const glm::mat4 view = rs.camera.view, proj = rs.camera.proj;
  graph.add_pass("shadow-map", {g.depth}, {out}, [=](PassContext& ctx) {
    ToonShadowMap m;
    m.depth = ctx.read<cv::Mat>(g.depth);
    m.light_view = view;
    m.light_proj = proj;
    ctx.write(out, m);
  });
  return out;
}

}  // namespace

StyleOutput build_toon(RenderGraph& graph, const GBufferHandles& gbuffer, const StyleParams& params,
                       const StyleContext& context) {
  validate_toon_params(params.toon);
  ToonResources r;
  r.normal = gbuffer.normal;
  r.albedo = gbuffer.albedo;
  r.ka = gbuffer.ka;
  r.position = gbuffer.position;
  if (params.toon.cast_shadows)
    r.shadow = add_key_shadow_pass(graph, context, params.toon.shadow_map_size);
  return {add_background_pass(graph,
                              add_toon_pass(graph, r, context.lighting, context.view, params.toon),
                              context.background)};
}

namespace {

// The strokes `a` with `b` drawn over them; either may be none.
Handle<StrokeDrawing> over(RenderGraph& graph, Handle<StrokeDrawing> a, Handle<StrokeDrawing> b,
                           const std::string& name) {
  if (!a.valid()) return b;
  if (!b.valid()) return a;
  return add_merge_strokes_pass(graph, a, b, name);
}

struct LineDrawing {
  Handle<StrokeDrawing> strokes;
  LeafLayers leaves;  // none without foliage primitives
  // What `strokes` is made of, rasterised part by part (add_stroke_parts_raster_pass).
  std::vector<StrokePart> parts;
};

// The line drawing: the foliage primitives (passes/leaf_primitives.h) and the wood drawn where
// it is seen (passes/wood_lines.h), or with lines.outline the crown's one contour and the wood
// at the working resolution; interior and detail lines from passes/ink_lines.h when on.
LineDrawing add_line_drawing(RenderGraph& graph, const GBufferHandles& gbuffer,
                             const StyleParams& params, const StyleContext& context) {
  const InkLineParams& lines = params.lines;
  InkLineParams rest = lines;
  if (!lines.outline) rest.silhouette.on = rest.wood.on = false;
  Handle<StrokeDrawing> strokes;
  if (lines.outline || rest.interior.on || rest.detail_lines.on) {
    InkLineResources r;
    r.color = gbuffer.color;
    r.depth = gbuffer.depth;
    r.normal = gbuffer.normal;
    r.id = gbuffer.id;
    r.samples = context.surface_samples;
    r.camera = context.camera;
    strokes = add_ink_lines_pass(graph, r, params.edges, rest, context.branch_cluster);
  }
  if (lines.outline) return {strokes, {}, {{"other", strokes}}};
  WoodResources wr;
  wr.id = gbuffer.id;
  wr.depth = gbuffer.depth;
  wr.samples = context.surface_samples;
  wr.camera = context.camera;
  const Handle<SeenWood> seen = add_seen_wood_pass(graph, wr, context.branch_cluster, lines.detail);
  Handle<StrokeDrawing> leaves;
  LeafLayers layer;
  if (lines.foliage.on && context.leaf_pieces.valid()) {
    LeafResources lr;
    lr.pieces = context.leaf_pieces;
    lr.color = gbuffer.color;
    lr.depth = gbuffer.depth;
    lr.wood = seen;
    lr.camera = context.camera;
    lr.units_per_px = units_per_px(context.camera, context.scene_sphere);
    lr.samples = context.surface_samples;
    lr.light = key_light_of(context);
    layer = add_leaf_layer_pass(graph, lr, params.leaves, lines, params.edges);
    leaves = add_leaf_strokes_pass(graph, layer.layer);
  }
  const Handle<StrokeDrawing> wood = add_wood_lines_pass(graph, seen, lines, params.edges);
  // The leaves under the wood, the other lines over both.
  return {over(graph, over(graph, leaves, wood, "leaves-and-wood"), strokes, "line-drawing"),
          layer,
          {{"leaves", leaves}, {"wood", wood}, {"other", strokes}}};
}

}  // namespace

StyleOutput build_ink(RenderGraph& graph, const GBufferHandles& gbuffer, const StyleParams& params,
                      const StyleContext& context) {
  const LineDrawing drawing = add_line_drawing(graph, gbuffer, params, context);
  Handle<StrokeDrawing> strokes = drawing.strokes;
  std::vector<StrokePart> parts = drawing.parts;
  const bool hatch = params.pen.tone == PenTone::Hatching;
  if (drawing.leaves.layer.valid() && (hatch || params.lines.wood_shade)) {
    validate_pen_params(params.pen);
    // pen: the crown and the wood; ink: the wood's shadow side only (lines.wood_shade), from the
    // wood's layer, so it does not wait for the foliage's painting.
    const Handle<StrokeDrawing> tone = add_hatch_groups_pass(
        graph, hatch ? drawing.leaves.layer : drawing.leaves.wood, gbuffer.normal, gbuffer.color,
        params.pen, params.lines.detail, {.foliage = hatch, .wood = params.lines.wood_shade},
        drawing.leaves.tone);
    strokes = add_merge_strokes_pass(graph, tone, strokes);  // tone under the lines
    parts.push_back({"tone", tone});
  } else if (params.pen.enabled()) {
    validate_pen_params(params.pen);
    ToneResources t;
    t.position = gbuffer.position;
    t.id = gbuffer.id;
    t.color = gbuffer.color;
    t.samples = context.surface_samples;
    ToneView view;
    view.view = context.view;
    view.proj = context.camera.proj;
    view.ortho = context.camera.ortho;
    view.units_per_px = units_per_px(context.camera, context.scene_sphere);
    const Handle<StrokeDrawing> tone =
        add_tone_pass(graph, t, view, params.pen, params.lines.detail);
    strokes = add_merge_strokes_pass(graph, tone, strokes);  // tone under the lines
    parts.push_back({"tone", tone});
  }
  // Each part rasterised as soon as it is drawn: the same coverage as `strokes` rasterised.
  const ImageHandle lines = add_stroke_parts_raster_pass(graph, parts);
  InkParams ink = params.ink;
  ink.line_color = params.edges.color;
  // The colour target is drawn on a transparent clear for ink (Style::configure), so its
  // alpha is the coverage the composite needs, and its colour the wash.
  const cv::Size frame(context.camera.width, context.camera.height);
  return {add_ink_composite_pass(graph, lines, gbuffer.color, ink, frame), strokes, lines};
}

StyleOutput build_watercolor(RenderGraph& graph, const GBufferHandles& gbuffer,
                             const StyleParams& params, const StyleContext& context) {
  WatercolorParams p = params.watercolor;
  p.reference_length = context.foliage_diagonal;
  WatercolorResources r;
  r.color = gbuffer.color;
  r.albedo = gbuffer.albedo;
  r.id = gbuffer.id;
  r.depth = gbuffer.depth;
  r.position = gbuffer.position;
  r.samples = context.surface_samples;
  r.camera = context.camera;
  r.wood_cluster = context.branch_cluster;
  r.units_per_px = units_per_px(context.camera, context.scene_sphere);
  r.pieces = context.leaf_pieces;
  r.light = key_light_of(context);
  r.clear = context.clear;
  return {add_watercolor_pass(graph, r, glm::inverse(context.view), p)};
}

StyleOutput build_blobs(RenderGraph& graph, const GBufferHandles& gbuffer,
                        const StyleParams& params, const StyleContext& context) {
  const BlobParams& p = params.blobs;
  validate_blob_params(p);
  Handle<BlobSet> outlines;
  if (context.blobs) {
    outlines = graph.resource<BlobSet>("blob-outlines");
    graph.add_pass(
        "blob-keyframes", {}, {outlines},
        [outlines, set = context.blobs](PassContext& ctx) { ctx.write(outlines, *set); });
  } else if (p.outlines == BlobOutlineSource::Alone) {
    SYLVA_CHECK(context.rasterizer != nullptr, "blobs.outlines = alone: no rasteriser");
    outlines = graph.resource<BlobSet>("blob-outlines");
    graph.add_pass("blob-outlines", {gbuffer.id}, {outlines},
                   [outlines, id = gbuffer.id, p, context](PassContext& ctx) {
                     ctx.write(outlines, still_blob_set(rasterised_blob_outlines(
                                             *context.rasterizer, context.camera, context.lighting,
                                             RasterRequest{}, p, context.branch_cluster,
                                             ctx.read<cv::Mat>(id))));
                   });
  } else {
    // "scene" without surface samples (a graph built without a scene) outlines what is seen.
    const SamplesHandle samples =
        p.outlines == BlobOutlineSource::Scene ? context.surface_samples : SamplesHandle{};
    outlines = add_blob_outlines_pass(graph, gbuffer.id, gbuffer.depth, context.branch_cluster, p,
                                      samples, context.camera);
  }
  BlobResources r;
  r.color = gbuffer.color;
  r.albedo = gbuffer.albedo;
  r.id = gbuffer.id;
  r.depth = gbuffer.depth;
  r.position = gbuffer.position;
  if (p.silhouettes) {
    // Leaf silhouettes from depth and normal jumps; the id buffer holds clusters, not leaves.
    EdgeParams e = params.edges;
    e.id = false;
    EdgeResources er;
    er.normal = gbuffer.normal;
    er.depth = gbuffer.depth;
    er.color = gbuffer.color;
    r.lines = add_edges_pass(graph, er, e);
  }
  BlobFrame frame;
  frame.lighting = context.lighting;
  frame.view = context.view;
  frame.background = context.background;
  frame.branch_cluster = context.branch_cluster;
  return {add_blobs_pass(graph, outlines, r, frame, p)};
}

const std::vector<StyleBuilder>& builder_table() {
  static const std::vector<StyleBuilder> table = {
      {"shaded",
       "local illumination (Luft et al. Eq. 1) from the raster pass",
       &build_shaded,
       IdKind::Primitive,
       {}},
      {"ink",
       "strokes of the line hierarchy, abstracted to the picture's scale, over paper",
       &build_ink,
       IdKind::Cluster,
       {.coverage_alpha = true, .strokes = true}},
      {"toon", "cartoon shading in k bands of N.L (Decaudin)", &build_toon, IdKind::Primitive, {}},
      {"watercolor",
       "a glazed watercolor wash per leaf cluster (Bousseau et al.)",
       &build_watercolor,
       IdKind::Cluster,
       {.premultiplied_color = true}},
      {"blobs",
       "shrink-wrapped blob billboards per leaf cluster over the branches (Dudley)",
       &build_blobs,
       IdKind::Cluster,
       {.coverage_alpha = true, .blob_outlines = true}},
  };
  return table;
}

const StyleBuilder& find_builder(const std::string& name, const std::string& where) {
  std::string names;
  for (const StyleBuilder& b : builder_table()) {
    if (b.name == name) return b;
    names += (names.empty() ? "" : ", ") + b.name;
  }
  throw InputError(where, "unknown builder '" + name + "' (available: " + names + ")");
}

Style::Style(const std::string& name_or_path, const std::vector<std::string>& overrides) {
  bind_style_params(m_set, m_params);
  m_info = apply_preset(name_or_path, m_set);
  for (const std::string& a : overrides)
    apply_assignment(a, m_set, "--set");
  if (m_info.layers.empty())
    m_traits = find_builder(m_info.builder, m_info.source).traits;
  else
    add_layers(name_or_path, overrides);
}

void Style::add_layers(const std::string& name_or_path, const std::vector<std::string>& overrides) {
  const std::string label =
      m_info.source == "built-in" ? "preset '" + m_info.name + "'" : m_info.source;
  for (const std::string& name : m_info.layers) {
    auto layer = std::make_unique<Style>(name);
    if (!layer->m_layers.empty())
      throw InputError(label, "layer '" + name + "' is itself a stack of layers");
    if (!m_layers.empty() && !layer->has_strokes())
      throw InputError(label, "layer '" + name + "' draws no lines (builder " +
                                  layer->m_info.builder +
                                  "): every layer after the first must be a line style");
    for (const auto& other : m_layers)
      if (other->m_info.name == layer->m_info.name)
        throw InputError(label, "layer '" + name + "' is named twice");
    apply_preset(name_or_path, layer->m_set);  // the stacked preset's keys over every layer
    for (const std::string& a : overrides)
      apply_assignment(a, layer->m_set, "--set");
    m_traits.strokes = m_traits.strokes || layer->m_traits.strokes;
    m_traits.coverage_alpha = m_traits.coverage_alpha || layer->m_traits.coverage_alpha;
    m_traits.blob_outlines = m_traits.blob_outlines || layer->m_traits.blob_outlines;
    m_layers.push_back(std::move(layer));
  }
  m_params = primary().m_params;  // the G-buffers follow the line layer
  // The first layer's own sections as it reads them, so the stack's parameters list each key
  // as the layer that uses it has it (a builder reads no other builder's section).
  const StyleParams& first = m_layers[0]->m_params;
  m_params.toon = first.toon;
  m_params.watercolor = first.watercolor;
  m_params.blobs = first.blobs;
}

std::string Style::builder_text() const {
  if (m_layers.empty()) return m_info.builder;
  std::string text;
  for (const auto& layer : m_layers)
    text += (text.empty() ? "" : "+") + layer->m_info.builder;
  return text;
}

const Style& Style::primary() const {
  return m_layers.size() > 1 ? *m_layers[1] : *m_layers[0];
}

FoliageSettings Style::foliage_settings(const Camera& camera, const Sphere& sphere) const {
  FoliageSettings s = m_params.foliage;
  if (has_strokes() && m_params.lines.detail > 0.0f && camera.height > 0) {
    const double scale = reference_scale(cv::Size(camera.width, camera.height));
    s.picture_rho = 3.0 * m_params.lines.detail * scale * units_per_px(camera, sphere);
  }
  return s;
}

NormalMode Style::normals() const {
  return m_params.normals;
}

IdKind Style::id_kind() const {
  if (m_layers.empty()) return find_builder(m_info.builder, m_info.source).ids;
  // Only the cluster builders read the id buffer.
  for (const auto& layer : m_layers)
    if (layer->id_kind() == IdKind::Cluster) return IdKind::Cluster;
  return IdKind::Primitive;
}

void Style::configure(RasterRequest& request) const {
  request.flat_albedo = m_params.albedo == AlbedoSource::Flat;
  request.id_kind = id_kind();
  // ink and blobs read the colour's alpha as coverage (the sheet keeps the view's background
  // for the style context).
  if (traits().coverage_alpha) request.background.a = 0.0f;
  if (m_layers.empty() && traits().premultiplied_color) request.background = glm::vec4(0.0f);
}

const BuilderTraits& Style::traits() const {
  return m_traits;
}

bool Style::has_strokes() const {
  return traits().strokes;
}

StyleOutput Style::build(RenderGraph& graph, const GBufferHandles& gbuffer,
                         const StyleContext& context) const {
  if (!m_layers.empty()) return build_layers(graph, gbuffer, m_layers, context);
  return find_builder(m_info.builder, m_info.source).build(graph, gbuffer, m_params, context);
}

}  // namespace sylva

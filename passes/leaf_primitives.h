// The foliage drawn with abstract drawing primitives (Deussen & Strothotte 2000; issue
// "Pen-and-ink that depicts the tree"): every leaf piece of the scene (npr/leaf_pieces.h)
// becomes a view-facing ellipse at its projected centre, of its own projected shape (auto) or
// round (disc), never smaller than leaves.size x ink.detail across, painted as a solid at its
// centre's view depth into a primitive buffer (a z-buffer of flat ellipses) where the raster's
// wood, which no leaf hides, stays in front. A primitive's outline is drawn where it stands in
// front of what lies behind it by more than a depth step, a share of the plant's depth extent
// (leaves.depth_step at ink.detail = 10 px, in proportion to the detail: bigger primitives and
// a bigger step give a more abstract crown of fewer, larger clumps; the plant is a connected
// piece of the picture, so plants side by side each get their own), and fades in over a band
// around the step (leaves.fade) by its width, so outlines thin out instead of popping as the
// view turns. Against the paper the outline is the plant's silhouette (LineClass::Silhouette,
// lines.silhouette_width); inside, a foliage line (LineClass::Foliage, lines.foliage_*).
//
// Tone zones as illustrators draw them: the tone is the rank of the primitive's darkness among
// the plant's (passes/tone_rank.h: the shaded colour, Luft's realigned normals and ka, smoothed
// at the detail), so every plant gets the same share of each zone. The lightest leaves.lit of
// the plant is lit: its depth step is leaves.lit_step times larger (few outlines, the lit side
// nearly bare); the darkest leaves.black is deep shadow: each primitive there is filled black
// from its centre, the fill growing from nothing to the whole primitive over leaves.black_fade
// of rank, so the black masses grow out of dots rather than switch on (LineClass::Shadow,
// filled regions). The darkness is the
// shaded colour times the share of the key light reaching the primitive through the crown
// (npr/sample_shadow.h, weighted by leaves.shadow).
//
// Everything is anchored in the scene: the primitives are the pieces' projections, their depth
// order and tone move with the scene. The primitive buffer is at a working resolution where a
// primitive is at least kPrimitivePx across, so every image size draws the same picture; the
// outlines are the ellipses' own arcs (no pixel staircase).
//
// Reads (render graph): "leaf-pieces", "color" (CV_8UC4, alpha = coverage: the tone),
// "seen-wood" and "surface-samples" (the key light's shadow map).
// Writes "leaf-primitives" (the primitives and the key light reaching them, which need no
// raster), "leaf-tone", "wood-layer" (the layer with the wood alone, for hatching the wood beside
// the foliage's painting), "leaf-paint" (the primitives painted over it, beside the tone) and
// "leaf-layer" (a LeafLayer).
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "core/gl/camera.h"
#include "core/graph/render_graph.h"
#include "core/params.h"
#include "core/strokes.h"
#include "npr/leaf_pieces.h"
#include "passes/ink_lines.h"
#include "passes/seen_wood.h"

namespace sylva {

// leaves.shape
enum class LeafShape {
  Auto,  // each piece's own projected shape (a needle or a willow leaf long, a broad leaf round)
  Disc,  // round, of the piece's projected area
};

struct LeafParams {
  LeafShape shape = LeafShape::Auto;
  // leaves.size: the smallest primitive's diameter as a multiple of ink.detail. [0.1, 8]; 1.
  float size = 1.0f;
  // leaves.depth_step: the depth step from which a primitive is outlined, as a share of the
  // plant's depth extent at ink.detail = 10 px (in proportion to the detail). [0.001, 1]; 0.1.
  float depth_step = 0.1f;
  // leaves.fade: the band over which an outline fades in, as a share of the step on either
  // side (0 = on or off). [0, 0.95]; 0.5.
  float fade = 0.5f;
  // leaves.lit: the lightest share of the plant drawn as lit. [0, 1]; 0.35.
  float lit = 0.35f;
  // leaves.lit_step: the depth step is this many times larger where lit. [1, 20]; 3.
  float lit_step = 3.0f;
  // leaves.shadow: how much the key light's shadow through the crown (npr/sample_shadow.h)
  // darkens the tone; 0 = the shaded colour alone. [0, 1]; 0.2.
  float shadow = 0.2f;
  // leaves.shadow_depth: how deep into the crown the key light reaches, as a share of the
  // scene's radius (the light falls to 1/e over it behind the first leaves). [0.02, 2]; 1.
  float shadow_depth = 1.0f;
  // leaves.black: the darkest share of the plant filled black (0 = none). [0, 1]; 0.25.
  float black = 0.25f;
  // leaves.black_fade: the share of the plant's tone over which a primitive's fill grows from a
  // dot to all of it. [0.01, 0.5]; 0.1.
  float black_fade = 0.1f;
};

// Binds leaves.* with ranges, units and docs. `set` refers into `p`.
void bind_leaf_params(ParamSet& set, LeafParams& p);

// A primitive is at least this many px across at the working resolution.
inline constexpr double kPrimitivePx = 6.0;

// One frame's primitives and the buffers the hatching (passes/hatching.h) lays its groups by.
struct LeafLayer {
  StrokeDrawing drawing;  // Shadow fills, then Foliage and Silhouette arcs
  double factor = 1.0;    // output px per working px (>= 1)
  // At the working resolution: the front primitive's index + 1 (kWoodFront where the raster's
  // wood is in front, 0 where nothing is), its view depth, the tone rank (0 off the plant).
  cv::Mat front, depth, rank;
  std::vector<uint32_t> clusters;    // per primitive, its leaf cluster
  std::vector<cv::Point2f> centres;  // per primitive, its centre (working px)
  std::vector<float> areas;          // per primitive, its leaves' area (scene units²)
  float near = 0, far = 0;           // the plant's depth range (scene units)
};
inline constexpr int32_t kWoodFront = -1;

// The key light, for the shadow through the crown.
struct KeyLight {
  bool on = false;         // a key light (not a headlight)
  glm::vec3 toward{0.0f};  // world direction toward a directional light, or a point light's place
  bool point = false;
  Sphere sphere;  // what the shadow map covers (the scene's framing sphere)
};
inline constexpr int kShadowMapSize = 256;  // texels

struct LeafImages {
  std::shared_ptr<const LeafPieces> pieces;
  Camera camera;  // the frame's
  cv::Mat color;  // CV_8UC4, alpha = coverage (the tone)
  cv::Mat depth;  // CV_32FC1 linear view depth, 0 = background
  SeenWood wood;  // the wood seen (passes/seen_wood.h), in front of every primitive
  // Scene units per px at the plant's distance (passes/hatching.h units_per_px): the clumps'
  // cell; 0 = one primitive per piece.
  double units_per_px = 0.0;
  std::shared_ptr<const SurfaceSamples> samples;  // the shadow map's points, or null (no shadow)
  KeyLight light;
};

struct Primitive;  // passes/leaf_outlines.h

// One frame's primitives and the key light reaching them: made from the scene and the camera
// alone, before the raster.
struct LeafFrame {
  cv::Size size, work;           // the output and the working resolution, px
  double factor = 1.0;           // output px per working px (>= 1)
  double sigma = 1.0;            // working px: the tone's smoothing (ink.detail)
  std::vector<Primitive> prims;  // those landing in or near the frame (rank and extent not set)
  // Per primitive: the key light's share reaching its centre, weighted by leaves.shadow (1 =
  // all of it, or no key light).
  std::vector<float> light;
};

// The primitives' tone, from the raster's colour.
struct LeafTone {
  std::vector<float> dark;  // per primitive, its darkness in [0, 1] (colour and shadow)
  // The colour's darkness at the working resolution, not smoothed (ToneRank::darkness; empty
  // when the frame shows no plant): the wood's hatching ranks the wood's tone by it.
  cv::Mat darkness;
};

// The frame's size is the colour's, or without one the camera's. lines: ink.detail.
LeafFrame leaf_frame(const LeafImages& in, const LeafParams& p, const InkLineParams& lines);

// color: the raster's (CV_8UC4) at frame.size.
LeafTone leaf_tone(const LeafFrame& frame, const cv::Mat& color);

// The layer with only the wood painted (front kWoodFront where `wood` is seen, 0 elsewhere; no
// primitives, no drawing): what the foliage is painted over.
LeafLayer wood_layer(const LeafFrame& frame, const SeenWood& wood, const EdgeParams& edges);

// A frame's primitives painted behind the wood, before their tone is known.
struct LeafPaint {
  // `wood` with the primitives painted (front, depth), and their depth range, clusters, centres
  // and areas; no rank or drawing yet.
  LeafLayer layer;
  std::vector<Primitive> prims;  // the frame's, with their plant's extent (rank not set)
};
LeafPaint leaf_paint(const LeafFrame& frame, const LeafLayer& wood);

// The layer: the painted primitives ranked by `tone` (made from the same frame) and outlined.
// lines: ink.detail, lines.foliage (the interior arcs) and lines.silhouette (the arcs against the
// paper); edges: edges.min_width.
LeafLayer leaf_layer(const LeafPaint& paint, const LeafTone& tone, const LeafParams& p,
                     const InkLineParams& lines, const EdgeParams& edges);

// leaf_layer of leaf_frame(in, p, lines), its tone from in.color, and in.wood.
LeafLayer leaf_layer(const LeafImages& in, const LeafParams& p, const InkLineParams& lines,
                     const EdgeParams& edges);

struct LeafResources {
  LeafPiecesHandle pieces{};
  ImageHandle color{}, depth{};
  Handle<SeenWood> wood{};  // or none
  Camera camera;
  double units_per_px = 0.0;
  SamplesHandle samples{};  // "surface-samples": the shadow map's points, or none
  KeyLight light;
};

struct LeafLayers {
  Handle<LeafLayer> layer;  // "leaf-layer"
  Handle<LeafLayer> wood;   // "wood-layer": wood_layer
  Handle<LeafTone> tone;    // "leaf-tone": its darkness ranks the wood's hatching
};

// Adds the passes "leaf-primitives" (a LeafFrame, made while the raster draws), "leaf-tone" (a
// LeafTone), "wood-layer", "leaf-paint" (a LeafPaint: the primitives painted over a copy of the
// wood layer, beside the tone) and "leaf-layer".
LeafLayers add_leaf_layer_pass(RenderGraph& g, const LeafResources& in, const LeafParams& p,
                               const InkLineParams& lines, const EdgeParams& edges);

// Adds the pass "leaf-strokes": the layer's drawing.
Handle<StrokeDrawing> add_leaf_strokes_pass(RenderGraph& g, Handle<LeafLayer> layer);

}  // namespace sylva

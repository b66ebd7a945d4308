// Watercolor (Bousseau et al. 2006 "Interactive watercolor rendering with temporal coherence
// and abstraction"; Luft & Deussen 2006 "Real-time watercolor illustrations of plants using a
// blurred depth test"). The leaf clusters are gathered into masses at the picture's scale
// (watercolor.mass, passes/watercolor_masses.h; gaps up to a twentieth of a mass between its
// leaves are painted over where they show the paper), and every mass becomes one wash (one per
// cluster with watercolor.mass = 0, or without the scene's samples): its id mask is blurred and
// thresholded (soft wet-on-wet or hard wet-on-dry edges), wobbled by the paper's gradient,
// darkened along its rim where pigment pools (on the plant's outer edge and at depth steps
// between washes, watercolor.rim_step), thinned where the foliage thins (its pigment follows the
// leaves' smoothed coverage, watercolor_layers.h kThinCover: a willow's curtain of strands is a
// pale veil), graded with the light inside it, tinted with the cluster's
// mean colour, given leaf detail through a blurred depth test, and glazed over the washes behind
// it, back to front by mean depth. Glazing is subtractive: each wash is an optical density (-log2
// of its linear transmittance) scaled by its coverage, and densities add (transmittances multiply),
// so a thin or half-covered wash keeps its hue instead of greying towards the paper. A cluster's
// wash continues under the clusters in front of it (normalised convolution that ignores the
// occluding pixels), fading out over about two blur radii, and where a nearer wash covers it
// only about a third of its pigment shows (weakened by the nearer wash's own coverage, so the
// two meet without a band of doubled pigment): overlaps read as soft glazes rather than as
// abutting flat regions or outlined patches. The detail layer (passes/watercolor_marks.h,
// watercolor.marks) then glazes leaf-scale touches of each leaf's own shape over the washes,
// denser in shadow and faded by the blurred depth test. Paper grain and world-space turbulence then
// modulate the pigment density with Bousseau's formula, and the result sits on paper. The masks are
// blurred at reduced resolution and each wash is painted over its bounding box only.
//
// Reads (cv::Mat render-graph resources, conventions of core/gl/gbuffer.h):
//   color     CV_8UC4 BGRA sRGB shaded, alpha = coverage (premultiplied over black): the
//             pigment colour (pigment = "shaded") and the leaf detail (luminance variation)
//   albedo    CV_8UC4 BGRA sRGB unlit base colour: the pigment colour when pigment = "albedo"
//             (only then is it read)
//   id        CV_32SC1 cluster ids, 0 = background: one wash per distinct non-zero id
//   depth     CV_32FC1 linear view depth, 0 = background: layer order and the blurred depth
//             test
//   position  CV_32FC3 view-space position: where the turbulence noise and the key light's
//             shadow are evaluated (through view_to_world, so they stick to the plant in a
//             turntable); read only when turbulence_strength > 0 or shadow > 0
// Writes "watercolor": CV_8UC4 BGRA sRGB, opaque (alpha 255), on the paper colour.
//
// Pigment colour: the cluster's mean *shaded* colour by default, because the Luft foliage
// illumination (ka, inner clusters darker) is what gives the painted tree its volume; the
// albedo gives flat local colour with all the shading left to glazing and detail.
//
// Parts: the washes in passes/watercolor_layers.h, the paper and turbulence textures in
// passes/watercolor_textures.h, the colour curves they share in passes/watercolor_common.h;
// watercolor.cpp sorts the clusters, glazes the washes and puts them on paper.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "core/gl/camera.h"
#include "core/graph/render_graph.h"
#include "core/params.h"
#include "npr/leaf_pieces.h"
#include "npr/surface_samples.h"
#include "passes/leaf_primitives.h"

namespace sylva {

// watercolor.pigment (WatercolorParams::pigment).
enum class Pigment { Shaded, Albedo };

struct WatercolorParams {
  // Gaussian sigma applied to each cluster mask before thresholding; shapes become rounder
  // and small gaps between leaves close. px at 1024 px; default 5; [0, 64].
  float blur = 5.0f;
  // Width of the smoothstep threshold of the blurred mask: 0 = hard wet-on-dry edge (about a
  // pixel wide), 1 = soft wet-on-wet edge spanning the whole blur. [0, 1]; default 0.25.
  float edge_softness = 0.25f;
  // Pigment pooling at the wash's rim, from the blurred mask's gradient magnitude: the extra
  // pigment density at the steepest edge (Bousseau's d - 1; 1 = twice the pigment), scaled
  // down on soft edges (by 1 - 0.8 edge_softness: wet-on-wet diffuses rather than pools).
  // [0, 1]; default 0.4.
  float edge_darkening = 0.4f;
  // Where rims darken besides the foliage's outer edge: between two washes whose depths differ
  // by more than this share of the plant's depth extent (a nearer mass over a farther one);
  // 0 = along every border between clusters, 1 = the outer edge only. [0, 1]; default 0.15.
  float rim_step = 0.15f;
  // The size of the masses the crown is painted as (passes/watercolor_masses.h): leaf clusters
  // whose centres lie within half of it of a mass's founding cluster are one wash. px at
  // 1024 px (at the plant's distance, so a turntable keeps its masses); 0 = one wash per leaf
  // cluster. Needs the scene's surface samples (the styles have them). [0, 1024]; default 450.
  float mass = 450.0f;
  // Wet-in-wet gradation: how far a wash's value follows the light inside it (the shaded
  // luminance smoothed at twice the blur), 0 = a flat wash per cluster. [0, 1]; default 0.8.
  float gradation = 0.8f;
  // beta of Bousseau's density modulation by the paper texture (pigment settling in the
  // grain). [0, 1]; default 0.45.
  float paper_strength = 0.45f;
  // beta of Bousseau's density modulation by low-frequency turbulence (uneven pigment flow),
  // 3-D noise in world space. [0, 1]; default 0.5.
  float turbulence_strength = 0.5f;
  // Feature size of the turbulence in scene units: "0.3" (scene units), "5%" (of
  // reference_length) or "auto" (= 6% of reference_length). Default "auto".
  std::string turbulence_size = "auto";
  // Displacement of the mask lookup along the paper texture's gradient (hand-drawn wobble of
  // the wash outline), as the RMS displacement. px at 1024 px; default 1.5; [0, 8].
  float wobble = 1.5f;
  // How much pigment the washes carry: their optical density is scaled by it, so 1 is the full
  // wash and 0.5 a dilute one with twice the transmittance's log (a light wash under ink
  // lines, pen-and-wash). [0.05, 1]; default 1.
  float strength = 1.0f;
  // Leaf detail inside a wash: the share of the shaded colour's luminance variation kept where
  // leaves stand in front of their blurred depth (Luft & Deussen's blurred depth test).
  // [0, 1]; default 0.5.
  float detail = 0.5f;
  // The detail layer (passes/watercolor_marks.h): the pigment of the leaf-scale marks glazed
  // over the washes, 0 = none. Needs the scene's leaf pieces (the styles have them). [0, 1];
  // default 0.6.
  float marks = 0.6f;
  // The smallest mark's diameter. px at 1024 px; default 10; [2, 64].
  float mark_size = 10.0f;
  // The shadow glaze (passes/watercolor_shadow.h): its strength where the key light does not
  // reach through the crown, 0 = none. Needs the scene's samples, the position buffer and a
  // key light. [0, 1]; default 0.5.
  float shadow = 0.5f;
  // Warm light, cool shade: how far the shadow glaze is ultramarine rather than the pigment's
  // own darker value, and the washes' lit sides shift towards warm. [0, 1]; default 0.5.
  float warm_cool = 0.5f;
  // Paper grain size (the generated paper's finest noise period). px at 1024 px; default 3;
  // [1, 16].
  float grain = 3.0f;
  // "generated" (value-noise fBm from the seed, in screen space so it stays put like paper)
  // or the path of a grey-scale paper image (tiled, 1 image px = 1 px at 1024 px; bright =
  // raised grain). A missing or unreadable file is an InputError.
  std::string paper = "generated";
  glm::vec3 paper_color{0.913f, 0.871f, 0.784f};  // linear RGB of "#f5f0e5"
  // watercolor.pigment: shaded (mean of the color buffer) or albedo (mean of the albedo buffer).
  Pigment pigment = Pigment::Shaded;
  // Seed of the generated paper and of the turbulence noise. [0, 2^31 - 1]; default 1.
  int seed = 1;
  // Not a parameter: the reference for a relative turbulence_size, in scene units (the style
  // sets the foliage bounding-box diagonal). 0 = the world-space bounding-box diagonal of the
  // visible points, which is fine for a still but changes slightly as a turntable rotates.
  float reference_length = 0.0f;
};

struct WatercolorImages {
  cv::Mat color;   // CV_8UC4 BGRA sRGB shaded, alpha = coverage
  cv::Mat albedo;  // CV_8UC4 BGRA sRGB; may be empty unless pigment = "albedo"
  cv::Mat id;      // CV_32SC1, 0 background
  cv::Mat depth;   // CV_32FC1 linear view depth, 0 background
  // CV_32FC3 view space; may be empty when the camera is given (the positions are then the
  // depth's pixels unprojected: passes/watercolor_common.h ViewPositions) or when
  // turbulence_strength = shadow = 0.
  cv::Mat position;
  // The scene's surface samples (npr/surface_samples.h) and the frame's camera, or null: the
  // washes' shapes and order then come from the id buffer and its depths.
  std::shared_ptr<const SurfaceSamples> samples;
  Camera camera;  // the frame's (width 0 = unknown)
  // The cluster id of trunk and branches (0 = none): the wood's wash lies under the leaves'
  // washes, as a painter lays the trunk under the crown, and wherever the id buffer shows the
  // wood the leaves' washes leave it bare.
  uint32_t wood_cluster = 0;
  // Scene units per px at the plant's distance (passes/hatching.h units_per_px): the masses'
  // size in the scene. 0 = one wash per cluster.
  double units_per_px = 0.0;
  // The scene's leaf pieces (npr/leaf_pieces.h) for the marks and the leaves' size (a plant of
  // large leaves is painted leaf by leaf: passes/watercolor_masses.h large_leaved), or null (no
  // detail layer), and the key light whose shadow through the crown darkens the marks.
  std::shared_ptr<const LeafPieces> pieces;
  KeyLight light;
  // The colour target's clear (linear RGBA, RasterRequest::background). Transparent black: the
  // colour is premultiplied. With alpha 0 and a colour (a stack's layers share the line
  // layer's clear), supersampled edge pixels carry (1 - alpha) of that colour, which is taken
  // out before the washes take their pigment.
  glm::vec4 clear{0.0f};
};

// Bousseau et al. 2006, pigment density variation: modulation of a colour channel c in [0, 1]
// (1 = no pigment) by density d (1 = unchanged, > 1 denser/darker): c(1 - (1 - c)(d - 1)).
// 0 and 1 are fixed points; the result is clamped to [0, 1].
inline float pigment_density(float c, float d) {
  const float v = c * (1.0f - (1.0f - c) * (d - 1.0f));
  return v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
}
// d for a texture value t in [0, 1] and strength beta: 1 + beta (t - 0.5).
inline float texture_density(float t, float beta) {
  return 1.0f + beta * (t - 0.5f);
}

// Throws InputError naming watercolor.paper / watercolor.pigment when the paper file is
// unreadable or the albedo is missing for pigment = "albedo". SYLVA_CHECKs image types.
cv::Mat watercolor(const WatercolorImages& in, const glm::mat4& view_to_world,
                   const WatercolorParams& p);

// Paper relief in [0, 1] (mean about 0.5) at `size`, generated or loaded as p.paper says.
cv::Mat watercolor_paper(const cv::Size& size, const WatercolorParams& p);

// The turbulence texture in [0, 1] (CV_32FC1) at every covered pixel (depth > 0, or position
// non-zero when depth is empty), evaluated at the world position view_to_world * position;
// background 0.5.
cv::Mat watercolor_turbulence(const cv::Mat& position, const cv::Mat& depth,
                              const glm::mat4& view_to_world, const WatercolorParams& p);

void bind_watercolor_params(ParamSet& set, WatercolorParams& p);

struct WatercolorResources {
  ImageHandle color{}, albedo{}, id{}, depth{}, position{};
  SamplesHandle samples{};    // "surface-samples", or none
  Camera camera;              // the frame's (width 0 = none: positions from `position`)
  uint32_t wood_cluster = 0;  // WatercolorImages::wood_cluster
  double units_per_px = 0.0;  // WatercolorImages::units_per_px
  LeafPiecesHandle pieces{};  // "leaf-pieces", or none (no marks, no large_leaved)
  KeyLight light;             // WatercolorImages::light
  glm::vec4 clear{0.0f};      // WatercolorImages::clear
};

// Adds the pass "watercolor" and returns its output resource "watercolor". albedo is read only
// for pigment = "albedo" (InputError at run time if it is -1 then), position only when
// turbulence_strength > 0 or shadow > 0 and the camera is not given (width 0). The parameters
// are copied.
ImageHandle add_watercolor_pass(RenderGraph& graph, const WatercolorResources& res,
                                const glm::mat4& view_to_world, const WatercolorParams& p);

}  // namespace sylva

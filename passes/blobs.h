// Blob painting (Dudley 2005 "Non-photorealistic rendering of generated trees", ch. 4): every
// leaf cluster becomes a screen-aligned billboard clipped to its shrink-wrapped outline
// (npr/blob_outlines.h, a closed cubic B-spline through the control points). Inside it a
// height field with Gaussian peaks at the regional centres (npr/blob_shape.h) is shaded twice:
// with the scene lights in the cluster's mean albedo (the colour wash), and with the blend
// light, whose brightness is the alpha mask: Final = wash x alpha + detail x (1 - alpha)
// (§4.2), where detail is the cluster's own leaves as the raster pass drew them (smoothed over
// 2 px at 1024 px, so needles landing on pixel centres or missing them as a turntable turns do
// not flicker; where they cover part of a pixel the wash fills the rest), optionally with
// their silhouettes in silhouette_tone x the unlit blob colour (§4.2.2). An outline in
// edge_tone x the lit wash runs around each blob, wider where the edge lies to the pixel's
// left (§4.2.2, for depth). Painter's algorithm (§4.3): trunk and branches from the raster
// pass first, then the blobs from the farthest nearest-leaf depth to the nearest.
//
// Reads (render graph):
//   outlines  BlobSet (add_blob_outlines_pass, or interpolated keyframes: npr/blob_keyframes.h)
//   color     CV_8UC4 BGRA sRGB shaded scene: the detail and the branches; alpha = coverage,
//             the rest of a pixel being the background colour (the style clears alpha to 0)
//   albedo    CV_8UC4 BGRA sRGB unlit colour: the wash colour (cluster mean)
//   id        CV_32SC1 cluster ids: which pixels are a blob's own leaves and which are branches
//   position  CV_32FC3 view-space position, only when a point light (scene or blend) needs
//             the blob's position (-1 otherwise)
//   lines     CV_32FC1 leaf silhouette coverage (passes/edges.h), or -1 for none
// Writes "blobs": CV_8UC4 BGRA sRGB over the background colour (alpha = background alpha
// outside the plant).
#pragma once

#include <glm/glm.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/gl/camera.h"
#include "core/gl/lights.h"
#include "core/graph/render_graph.h"
#include "core/params.h"
#include "npr/blob_outlines.h"
#include "npr/surface_samples.h"

namespace sylva {

// blobs.outlines (BlobParams::outlines).
enum class BlobOutlineSource { Scene, Visible, Alone };
// blobs.blend_light (BlobParams::blend_light).
enum class BlendLight { Directional, Point };

struct BlobParams {
  // blobs.control_points, blobs.step: the shrink-wrap (npr/shrink_wrap.h). [3, 512], default
  // 20; (0, 1], default 0.2.
  int control_points = 20;
  float step = 0.2f;
  // blobs.gap: gaps between a cluster's leaves up to this wide are closed before the
  // shrink-wrap (npr/blob_outlines.h close_gaps), so outlines wrap the cluster's hull instead
  // of reaching in between its leaves. px at 1024 px; 0 = Dudley's plain leaf mask.
  // [0, 128]; default 24.
  float gap = 24.0f;
  // blobs.outlines: "scene" shrink-wraps each cluster's part of the crown projected from the
  // scene's surface samples, the parts painted back to front by their mean depth
  // (passes/crown_coverage.h), so blobs hold still in a turntable (issue "Temporal
  // coherence"; without surface samples, "visible"); "visible" shrink-wraps each cluster's
  // visible leaves from the frame's one cluster-id raster pass; "alone" rasterises each
  // cluster on its own (hidden leaves included, Dudley §4.2.1) for its outline and nearest
  // depth: one more pass per cluster (styles/blob_raster.h).
  BlobOutlineSource outlines = BlobOutlineSource::Scene;
  // blobs.peaks: Gaussian peaks of the height field (Dudley uses 3). [1, 16]; default 3.
  int peaks = 3;
  // blobs.peak_height: peak height as a fraction of the blob's width: 0 flat, 1 as high as
  // wide. [0, 2]; default 0.5.
  float peak_height = 0.5f;
  // blobs.blend_light: "directional" (toward right, up, 1 in view space) or "point" (at
  // right x d, up x d beside the eye, d = the blob's depth), Dudley §6.3.
  BlendLight blend_light = BlendLight::Directional;
  // blobs.blend_right, blobs.blend_up: the blend light's place relative to the view, as
  // fractions of the viewing distance along the camera's right and up vectors. [-10, 10];
  // default 1 and 1 (Dudley §7: right 1, up 1).
  float blend_right = 1.0f;
  float blend_up = 1.0f;
  // blobs.blend_ambient, blobs.blend_diffuse: the blend light's ambient and diffuse strength;
  // alpha = clamp(ambient + diffuse N.L, 0, 1), so darker parts of the blend-lit shape show
  // leaf detail. [0, 1] default 0 and [0, 2] default 0.7 (Dudley §7: 0 % ambient, 70 %
  // diffuse).
  float blend_ambient = 0.0f;
  float blend_diffuse = 0.7f;
  // blobs.silhouettes: leaf silhouettes in the detail, from the edges.* settings (edges.color
  // is not used). Default true.
  bool silhouettes = true;
  // blobs.silhouette_tone: silhouette colour = tone x the blob's unlit colour (0 black, 1 the
  // blob colour, >= 1 towards white; the result is clamped). [0, 10]; default 0.5.
  float silhouette_tone = 0.5f;
  // blobs.edge_width: outline width inside the blob, px at 1024 px; 0 = none. [0, 32];
  // default 2.
  float edge_width = 2.0f;
  // blobs.edge_left: extra width where the outline lies to the left of the pixel (the edge's
  // outward normal points left): width x (1 + edge_left) there, blended by direction. [0, 4];
  // default 1.
  float edge_left = 1.0f;
  // blobs.edge_tone: outline colour = tone x the lit wash under it. [0, 10]; default 0.45.
  float edge_tone = 0.45f;
  // blobs.translucency: how much of what lies behind shows through a blob. [0, 1]; default 0.
  float translucency = 0.0f;
  // blobs.variation: per-blob brightness variation, the wash x (1 +- variation), from the
  // seed and the cluster id (so a blob keeps its tone through an animation). [0, 0.5];
  // default 0.08.
  float variation = 0.08f;
  // blobs.seed: seed of the per-blob variation. [0, 2147483647]; default 1.
  int seed = 1;
};

// Binds blobs.* with ranges, units and docs. `set` refers into `p`.
void bind_blob_params(ParamSet& set, BlobParams& p);
// Throws InputError("blobs.<key>", ...) for values outside the ranges above.
void validate_blob_params(const BlobParams& p);

struct BlobImages {
  cv::Mat color, albedo, id;  // required
  cv::Mat position;           // required when blob_needs_position
  cv::Mat lines;              // optional leaf silhouettes
};

struct BlobFrame {
  Lighting lighting;
  glm::mat4 view{1.0f};              // world -> view (scene-fixed lights)
  glm::vec4 background{1, 1, 1, 1};  // linear RGBA
  uint32_t branch_cluster = 0;       // cluster id of trunk and branches; 0 = none
};

// Whether the pass must read the position buffer (a point light among the scene lights, or
// a point blend light).
bool blob_needs_position(const Lighting& lighting, const BlobParams& p);

// The painting of `blobs` over the branches and the background, in the set's painter's order
// (cross-faded to next_order by fade), each blob's coverage scaled by its opacity.
// Deterministic.
cv::Mat paint_blobs(const BlobImages& in, const BlobSet& blobs, const BlobFrame& frame,
                    const BlobParams& p);

struct BlobResources {
  ImageHandle color{}, albedo{}, id{}, depth{}, position{}, lines{};
};

// The ShrinkWrapParams of p, and blobs.gap as the closing radius in px for an image of `size`.
ShrinkWrapParams blob_shrink_wrap(const BlobParams& p);
float blob_gap_radius(const BlobParams& p, const cv::Size& size);

// The blobs of blobs.outlines = "scene" seen by `camera` (its size is the image's): each
// cluster's part of the crown (passes/crown_coverage.h, the wood left out), closed by
// blobs.gap and shrink-wrapped, ordered by the parts' mean depths.
std::vector<BlobOutline> scene_blob_outlines(const SurfaceSamples& samples, const Camera& camera,
                                             uint32_t branch_cluster, const BlobParams& p);

// Adds "blob-outlines" (reads id and depth, or with `samples` >= 0 the "surface-samples" seen
// by `camera`; writes the frame's BlobSet) and returns it.
Handle<BlobSet> add_blob_outlines_pass(RenderGraph& graph, ImageHandle id, ImageHandle depth,
                                       uint32_t branch_cluster, const BlobParams& p,
                                       SamplesHandle samples = {}, const Camera& camera = {});
// Adds "blobs" (reads `outlines` and the images above) and returns "blobs".
ImageHandle add_blobs_pass(RenderGraph& graph, Handle<BlobSet> outlines, const BlobResources& r,
                           const BlobFrame& frame, const BlobParams& p);

}  // namespace sylva

// Tone drawn with strokes (issue "Ink for illustrators", the `pen` preset): hatching or
// stippling whose density follows the tone of the shaded colour target, which for the pen
// style is Luft et al.'s Eq. 1 with the realigned normals and the density ka (Fig. 7), so the
// inner, shadowed crown is dense and the lit rim bare, and wood by its own shading and bark.
//
// Tone: darkness = 1 - the Rec. 709 luma of the colour (sRGB), averaged over the plant with a
// Gaussian of sigma = ink.detail so the tone follows crown parts, not the leaves whose shading
// changes as they turn; tone t = clamp((darkness - lo) / (hi - lo), 0, 1)^pen.gamma with lo
// and hi the darkness at the plant's pen.lightest and pen.darkest quantiles, so every plant
// gets the same range of tone (a dark conifer and a light aspen alike), its own shadows dense
// and its lit parts bare.
// Anchors are fixed to the scene, not the screen, so a turntable does not shower-door: space
// is cut into cubes of pen.spacing / 2 px (at the plant's distance), each with a seeded point
// and two seeded ranks. The cubes the plant's surface passes through (from the scene's surface
// samples, npr/surface_samples.h; without them, from the visible pixels' surface points) whose
// point projects inside the strokes' region and is in sight anchor a stroke at the point's
// projection, which moves exactly with the scene. In sight (issue "Temporal coherence"): with
// surface samples, not more than 8 cubes behind the crown's mean depth there (the samples'
// depth smoothed over the detail), a test that moves with the scene; without, not more than
// 16 cubes behind the nearest surface the raster shows within a pixel. A cube's region is the
// leaf cluster most of its points belong to. Each anchor decides alone (no stroke's coming or
// going moves another): it gets a stroke when its rank is below t / c, c being the anchors per
// pen.spacing-sized cell around it (averaged over 9 x 9 cells), so the density is t strokes
// per cell whatever the depth complexity; a second layer crossing at 90 degrees, with the
// other rank, where the tone passes pen.cross. A hatching stroke is a straight line of about
// pen.length px through the anchor at its region's angle (pen.angle plus a seeded offset of
// up to pen.angle_jitter per leaf cluster), clipped to the strokes' region: the plant and its
// crown at ink.detail (with surface samples, the ink outline's crown, passes/ink_abstraction.h
// crown_field; else the raster's crown_shape); a stipple is a dot of pen.width. Strokes are at
// least 1 px wide and, in small renders, spaced at least 4 widths apart (spacing and length
// grow together), so the tone never fills in.
//
// Reads (render graph): "position" (CV_32FC3 view space), "id" (CV_32SC1 cluster ids),
// "color" (CV_8UC4 sRGB, alpha = coverage) and, when given, "surface-samples". Writes
// "tone-strokes", a StrokeDrawing of LineClass::Tone strokes.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "core/gl/camera.h"
#include "core/graph/render_graph.h"
#include "core/params.h"
#include "core/strokes.h"
#include "npr/surface_samples.h"

namespace sylva {

// pen.tone (PenParams::tone).
enum class PenTone { None, Hatching, Stipple };

struct PenParams {
  // pen.tone: none | hatching | stipple. Default none (the `pen` preset: hatching).
  PenTone tone = PenTone::None;
  // pen.spacing: px at 1024 px between neighbouring strokes at full darkness. [2, 64]; 7.
  float spacing = 7.0f;
  // pen.length: px at 1024 px of a hatching stroke. [1, 128]; 16.
  float length = 16.0f;
  // pen.width: px at 1024 px of a hatching stroke, or a stipple dot's diameter (no thinner
  // than 1 px). [0.25, 8]; 1.
  float width = 1.0f;
  // pen.angle: degrees, counter-clockwise from the image's x axis, of the hatching. [-180,
  // 180]; 60.
  float angle = 60.0f;
  // pen.angle_jitter: degrees by which each crown region's angle differs at most. [0, 90]; 25.
  float angle_jitter = 25.0f;
  // pen.lightest: the lightest share of the plant (by smoothed darkness) left bare. [0,
  // 0.99]; 0.4.
  float lightest = 0.4f;
  // pen.darkest: the quantile of darkness from which the tone is full. (pen.lightest, 1];
  // 0.95.
  float darkest = 0.95f;
  // pen.cross: tone t from which hatching crosses (a second stroke at +90 degrees); 1 = only
  // the very darkest. (0, 1]; 0.6.
  float cross = 0.6f;
  // pen.gamma: exponent from darkness to tone (> 1: fewer strokes in the mid-tones). [0.1,
  // 10]; 1.
  float gamma = 1.0f;
  // pen.opacity: ink opacity of the tone strokes. [0, 1]; 1.
  float opacity = 1.0f;
  // pen.seed: the anchors' and angles' random seed. [0, 2147483647]; 1.
  int seed = 1;
  bool enabled() const { return tone != PenTone::None; }
};

// Binds pen.* with ranges, units and docs. `set` refers into `p`.
void bind_pen_params(ParamSet& set, PenParams& p);
// InputError("pen.darkest", ...) unless pen.darkest > pen.lightest.
void validate_pen_params(const PenParams& p);

struct ToneImages {
  cv::Mat position;  // CV_32FC3 view space
  cv::Mat id;        // CV_32SC1 cluster ids, or empty (one region)
  cv::Mat color;     // CV_8UC4, alpha = coverage
  // The scene's surface samples (npr/surface_samples.h), or null: the anchors' cubes are then
  // those the visible pixels' surface points fall in.
  std::shared_ptr<const SurfaceSamples> samples;
};

// The frame's view: world -> view, the projection, and the scene units per px at the plant's
// distance (the anchor cubes' scale; constant along a turntable).
struct ToneView {
  glm::mat4 view{1.0f};
  glm::mat4 proj{1.0f};  // view -> clip (the camera's projection)
  bool ortho = false;    // the projection is orthographic
  double units_per_px = 0.0;
};

// units_per_px of a camera at the centre of `sphere` (the framing sphere).
double units_per_px(const Camera& camera, const Sphere& sphere);

// detail: ink.detail (px at 1024 px; the tone's smoothing and the crown the strokes keep to).
StrokeDrawing tone_strokes(const ToneImages& in, const ToneView& view, const PenParams& p,
                           double detail);

struct ToneResources {
  ImageHandle position{}, id{}, color{};
  SamplesHandle samples{};  // "surface-samples", or none
};

// Adds the pass "tone-strokes" and returns its output (StrokeDrawing).
Handle<StrokeDrawing> add_tone_pass(RenderGraph& g, const ToneResources& in, const ToneView& view,
                                    const PenParams& p, double detail);

}  // namespace sylva

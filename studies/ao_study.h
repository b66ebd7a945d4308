// The speed/accuracy trade of the ambient-occlusion models (DESIGN.md §5), measured by the
// program itself: one view of a scene is rendered with each AO model (npr/ao_pass.h: none,
// constant, luft-density, Hegeman et al.'s sphere, ellipsoid and k shells, and ray-traced AO
// with a few ray counts), and each model's AO buffer is compared per pixel with ray-traced
// visibility with many rays (Hegeman et al. §4 judge their model the same way), separately on
// foliage pixels and on the rest (wood, ground), together with the time the model adds to a
// frame. Written as CSV and as a chart (error against frame time).
#pragma once

#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/gl/camera.h"
#include "core/gl/lights.h"
#include "core/gl/rasterizer.h"
#include "core/scene/scene.h"
#include "npr/foliage_illumination.h"

namespace sylva {

struct AoStudyOptions {
  // The view: size, projection and lights of every frame; request's ssaa, background and
  // ambient are used, its targets and ao are the study's own.
  Camera camera;
  Lighting lighting;
  RasterRequest request;
  // The models measured besides the two always measured: none (the time baseline) and the
  // reference (raytraced with reference_rays). Each at most once; names as ao.model.
  std::vector<std::string> models = {"none",           "constant",          "luft-density",
                                     "hegeman-sphere", "hegeman-ellipsoid", "hegeman-shells",
                                     "raytraced"};
  std::vector<int> shells = {1, 2, 4, 8};  // hegeman-shells: k per row, each in [1, 64]
  std::vector<int> rays = {4, 16, 64};     // raytraced: rays per pixel per row, [1, 4096]
  int reference_rays = 256;                // the reference's rays per pixel, [1, 4096]
  // Timed frames per row (after one untimed warm-up frame whose AO buffer is compared); the
  // row's frame time is their median. [1, 100]
  int repeats = 3;
  // hegeman-*: ao.alpha_rho, "auto" (fitted to the ray tracer, npr/ao_pass.h) or a number
  // >= 0 per scene unit cubed.
  std::string alpha_rho = "auto";
  // luft-density: the Luft preprocessing whose ka is the AO (computed once, not cached).
  FoliageParams luft;
  // Seeds the shells' k-means, the alpha_rho fit and every ray-traced frame (the reference
  // and the rows use the same seed).
  uint64_t seed = 1;
  // Called after each row is measured (the reference first) with a short description, for
  // progress reports. May be empty.
  std::function<void(const std::string&)> on_run;
  // The GL context to render in (it must outlive the run); null: one of the environment's
  // choice (SYLVA_GL, core/gl/gl_context.h).
  GlContext* context = nullptr;
};

// Throws InputError (where: models, shells, rays, reference-rays, repeats, ao.alpha_rho)
// naming what is allowed; also validate_foliage_params(luft) when luft-density is measured.
void validate_ao_study(const AoStudyOptions& options);

// Rows a study measures: the reference, none, one per listed model except hegeman-shells
// (one per k) and raytraced (one per ray count other than reference_rays).
size_t ao_study_runs(const AoStudyOptions& options);

// The Gaussian's standard deviation for AoPixelError::trend_rmse, as a fraction of the
// frame's shorter side (10 pixels at 512²: a few leaves of a tree filling the frame).
constexpr double kAoTrendSigma = 0.02;

// The AO buffer against the reference over one class of pixels.
struct AoPixelError {
  size_t pixels = 0;  // covered pixels of the class the reference traced
  // Empty when there are no such pixels (or the row failed).
  std::optional<double> mean;  // mean AO of this model there
  std::optional<double> rmse;  // sqrt(mean (ao - reference)^2)
  std::optional<double> mae;   // mean |ao - reference|
  // The same at the crown's scale rather than the leaves': RMSE between the two buffers each
  // averaged over the class's pixels within a Gaussian of kAoTrendSigma x the frame's shorter
  // side (Hegeman et al. §3 claim their model keeps "the overall appearance trends", not
  // leaf-scale detail; this measures that claim).
  std::optional<double> trend_rmse;
};

struct AoStudyRow {
  std::string model;                // as ao.model
  std::optional<int> shells;        // hegeman-shells: k asked for
  std::optional<int> rays;          // raytraced: rays per pixel
  bool reference = false;           // raytraced with the reference's rays: zero error by definition
  std::optional<double> constant;   // constant: the visibility used (the reference's mean)
  std::optional<double> alpha_rho;  // hegeman-*: the one used (fitted for auto)
  // Once per scene (a turntable pays it once): fitting the shells and alpha_rho (hegeman-*),
  // the Luft preprocessing and uploading its ka (luft-density); 0 for the others. Seconds.
  std::optional<double> setup_seconds;
  // Median wall time of `repeats` frames: executing a render graph that presents the colour
  // (Luft Eq. 1, ambient darkened by the AO) and, except for none, the AO buffer; raytraced
  // frames also rasterise position and normal and trace (building the scene's BVH each
  // frame, as a render does). Seconds.
  std::optional<double> frame_seconds;
  // frame_seconds minus none's: what the model adds to a frame (may be slightly negative for
  // models that add almost nothing: timing noise).
  std::optional<double> added_seconds;
  AoPixelError foliage, nonfoliage;
  std::string error;  // why the row failed (e.g. a model that needs foliage), else empty
};

struct AoStudy {
  int width = 0, height = 0;  // frame size, pixels
  int repeats = 0;
  int reference_rays = 0;
  double reference_mean = 0;  // over every evaluated pixel: the constant model's value
  // Nested in the order: reference, then none, constant, luft-density, hegeman-sphere,
  // hegeman-ellipsoid, hegeman-shells (per k), raytraced (per ray count), keeping only
  // the models asked for.
  std::vector<AoStudyRow> rows;
};

// Renders in its own GL context. Pixels are those the reference traced (covered, with a
// normal); foliage pixels are those whose primitive is a foliage triangle (Role::Foliage),
// every other covered pixel is non-foliage. Throws InputError when the options are out of
// range or the view covers no pixel; a model that fails on this scene (hegeman-* or
// luft-density without foliage) is recorded in its row instead. Deterministic apart from
// the times.
AoStudy run_ao_study(const Scene& scene, const AoStudyOptions& options);

// The CSV text, one row per AoStudyRow, header:
// model,shells,rays,reference,constant,alpha_rho,setup_seconds,frame_seconds,added_seconds,
// foliage_pixels,foliage_mean,foliage_rmse,foliage_mae,foliage_trend_rmse,nonfoliage_pixels,
// nonfoliage_mean,nonfoliage_rmse,nonfoliage_mae,nonfoliage_trend_rmse,error
// A field that does not apply to the row, or a class without pixels, is empty (never NaN);
// failed rows keep their identity columns and a quoted error.
std::string ao_study_csv(const AoStudy& study);

// The chart: x = frame time (s, log scale); left panel y = RMSE on foliage pixels, right
// panel on non-foliage pixels; one colour and marker per model, lines through the shell
// counts and through the ray counts (points labelled k / rays), the reference ringed; title
// with `scene_name`, the size and the reference. 8-bit BGR, white background; width in [600,
// 4000], height in [400, 4000].
cv::Mat plot_ao_study(const AoStudy& study, const std::string& scene_name, int width = 1200,
                      int height = 800);

}  // namespace sylva

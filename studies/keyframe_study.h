// The speed/coherence trade of keyframed blob turntables (DESIGN.md §5; Dudley 2005 §5.1),
// measured by the program itself: one blobs turntable is rendered in-process once per
// keyframe interval n (styles/turntable_frames.h, as `sylva turntable --keyframe-every n`),
// and each run is compared with n = 1 (fresh blobs every frame, the reference): time,
// keyframes shrink-wrapped, flicker and blob outline jitter between consecutive frames
// (styles/turntable.h), and the frames' difference from the reference's frames. Written as
// CSV and as a chart (flicker and time against n).
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "styles/sheet.h"
#include "styles/style.h"
#include "styles/turntable.h"

namespace sylva {

struct KeyframeStudyOptions {
  TurntablePath path;  // frames, degrees, axis, zoom (validate_turntable)
  // Keyframe intervals measured, each in [1, 100000], each at most once; n = 1 (the
  // reference) is measured even when not listed.
  std::vector<int> every = {1, 2, 5, 10, 20};
  // Called after each frame is rendered with a short description, for progress reports
  // (keyframe_study_frames() calls in all). May be empty.
  std::function<void(const std::string&)> on_frame;
};

// Throws InputError("--every", ...) or validate_turntable's errors; InputError("--style",
// ...) unless the style's builder is "blobs".
void validate_keyframe_study(const KeyframeStudyOptions& options, const Style& style);

// The intervals run, in increasing order: 1 and the listed ones.
std::vector<int> keyframe_study_intervals(const KeyframeStudyOptions& options);
// Frames rendered in all (excluding one untimed warm-up frame).
size_t keyframe_study_frames(const KeyframeStudyOptions& options);

struct KeyframeStudyRow {
  int every = 1;
  bool reference = false;  // n = 1
  // Wall time of rendering every frame (keyframes, interpolation, render graph; no file is
  // written), after an untimed warm-up frame that also runs the Luft preprocessing once for
  // all runs. Seconds.
  double seconds = 0;
  double seconds_per_frame = 0;
  // Blob outlines shrink-wrapped: one per frame for n = 1 (the style's own per-frame blobs),
  // the keyframes for n > 1 (0, n, 2n, ... up to the first at or past the last frame).
  int keyframes = 0;
  // Flicker (frame_flicker: mean |change| of B, G, R in 8-bit levels inside the plant mask)
  // over the frames-1 pairs of consecutive frames; empty with a single frame.
  std::optional<double> flicker_mean, flicker_max;
  // blob_jitter (px) averaged over the same pairs; empty with a single frame.
  std::optional<double> jitter_mean;
  // Against the reference's frame i: frame_flicker(reference_i, frame_i) averaged over the
  // frames (mean) and the worst frame (max); 0 for the reference. 8-bit levels.
  double error_mean = 0, error_max = 0;
};

struct KeyframeStudy {
  int width = 0, height = 0;  // frame size, pixels
  TurntablePath path;
  std::string style;                   // the style's name
  std::vector<KeyframeStudyRow> rows;  // in keyframe_study_intervals() order
};

// Renders with scene.raster's rasteriser (its camera is frame 0's; scene_sphere.centre the
// centre of the turn). scene.foliage is memoised for all runs. Deterministic apart from the
// times. Keeps the reference's frames in memory (frames x width x height x 4 bytes).
KeyframeStudy run_keyframe_study(const SheetScene& scene, const Style& style,
                                 const KeyframeStudyOptions& options);

// The CSV text, one row per KeyframeStudyRow, header:
// every,reference,frames,seconds,seconds_per_frame,keyframes,flicker_mean,flicker_max,
// jitter_mean,error_mean,error_max
// A field without a value (a single frame) is empty (never NaN).
std::string keyframe_study_csv(const KeyframeStudy& study);

// The chart: x = n (log scale); left panel y = flicker (mean and max) and the error against
// n = 1, right panel y = seconds per frame; the reference ringed; title with `scene_name`,
// the size, frames and degrees. 8-bit BGR, white background; width in [600, 4000], height
// in [400, 4000].
cv::Mat plot_keyframe_study(const KeyframeStudy& study, const std::string& scene_name,
                            int width = 1200, int height = 800);

}  // namespace sylva

// The coherence study behind `sylva tradeoff --study coherence` (issue "Temporal coherence";
// DESIGN.md §5): for each style, a short turntable of views `step` degrees apart is rendered
// in-process (styles/turntable_frames.h) and each consecutive pair is measured with the motion
// taken out (styles/reprojection.h): the mean and worst reprojection_error and line_pop over
// the pairs, against the time per frame; also the plain flicker (styles/turntable.h) for
// comparison. Written as CSV and as a chart (error against time, one point per style).
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

struct CoherenceStudyOptions {
  int frames = 12;    // views per style, [2, 100000]
  float step = 1.0f;  // degrees between consecutive views, [-360, 360], not 0
  char axis = 'y';    // world axis of the turn
  float zoom = 1.0f;  // (0, 100]
  // Called after each frame with a short description (progress). May be empty.
  std::function<void(const std::string&)> on_frame;
};

// Throws InputError("--frames" / "--step" / "--axis" / "--zoom", ...).
void validate_coherence_study(const CoherenceStudyOptions& options);

struct CoherenceStudyRow {
  std::string style;
  double seconds_per_frame = 0;  // render only (no file), after an untimed warm-up frame
  double reprojection_mean = 0, reprojection_max = 0;  // 8-bit levels
  std::optional<double> line_pop_mean, line_pop_max;   // shares; styles with lines only
  double flicker_mean = 0;  // frame_flicker, 8-bit levels (the motion left in)
};

struct CoherenceStudy {
  int width = 0, height = 0;
  CoherenceStudyOptions options;
  std::vector<CoherenceStudyRow> rows;  // one per style, in the order given
};

// `scene` is frame 0's (as for TurntableRenderer); styles outlive the call.
CoherenceStudy run_coherence_study(const SheetScene& scene, const std::vector<const Style*>& styles,
                                   const CoherenceStudyOptions& options);

std::string coherence_study_csv(const CoherenceStudy& study);

// Two panels against seconds per frame (log scale): reprojection error, line pop (%).
cv::Mat plot_coherence_study(const CoherenceStudy& study, const std::string& scene_name,
                             int width = 1200, int height = 800);

}  // namespace sylva

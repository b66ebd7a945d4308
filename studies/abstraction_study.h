// The abstraction study behind `sylva tradeoff --study abstraction` (issue "Pen-and-ink that
// depicts the tree"): the line styles' one abstraction knob, ink.detail, swept over a list of
// values; for each style and value, the depiction measures of its first view against the
// `standard` and `expressive` renders of the same view (studies/depiction_measures.h: wood, tone,
// inside, marks, overreach), the line pop between views `step` degrees apart and the time per
// frame (studies/coherence_study.h). Written as CSV and as a chart (measures and line pop
// against the detail).
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "studies/coherence_study.h"
#include "studies/depiction_measures.h"

namespace sylva {

// One style at one value of ink.detail (the style built with it).
struct AbstractionCell {
  const Style* style = nullptr;
  std::string name;  // the style's name as given
  float detail = 0;  // px at 1024 px
};

struct AbstractionStudyRow {
  std::string style;
  float detail = 0;
  DepictionMeasures depiction;
  double seconds_per_frame = 0;
  std::optional<double> line_pop_mean, line_pop_max;
};

struct AbstractionStudy {
  int width = 0, height = 0;
  CoherenceStudyOptions options;  // the views measured for line pop
  std::vector<AbstractionStudyRow> rows;
};

// `standard` and `expressive`: the styles the depiction measures compare against. Throws what
// validate_coherence_study throws.
AbstractionStudy run_abstraction_study(const SheetScene& scene,
                                       const std::vector<AbstractionCell>& cells,
                                       const Style& standard, const Style& expressive,
                                       const CoherenceStudyOptions& options);

std::string abstraction_study_csv(const AbstractionStudy& study);

// Two panels against ink.detail (log scale): wood, tone and inside per style; line pop (%).
cv::Mat plot_abstraction_study(const AbstractionStudy& study, const std::string& scene_name,
                               int width = 1200, int height = 800);

}  // namespace sylva

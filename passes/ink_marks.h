// Marking the ink lines of each class (passes/ink_lines.h) as cracks between 4-neighbouring
// pixels (passes/crack_chains.h), before they are chained into strokes.
//
// Reads InkLineImages (passes/ink_lines.h); writes one Cracks per line class (Tone stays
// empty) and the plant's coverage. Rows are marked in parallel; every crack depends only on
// the inputs, so the result does not depend on the number of threads.
#pragma once

#include <array>
#include <opencv2/core.hpp>

#include "passes/crack_chains.h"
#include "passes/ink_lines.h"

namespace sylva {

struct InkMarks {
  std::array<Cracks, kLineClassCount> of;  // indexed by LineClass
  cv::Mat plant;                           // CV_8UC1, 255 = covered (alpha >= 0.5)
  // CV_8UC1, 255 = thin parts of the plant drawn as centre lines (CrownShape::thin of
  // passes/ink_abstraction.h); all 0 at ink.detail < 2 px.
  cv::Mat thin;
  // The silhouette, interior, wood and thin marks are found at a working resolution (the
  // detail 5 px across): output px per working px (>= 1); the detail marks are at the output's.
  double crown_scale = 1.0;
  float near = 0, far = 0;  // the plant's depth range
  // The crown field the silhouette is traced on (CrownField::field at the working resolution),
  // for snapping the outline between pixels; empty at ink.detail < 2 px.
  cv::Mat field;
  // The front crown part's view depth at the working resolution (CrownParts::depth, 0 = none),
  // for drawing each interior line on its nearer side; empty without surface samples.
  cv::Mat part_depth;
  // In a scene of many plants, each plant's outline where its crown stands in front of
  // another's, inside the crown (silhouette lines, not snapped to the field); at the working
  // resolution; empty Cracks otherwise.
  Cracks plants;
  cv::Mat plant_depth;  // the front plant's mean view depth there (0 = none), as part_depth
};

// `scale`: reference_scale of the frame (detail and widths are in px at 1024 px).
InkMarks mark_ink_lines(const InkLineImages& in, const EdgeParams& edges, const InkLineParams& p,
                        uint32_t branch_cluster, double scale);

}  // namespace sylva

// Crease marks of the edges pass (passes/edges.h, EdgeParams::crease): Saito & Takahashi's
// second-order depth differences along rows and along columns, with non-maximum suppression
// along the line, so each crease is marked once, on a pixel centre or half-way between two
// pixels (where its second difference peaks).
//
// Reads depth (CV_32FC1 linear view depth, background 0) and the covered pixels (CV_8UC1,
// non-zero = covered). Writes (ORs 255 into) marks.at, marks.between_x and marks.between_y,
// which must be allocated at the EdgeMarks sizes. Rows and columns are processed in parallel;
// each writes only its own line, so the result does not depend on the number of threads.
#pragma once

#include <opencv2/core.hpp>

#include "passes/edges.h"

namespace sylva {

// threshold: on min(|second difference of z| / z, |second difference of 1/z| * z) at the
// image's own resolution (the caller converts EdgeParams::crease_threshold), > 0.
void mark_creases(const cv::Mat& depth, const cv::Mat& foreground, double threshold,
                  EdgeMarks& marks);

}  // namespace sylva

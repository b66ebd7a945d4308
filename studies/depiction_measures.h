// Does a stylised picture depict the tree? The measures of ../shared/tools/depiction.py (wave 3;
// its header is the reference), computed in process against the `standard` and `expressive`
// renders of the same view, for the abstraction study (studies/abstraction_study.h):
//   wood      share of the visible trunk and branch outline (brown wood at least 3 px wide at
//             1024 px in the standard render) within 3 px of ink (lines) or painted in a wood
//             colour (paint); 1 where the plant shows no brown wood
//   tone      Spearman correlation of the picture's darkness and the expressive render's, both
//             averaged over the plant only (a Gaussian of 1.5 % of the image), away from the
//             silhouette; tone_range the expressive darkness's interquartile range there
//   inside    ink share of the crown's interior (the plant closed at 1 %, eroded by 3 %)
//   overreach area the picture claims beyond the plant grown by 1 %, as a share of the plant
//   marks     connected ink marks in the interior per 100 x 100 px at 1024 px
//   rims      share of the interior that is a thin dark rim (8 levels darker than its 4 px blur)
// Floors, not goals: a picture can pass them and still be wrong.
//
// Reads three CV_8UC4 (or CV_8UC3) BGR(A) images of one size; writes numbers.
#pragma once

#include <opencv2/core.hpp>

namespace sylva {

struct DepictionMeasures {
  double wood = 1, tone = 0, tone_range = 0, inside = 0, overreach = 0, marks = 0, rims = 0;
};

// line_style: measured as a line drawing (marks are dark pixels) rather than paint.
DepictionMeasures measure_depiction(const cv::Mat& standard, const cv::Mat& expressive,
                                    const cv::Mat& picture, bool line_style);

}  // namespace sylva

// Edge marking (passes/edges.h, mark_edges): where the enabled kinds of feature line lie on the
// half-pixel lattice, before widening. Silhouette from coverage (shifted to where the colour's
// alpha puts the boundary), depth jumps (Saito & Takahashi), creases (passes/edge_creases.h),
// normal discontinuities (Decaudin), id boundaries; then the two clean-ups: marks of other kinds
// next to the silhouette are dropped (the outline wins), and so are specks (groups of fewer
// than three marks); then, with EdgeParams::min_length, every connected group of marks of any
// kind shorter than that.
//
// Reads the EdgeImages the enabled kinds need (see passes/edges.h for types and which kind
// reads what); writes an EdgeMarks at the input size and the covered pixels. Rows are marked
// in parallel; every mark depends only on the inputs, never on the order of the work.
#pragma once

#include <opencv2/core.hpp>

#include "passes/edges.h"

namespace sylva {

// All marks of the enabled kinds of `p`, cleaned up, with the silhouette's sub-pixel shifts.
// `foreground` receives the covered pixels (CV_8UC1, 255 = covered) the marks were found on:
// colour alpha >= 0.5 when the colour image is given, else depth > 0, else id != 0, else
// |N| > 0. Missing inputs the parameters need are programming errors (SYLVA_CHECK).
EdgeMarks find_edge_marks(const EdgeImages& in, const EdgeParams& p, cv::Mat& foreground);

}  // namespace sylva

// Centre lines of thin shapes as polylines: a hanging strand, a twig or a fern's leaflet
// narrower than the smallest feature drawn is one line down its middle, not an outline
// (passes/ink_lines.h). Each connected piece is thinned (Zhang-Suen, passes/thinning.h) in its
// own bounding box, so the cost follows the pieces' area, and the one-pixel skeleton is walked
// into chains of pixel centres: through pixels with two neighbours, ending at ends and at
// junctions (three or more), loops closed. Spurs shorter than `min_spur` px that end freely at
// a junction are dropped.
//
// Reads a CV_8UC1 mask (non-zero = inside); writes polylines in the continuous image
// coordinates of core/strokes.h (pixel (i, j) at (i + 0.5, j + 0.5)), in raster order of their
// first point, so the result is deterministic.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "passes/crack_chains.h"

namespace sylva {

std::vector<Polyline> skeleton_chains(const cv::Mat& mask, double min_spur);

}  // namespace sylva

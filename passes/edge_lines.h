// Line drawing of the edges pass (passes/edges.h, detect_edges): the marks on the half-pixel
// lattice widened into antialiased line coverage. An exact Euclidean distance transform on the
// lattice (Felzenszwalb & Huttenlocher 2012; OpenCV's works on pixel centres only) finds each
// pixel's nearest mark; near a line, a least-squares line through the marks around it stands
// in for the boundary (a binary boundary zigzags by half a pixel about the true one); a
// one-pixel box filter across the line gives the coverage. Width and opacity may follow the
// nearest mark's depth (EdgeParams::depth_width, fade).
//
// Reads an EdgeMarks, depth (CV_32FC1 linear view depth, background 0; only with depth_width
// > 1 or fade > 0, else may be empty) and the covered pixels (CV_8UC1, non-zero = covered: the
// depth range is taken over them). Writes line coverage, CV_32FC1 in [0, 1] at the marks' size.
// Rows are drawn in parallel; every pixel depends only on the inputs, so the bytes do not
// depend on the number of threads.
#pragma once

#include <opencv2/core.hpp>

#include "passes/edges.h"

namespace sylva {

// Uses p.width (x reference_scale, no thinner than p.min_width px), p.depth_width and p.fade.
cv::Mat draw_edge_lines(const EdgeMarks& marks, const cv::Mat& depth, const cv::Mat& foreground,
                        const EdgeParams& p);

}  // namespace sylva

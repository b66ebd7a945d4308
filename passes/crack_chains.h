// Chaining line marks into polylines (the stroke representation, DESIGN.md §6). A mark is a
// crack: the boundary between two 4-neighbouring pixels, as EdgeMarks::between_x/_y hold
// them (passes/edges.h). Cracks meet at pixel corners, so a run of marks is a path in the graph
// of corners; chain_cracks walks that graph. A chain runs through corners where two cracks
// meet, goes straight on through a junction (3 or 4 cracks) when the crack opposite to the one
// it came along is free, and ends otherwise; a run with no ends is one closed chain. So the
// outline of a region is one closed polyline, and a T-junction gives one chain through its bar
// and one along its stem.
//
// Reads two CV_8UC1 crack images (non-zero = marked); writes polylines of corner points in the
// continuous image coordinates of core/strokes.h (corner (i, j) at (i, j)). The walk starts
// from chain ends in raster order, then junctions, then loops, so the result is deterministic.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "passes/pass_common.h"

namespace sylva {

// Cracks of a W x H image.
struct Cracks {
  cv::Mat x;  // CV_8UC1, H x (W - 1): between pixels (i, j) and (i + 1, j)
  cv::Mat y;  // CV_8UC1, (H - 1) x W: between pixels (i, j) and (i, j + 1)
  Cracks() = default;
  explicit Cracks(cv::Size image);  // all clear
  cv::Size image() const { return {y.cols, x.rows}; }
  int count() const;
};

struct Polyline {
  std::vector<cv::Point2f> points;
  bool closed = false;  // the last point joins the first (not repeated)
};

std::vector<Polyline> chain_cracks(const Cracks& cracks);

// Sets every crack (p, q) of `c` for which mark(p_index, q_index) holds (indices y * W + x),
// in parallel row bands; each band writes only its own rows.
template <class Mark>
void mark_cracks(Cracks& c, Mark mark) {
  const cv::Size size = c.image();
  const int w = size.width, h = size.height;
  for_bands(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      uint8_t* cx = c.x.empty() ? nullptr : c.x.ptr<uint8_t>(y);
      for (int x = 0; x + 1 < w; ++x)
        cx[x] = mark(y * w + x, y * w + x + 1) ? 255 : 0;
      if (y + 1 >= h) continue;
      uint8_t* cy = c.y.ptr<uint8_t>(y);
      for (int x = 0; x < w; ++x)
        cy[x] = mark(y * w + x, (y + 1) * w + x) ? 255 : 0;
    }
  });
}

// Total length in px (with the closing segment of a closed polyline).
double polyline_length(const Polyline& p);

// Gaussian smoothing of the points along the polyline, sigma in points (the chains of
// chain_cracks have points 1 px apart, so in px). An open polyline keeps its end points (the
// ends are reflected through them), so chains meeting at a junction still meet; a closed one
// wraps around. sigma <= 0 returns p.
Polyline smooth_polyline(const Polyline& p, double sigma);

// Douglas-Peucker simplification with `tolerance` px (cv::approxPolyDP).
Polyline simplify_polyline(const Polyline& p, double tolerance);

}  // namespace sylva

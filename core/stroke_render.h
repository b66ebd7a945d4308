// Drawing strokes (core/strokes.h): with cairo for the PDF, and as the raster ink's coverage,
// from the same geometry. A constant-width stroke is stroked with round caps and joins; a
// stroke with per-point widths, and a dot, is filled as its outline (stroke_outline, non-zero
// rule). Each stroke is painted on its own with its opacity, over the strokes before it.
//
// The raster covers the lines itself, of one width or tapered: each pixel by its share of the
// line's width across it at its nearest segment (so joins and ends are round; a tapered
// segment's width taken there, between its ends'), the stroke's own segments merged by the
// most, the strokes composited as cairo's OVER. For the thin lines a drawing is made of this
// agrees with cairo's exact stroking to about 1 % of the ink, several times faster (cairo
// spends about a microsecond a point on them: a willow's 5,000 branch outlines were the ink
// frame's longest pass). Dots and fills are cairo's.
#pragma once

#include <opencv2/core.hpp>

#include "core/strokes.h"

typedef struct _cairo cairo_t;

namespace sylva {

// Paints every stroke of `d` on `cr` in the drawing's colour (sRGB-encoded, as cairo takes
// it) times each stroke's opacity, with coordinates multiplied by `scale` (device units per
// px). Leaves cr's source and path cleared.
void paint_strokes(cairo_t* cr, const StrokeDrawing& d, double scale = 1.0);

// The ink's coverage at d.size: CV_32FC1 in [0, 1], 1 where the strokes cover a pixel fully at
// opacity 1 (opacity above 1 counts as 1; a line with a non-finite point is not drawn).
// Deterministic.
cv::Mat rasterize_strokes(const StrokeDrawing& d);

}  // namespace sylva

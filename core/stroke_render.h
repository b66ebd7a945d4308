// Drawing strokes (core/strokes.h) with cairo: the one drawing routine behind the raster ink
// and the PDF, so both show the same geometry. A constant-width stroke is stroked with round
// caps and joins; a stroke with per-point widths, and a dot, is filled as its outline
// (stroke_outline, non-zero rule). Each stroke is painted on its own with its opacity, in the
// drawing's order.
#pragma once

#include <opencv2/core.hpp>

#include "core/strokes.h"

typedef struct _cairo cairo_t;

namespace sylva {

// Paints every stroke of `d` on `cr` in the drawing's colour (sRGB-encoded, as cairo takes
// it) times each stroke's opacity, with coordinates multiplied by `scale` (device units per
// px). Leaves cr's source and path cleared.
void paint_strokes(cairo_t* cr, const StrokeDrawing& d, double scale = 1.0);

// The ink's coverage at d.size: CV_32FC1 in [0, 1] (8-bit precision, cairo's antialiasing),
// 1 where the strokes cover a pixel fully at opacity 1. Deterministic.
cv::Mat rasterize_strokes(const StrokeDrawing& d);

}  // namespace sylva

// A style's outputs as files, each written atomically: its image (.png or .tiff with alpha,
// 8 or 16 bits; .jpg without; .exr linear half RGBA premultiplied) and, for a style made of
// lines, its strokes (.svg or .pdf on the style's paper).
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "core/io/svg_writer.h"
#include "core/strokes.h"
#include "styles/style.h"

namespace sylva {

// Writes a style's BGRA image by the extension; `dpi` > 0 goes into a PNG's pHYs, a TIFF's
// resolution or an EXR's xDensity. bit_depth 16 (PNG, TIFF) widens the 8-bit values (v x 257).
void write_styled_image(const std::string& path, const cv::Mat& bgra, double dpi = 0.0,
                        int bit_depth = 8);

// The page of a style's vector drawing: its paper (ink.paper_color; none when ink.transparent
// or the view's background is transparent) and the dpi.
VectorPage vector_page(const Style& style, bool transparent_background, double dpi);
// Writes a drawing as .svg or .pdf (by the extension).
void write_vector_drawing(const std::string& path, const StrokeDrawing& d, const VectorPage& page);

}  // namespace sylva

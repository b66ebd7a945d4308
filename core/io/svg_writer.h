// SVG output of a stroke drawing (core/strokes.h; issue "Vector line art"). One Inkscape layer
// per line class present (a <g> with inkscape:groupmode="layer", inkscape:label = the class
// name and id "layer-<class>"), in the drawing's order, under an optional "paper" layer
// holding the background rect and a "paint" layer holding the drawing's paint
// (StrokeDrawing::paint) as an embedded PNG. A constant-width stroke is a path with stroke-width
// and round caps and joins; a stroke with per-point widths, or a dot, is its filled outline
// (stroke_outline, fill-rule nonzero), the same geometry core/stroke_render.h paints; a filled
// region (Stroke::filled) is a path of its rings with fill-rule evenodd. The
// viewBox is the image in px; width and height are px, or physical lengths with a DPI.
// Coordinates have two decimals, so the same drawing gives the same bytes.
#pragma once

#include <optional>
#include <string>

#include "core/strokes.h"

namespace sylva {

struct VectorPage {
  // Paper colour (linear RGB) of the background rect; empty = no background (transparent).
  std::optional<glm::vec3> paper = glm::vec3(1.0f);
  // Pixels per inch for the physical page size; 0 = sizes in px (SVG) or 72 dpi (PDF, one
  // point per px). Range [0, 10000] (outside: InputError from check_dpi).
  double dpi = 0.0;
};

// InputError(where, ...) unless dpi is finite and in [0, 10000] (0 = none).
void check_dpi(double dpi, const std::string& where);

std::string svg_document(const StrokeDrawing& d, const VectorPage& page);

// svg_document written atomically (core/io/atomic_file.h). Throws InputError(path, ...).
void write_svg(const std::string& path, const StrokeDrawing& d, const VectorPage& page);

}  // namespace sylva

// PDF output of a stroke drawing (core/strokes.h; issue "Vector line art") through cairo's PDF
// surface: one page the size of the image (at VectorPage::dpi, else one point per px), the
// paper as a filled rect unless transparent, and the strokes painted by the same routine as
// the raster ink (core/stroke_render.h), so the geometry is the raster's. The creation date is
// fixed, so the same drawing gives the same bytes.
#pragma once

#include <string>

#include "core/io/svg_writer.h"
#include "core/strokes.h"

namespace sylva {

std::string pdf_document(const StrokeDrawing& d, const VectorPage& page);

// pdf_document written atomically (core/io/atomic_file.h). Throws InputError(path, ...).
void write_pdf(const std::string& path, const StrokeDrawing& d, const VectorPage& page);

}  // namespace sylva

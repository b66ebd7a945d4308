#include "core/io/pdf_writer.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <memory>

#include "core/color.h"
#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/stroke_render.h"

namespace sylva {

namespace {

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

std::string pdf_document(const StrokeDrawing& d, const VectorPage& page) {
  check_dpi(page.dpi, "dpi");
  SYLVA_CHECK(d.size.width > 0 && d.size.height > 0, "pdf_document: empty drawing size");
  const double pt_per_px = page.dpi > 0.0 ? 72.0 / page.dpi : 1.0;
  std::string bytes;
  {
    std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
        cairo_pdf_surface_create_for_stream(&append, &bytes, d.size.width * pt_per_px,
                                            d.size.height * pt_per_px),
        &cairo_surface_destroy);
    SYLVA_CHECK(cairo_surface_status(surface.get()) == CAIRO_STATUS_SUCCESS,
                "pdf_document: cannot create the PDF surface");
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "Sylva");
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE,
                                   "2000-01-01T00:00:00Z");
    std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()),
                                                          &cairo_destroy);
    if (page.paper) {
      cairo_set_source_rgb(cr.get(), linear_to_srgb(page.paper->r), linear_to_srgb(page.paper->g),
                           linear_to_srgb(page.paper->b));
      cairo_paint(cr.get());
    }
    paint_strokes(cr.get(), d, pt_per_px);
    cr.reset();
    cairo_surface_finish(surface.get());
    SYLVA_CHECK(cairo_surface_status(surface.get()) == CAIRO_STATUS_SUCCESS,
                "pdf_document: cairo failed to write the PDF");
  }
  return bytes;
}

void write_pdf(const std::string& path, const StrokeDrawing& d, const VectorPage& page) {
  write_file_atomic(path, pdf_document(d, page));
}

}  // namespace sylva

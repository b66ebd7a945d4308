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

// A BGRA sRGB straight-alpha image as cairo's premultiplied ARGB32, painted over the page.
void paint_image(cairo_t* cr, const cv::Mat& bgra, double pt_per_px) {
  SYLVA_CHECK(bgra.type() == CV_8UC4, "pdf_document: the paint must be CV_8UC4");
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> image(
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, bgra.cols, bgra.rows),
      &cairo_surface_destroy);
  cairo_surface_flush(image.get());
  unsigned char* data = cairo_image_surface_get_data(image.get());
  const int stride = cairo_image_surface_get_stride(image.get());
  for (int y = 0; y < bgra.rows; ++y) {
    const cv::Vec4b* in = bgra.ptr<cv::Vec4b>(y);
    unsigned char* out = data + static_cast<ptrdiff_t>(y) * stride;
    for (int x = 0; x < bgra.cols; ++x)  // little-endian ARGB32 is B, G, R, A in memory
      for (int k = 0; k < 4; ++k)
        out[4 * x + k] =
            k == 3 ? in[x][3] : static_cast<unsigned char>((in[x][k] * in[x][3] + 127) / 255);
  }
  cairo_surface_mark_dirty(image.get());
  cairo_save(cr);
  cairo_scale(cr, pt_per_px, pt_per_px);
  cairo_set_source_surface(cr, image.get(), 0, 0);
  cairo_paint(cr);
  cairo_restore(cr);
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
    if (!d.paint.empty()) paint_image(cr.get(), d.paint, pt_per_px);
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

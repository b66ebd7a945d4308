#include "styles/style_files.h"

#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "core/io/exr_writer.h"
#include "core/io/image_io.h"
#include "core/io/pdf_writer.h"

namespace fs = std::filesystem;

namespace sylva {

VectorPage vector_page(const Style& style, bool transparent_background, double dpi) {
  VectorPage page;
  page.dpi = dpi;
  const InkParams& ink = style.params().ink;
  if (ink.transparent || transparent_background)
    page.paper.reset();
  else
    page.paper = ink.paper.color;
  return page;
}

void write_vector_drawing(const std::string& path, const StrokeDrawing& d, const VectorPage& page) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".pdf")
    write_pdf(path, d, page);
  else
    write_svg(path, d, page);
}

void write_styled_image(const std::string& path, const cv::Mat& bgra, double dpi, int bit_depth) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".jpg" || ext == ".jpeg") {
    cv::Mat bgr;
    cv::cvtColor(bgra, bgr, cv::COLOR_BGRA2BGR);
    write_image(path, bgr);
    return;
  }
  if (ext == ".exr") {
    ExrImage exr;
    add_exr_colour(exr, bgra, "");
    exr.dpi = dpi;
    write_exr(path, exr);
    return;
  }
  if (bit_depth == 16) {
    cv::Mat wide;
    bgra.convertTo(wide, CV_16U, 257.0);  // 255 -> 65535
    write_image(path, wide, dpi);
    return;
  }
  write_image(path, bgra, dpi);
}

}  // namespace sylva

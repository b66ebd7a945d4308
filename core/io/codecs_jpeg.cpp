// JPEG through libjpeg; see codecs_jpeg.h. libjpeg reports errors through error_exit, which
// must not return: it longjmps back to read_jpeg, which keeps nothing with a destructor alive
// across libjpeg calls.
#include "core/io/codecs_jpeg.h"

#include <csetjmp>
#include <cstdio>  // jpeglib.h needs FILE and size_t declared first

#include <jpeglib.h>

#include <string>
#include <vector>

namespace sylva {

namespace {

// OpenCV's limits on a decoded image (CV_IO_MAX_IMAGE_WIDTH/HEIGHT/PIXELS defaults).
constexpr JDIMENSION kMaxSide = 1u << 20;
constexpr unsigned long long kMaxPixels = 1ull << 30;

struct ErrorManager {
  jpeg_error_mgr mgr;  // first, so that a j_common_ptr's err points at the whole struct
  std::jmp_buf jump;
  DecodeReport* report;
};

std::string message_of(j_common_ptr info) {
  char text[JMSG_LENGTH_MAX] = {};
  info->err->format_message(info, text);
  return text;
}

[[noreturn]] void on_error(j_common_ptr info) {
  auto* errors = reinterpret_cast<ErrorManager*>(info->err);
  if (errors->report->error.empty()) errors->report->error = message_of(info);
  std::longjmp(errors->jump, 1);
}

// libjpeg's emit_message calls this for the first warning of an image (and for trace messages,
// which stay off): a warning instead of a line on stderr.
void on_message(j_common_ptr info) {
  reinterpret_cast<ErrorManager*>(info->err)->report->warn(message_of(info));
}

// Adobe's inverted CMYK (what libjpeg gives for Photoshop files) to BGR.
void cmyk_to_bgr(const cv::Mat& cmyk, cv::Mat& bgr) {
  bgr.create(cmyk.size(), CV_8UC3);
  for (int y = 0; y < cmyk.rows; ++y)
    for (int x = 0; x < cmyk.cols; ++x) {
      const cv::Vec4b p = cmyk.at<cv::Vec4b>(y, x);
      const int k = p[3];
      bgr.at<cv::Vec3b>(y, x) =
          cv::Vec3b(uchar(p[2] * k / 255), uchar(p[1] * k / 255), uchar(p[0] * k / 255));
    }
}

// Reads the header, then the pixels into `image`; false when libjpeg fails or the image is
// beyond the limits. The caller owns `image` and `rows` so that a longjmp skips no destructor.
// The scale 1/d (d = 1, 2, 4 or 8) at which the image fits `max_pixels`, or 0 when none does.
unsigned fitting_scale(JDIMENSION width, JDIMENSION height, unsigned long long max_pixels) {
  for (unsigned d = 1; d <= 8; d *= 2)
    if (static_cast<unsigned long long>((width + d - 1) / d) * ((height + d - 1) / d) <= max_pixels)
      return d;
  return 0;
}

bool read_jpeg(jpeg_decompress_struct& info, ErrorManager& errors, const unsigned char* bytes,
               size_t size, unsigned long long max_pixels, cv::Mat& image,
               std::vector<JSAMPROW>& rows) {
  if (setjmp(errors.jump)) return false;
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes, static_cast<unsigned long>(size));
  jpeg_read_header(&info, TRUE);
  if (info.image_width == 0 || info.image_height == 0 || info.image_width > kMaxSide ||
      info.image_height > kMaxSide ||
      static_cast<unsigned long long>(info.image_width) * info.image_height > kMaxPixels) {
    errors.report->error = "image size beyond 2^20 a side or 2^30 pixels";
    return false;
  }
  const std::string dims =
      std::to_string(info.image_width) + "x" + std::to_string(info.image_height);
  const unsigned d = fitting_scale(info.image_width, info.image_height, max_pixels);
  if (d == 0) {
    errors.report->error = dims + " is beyond 64 x " + std::to_string(max_pixels) + " pixels";
    return false;
  }
  if (d > 1) {
    info.scale_num = 1;
    info.scale_denom = d;
    errors.report->warn(dims + " is beyond " + std::to_string(max_pixels) +
                        " pixels: decoded at 1/" + std::to_string(d) + " of its size");
  }
  const bool cmyk = info.num_components == 4;
  const bool grey = info.num_components == 1;
  info.out_color_space = grey ? JCS_GRAYSCALE : cmyk ? JCS_CMYK : JCS_EXT_BGR;
  jpeg_start_decompress(&info);
  image.create(int(info.output_height), int(info.output_width), CV_8UC(info.output_components));
  rows.resize(info.output_height);
  for (int y = 0; y < image.rows; ++y)
    rows[size_t(y)] = image.ptr<JSAMPLE>(y);
  while (info.output_scanline < info.output_height)
    jpeg_read_scanlines(&info, rows.data() + info.output_scanline,
                        info.output_height - info.output_scanline);
  jpeg_finish_decompress(&info);
  return true;
}

}  // namespace

bool is_jpeg(const unsigned char* bytes, size_t size) {
  return bytes && size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

cv::Mat decode_jpeg(const unsigned char* bytes, size_t size, DecodeReport* report,
                    unsigned long long max_pixels) {
  DecodeReport ignored;
  ErrorManager errors{};
  errors.report = report ? report : &ignored;
  jpeg_decompress_struct info{};
  info.err = jpeg_std_error(&errors.mgr);
  errors.mgr.error_exit = on_error;
  errors.mgr.output_message = on_message;
  cv::Mat image;
  std::vector<JSAMPROW> rows;
  bool ok = false;
  if (is_jpeg(bytes, size)) {
    ok = read_jpeg(info, errors, bytes, size, max_pixels, image, rows);
    jpeg_destroy_decompress(&info);  // safe after a failed create: it checks info.mem
  }
  if (!ok) return cv::Mat();
  if (image.channels() == 4) {
    cv::Mat bgr;
    cmyk_to_bgr(image, bgr);
    return bgr;
  }
  return image;
}

}  // namespace sylva

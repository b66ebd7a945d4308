// PNG through libpng; see codecs_png.h. libpng reports errors by longjmp: the functions that
// set a jump point keep nothing with a destructor alive across libpng calls.
#include "core/io/codecs_png.h"

#include <cmath>

#include <png.h>
#include <zlib.h>

#include <bit>
#include <cstring>
#include <string>
#include <vector>

namespace sylva {

namespace {

void png_append(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), length);
}

void png_flush(png_structp) {}

// libpng's default handlers print "libpng error: ..." and "libpng warning: ..." to stderr; these
// keep the message in the DecodeReport given as the error pointer (or drop it, for none).
void png_on_error(png_structp png, png_const_charp message) {
  auto* report = static_cast<DecodeReport*>(png_get_error_ptr(png));
  if (report && report->error.empty()) report->error = message;
  png_longjmp(png, 1);
}

void png_on_warning(png_structp png, png_const_charp message) {
  if (auto* report = static_cast<DecodeReport*>(png_get_error_ptr(png))) report->warn(message);
}

struct ReadCursor {
  const unsigned char* data;
  size_t size;
  size_t pos;
};

void png_read_bytes(png_structp png, png_bytep dst, png_size_t length) {
  auto* in = static_cast<ReadCursor*>(png_get_io_ptr(png));
  if (length > in->size - in->pos) png_error(png, "PNG input buffer is incomplete");
  std::memcpy(dst, in->data + in->pos, length);
  in->pos += length;
}

// OpenCV's limits on a decoded image (CV_IO_MAX_IMAGE_WIDTH/HEIGHT/PIXELS defaults).
constexpr png_uint_32 kMaxSide = 1u << 20;
constexpr unsigned long long kMaxPixels = 1ull << 30;

// Reads the header, then the pixels into `image`. The caller owns `image` and `rows` so that a
// longjmp out of libpng skips no destructor. False when libpng fails or the image is beyond
// the limits.
bool read_png(png_structp png, png_infop info, png_infop end_info, unsigned long long max_pixels,
              cv::Mat& image, std::vector<png_bytep>& rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_info(png, info);
  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, color_type = 0;
  png_get_IHDR(png, info, &width, &height, &bit_depth, &color_type, nullptr, nullptr, nullptr);
  if (width == 0 || height == 0 || width > kMaxSide || height > kMaxSide ||
      static_cast<unsigned long long>(width) * height > kMaxPixels) {
    if (auto* report = static_cast<DecodeReport*>(png_get_error_ptr(png)))
      report->error = "image size beyond 2^20 a side or 2^30 pixels";
    return false;
  }
  if (static_cast<unsigned long long>(width) * height > max_pixels) {
    if (auto* report = static_cast<DecodeReport*>(png_get_error_ptr(png)))
      report->error = std::to_string(width) + "x" + std::to_string(height) + " is beyond " +
                      std::to_string(max_pixels) + " pixels";
    return false;
  }
  int channels = 1;
  switch (color_type) {
    case PNG_COLOR_TYPE_RGB:
    case PNG_COLOR_TYPE_PALETTE: {
      png_bytep trans = nullptr;
      int num_trans = 0;
      png_color_16p trans_values = nullptr;
      png_get_tRNS(png, info, &trans, &num_trans, &trans_values);
      channels = num_trans > 0 ? 4 : 3;
      break;
    }
    case PNG_COLOR_TYPE_GRAY_ALPHA:
    case PNG_COLOR_TYPE_RGB_ALPHA:
      channels = 4;
      break;
    default:
      channels = 1;
  }
  rows.resize(height);
  image.create(int(height), int(width), CV_MAKETYPE(bit_depth == 16 ? CV_16U : CV_8U, channels));
  // The transformations of OpenCV 4.6's PngDecoder::readData, in its order.
  if (bit_depth == 16 && std::endian::native == std::endian::little) png_set_swap(png);
  if (channels < 4)
    png_set_strip_alpha(png);
  else
    png_set_tRNS_to_alpha(png);
  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if ((color_type & PNG_COLOR_MASK_COLOR) == 0 && bit_depth < 8)
    png_set_expand_gray_1_2_4_to_8(png);
  const bool color = channels > 1;
  if ((color_type & PNG_COLOR_MASK_COLOR) && color)
    png_set_bgr(png);
  else if (color)
    png_set_gray_to_rgb(png);
  else
    png_set_rgb_to_gray(png, 1, 0.299, 0.587);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  for (int y = 0; y < image.rows; ++y)
    rows[size_t(y)] = image.ptr<png_byte>(y);
  png_read_image(png, rows.data());
  png_read_end(png, end_info);
  return true;
}

}  // namespace

bool encode_png(const cv::Mat& image, const PngEncodeOptions& options, std::string& out) {
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, png_on_error, png_on_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  static constexpr int kColorTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                        PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
  png_set_write_fn(png, &out, png_append, png_flush);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, options.sub_filter ? PNG_FILTER_SUB : PNG_FILTER_NONE);
  png_set_compression_level(png, options.level);
  if (options.rle) png_set_compression_strategy(png, Z_RLE);
  png_set_IHDR(png, info, png_uint_32(image.cols), png_uint_32(image.rows),
               image.depth() == CV_16U ? 16 : 8, kColorTypes[image.channels() - 1],
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (options.dpi > 0.0) {
    const auto per_metre = png_uint_32(std::lround(options.dpi / 0.0254));
    png_set_pHYs(png, info, per_metre, per_metre, PNG_RESOLUTION_METER);
  }
  png_write_info(png, info);
  if (image.channels() >= 3) png_set_bgr(png);  // OpenCV's channel order
  if (image.depth() == CV_16U && std::endian::native == std::endian::little) png_set_swap(png);
  for (int y = 0; y < image.rows; ++y)
    png_write_row(png, const_cast<png_bytep>(image.ptr<png_byte>(y)));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

bool is_png(const unsigned char* bytes, size_t size) {
  return bytes && size >= 8 && png_sig_cmp(bytes, 0, 8) == 0;
}

cv::Mat decode_png(const unsigned char* bytes, size_t size, DecodeReport* report,
                   unsigned long long max_pixels) {
  if (!is_png(bytes, size)) return cv::Mat();
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, report, png_on_error, png_on_warning);
  if (!png) return cv::Mat();
  png_infop info = png_create_info_struct(png);
  png_infop end_info = png_create_info_struct(png);
  cv::Mat image;
  std::vector<png_bytep> rows;
  bool ok = false;
  if (info && end_info) {
    ReadCursor in{bytes, size, 0};
    png_set_read_fn(png, &in, png_read_bytes);
    ok = read_png(png, info, end_info, max_pixels, image, rows);
  }
  png_destroy_read_struct(&png, &info, &end_info);
  if (!ok) image.release();
  return image;
}

}  // namespace sylva

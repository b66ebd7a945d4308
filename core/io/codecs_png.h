// PNG encoding and decoding with libpng, in process: the PNG paths (rendered output, glTF
// textures in and out) never load the sylva_codecs plugin (core/io/codecs.h). Images are
// cv::Mat in OpenCV's layout: 8- or 16-bit, 1-4 channels, BGR(A) order.
#pragma once

#include <cstddef>
#include <opencv2/core.hpp>
#include <string>

#include "core/io/decode_report.h"

namespace sylva {

// Row filter and zlib settings. The defaults are sylva's own (fast rather than small); see
// kOpenCvPng for what cv::imencode(".png") does.
struct PngEncodeOptions {
  int level = 3;            // zlib level, 0 (store) .. 9 (smallest)
  bool sub_filter = false;  // the SUB row filter on every row; false: no filter
  bool rle = false;         // zlib's Z_RLE strategy; false: libpng's default
  double dpi = 0.0;         // > 0: a pHYs chunk of round(dpi / 0.0254) pixels per metre
};

// What cv::imencode(".png") does without parameters in OpenCV 4.6: zlib level 1, SUB row
// filter, Z_RLE. The same settings through the same libpng and zlib give the same bytes.
inline constexpr PngEncodeOptions kOpenCvPng = {1, true, true, 0.0};

// Appends the PNG to `out`. False when libpng fails; `image` must be 8/16-bit, 1-4 channels.
bool encode_png(const cv::Mat& image, const PngEncodeOptions& options, std::string& out);

// True when `bytes` start with the PNG signature.
bool is_png(const unsigned char* bytes, size_t size);

// What cv::imdecode(bytes, cv::IMREAD_UNCHANGED) gives for a PNG in OpenCV 4.6: 16-bit kept;
// grey (1-, 2-, 4-bit expanded) as 1 channel; grey+alpha as BGRA; RGB and palette as BGR, or
// BGRA when a tRNS chunk is present. An empty Mat for data libpng cannot read or an image
// beyond OpenCV's limits (2^20 a side, 2^30 pixels) or `max_pixels`; libpng's reason and
// warnings go to `report` (never to stderr).
cv::Mat decode_png(const unsigned char* bytes, size_t size, DecodeReport* report = nullptr,
                   unsigned long long max_pixels = 1ull << 30);

}  // namespace sylva

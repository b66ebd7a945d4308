// JPEG decoding with libjpeg(-turbo), in process: glTF's JPEG textures never load the
// sylva_codecs plugin, and libjpeg's messages ("Corrupt JPEG data: ...") reach a DecodeReport
// instead of stderr. Images come out in OpenCV's layout.
#pragma once

#include <cstddef>
#include <opencv2/core.hpp>

#include "core/io/decode_report.h"

namespace sylva {

// True when `bytes` start with the JPEG SOI marker (FF D8 FF).
bool is_jpeg(const unsigned char* bytes, size_t size);

// What cv::imdecode(bytes, cv::IMREAD_UNCHANGED) gives for a JPEG in OpenCV 4.6: 8-bit, grey as 1
// channel, colour as BGR, no EXIF rotation; CMYK (Adobe's inverted form) converted to BGR. An
// empty Mat, with the reason in `report`, for data libjpeg cannot read or an image beyond
// OpenCV's limits (2^20 a side, 2^30 pixels). An image of more than `max_pixels` is decoded at
// 1/2, 1/4 or 1/8 of its size (libjpeg's DCT scaling, the largest that fits), with a warning;
// beyond 64 x max_pixels it is an error.
cv::Mat decode_jpeg(const unsigned char* bytes, size_t size, DecodeReport* report = nullptr,
                    unsigned long long max_pixels = 1ull << 30);

}  // namespace sylva

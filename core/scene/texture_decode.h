// Decoding an encoded image (PNG, JPEG, any bit depth, 1-4 channels) from memory into the
// scene's 8-bit RGBA Texture: 16-bit is scaled down, grey/RGB get an opaque alpha. Bad data
// throws InputError(path, "<what>: cannot decode ...: <the decoder's reason>"); a decoder's
// warning (a damaged but readable image) is appended to `warnings` as "<what>: <warning>".
// PNG and JPEG are decoded in process (core/io/codecs.h). Used by gltf_read.cpp; header-only so
// it needs no build entry of its own.
#pragma once

#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/io/codecs.h"
#include "core/scene/scene.h"

namespace sylva {

// At most 2^26 pixels (8192 x 8192) in a decoded texture: a 16-byte-per-pixel peak stays near
// 1 GiB, while a PNG header or a JPEG of a few hundred bytes may declare 2^30 pixels. A larger
// JPEG is decoded at 1/2, 1/4 or 1/8 of its size with a warning; a larger PNG is an error.
inline constexpr unsigned long long kMaxTexturePixels = 1ull << 26;

// `path` is the scene file and `what` names the image in error messages.
inline Texture decode_texture(const unsigned char* bytes, size_t size, const std::string& name,
                              const std::string& path, const std::string& what,
                              std::vector<std::string>& warnings) {
  cv::Mat m;
  DecodeReport report;
  if (bytes && size > 0 && size < size_t(1) << 31) {
    try {
      m = decode_png_or_jpeg(bytes, size, &report, kMaxTexturePixels);
    } catch (const cv::Exception&) {
      m = cv::Mat();
    }
  }
  if (m.empty())
    throw InputError(path, what + ": cannot decode the image (PNG or JPEG expected)" +
                               (report.error.empty() ? "" : ": " + report.error));
  for (const std::string& w : report.warnings)
    warnings.push_back(what + ": " + w);
  if (m.depth() == CV_16U)
    m.convertTo(m, CV_8U, 1.0 / 257.0);
  else if (m.depth() != CV_8U)
    m.convertTo(m, CV_8U, 255.0);
  cv::Mat rgba;
  if (m.channels() == 1) {
    cv::cvtColor(m, rgba, cv::COLOR_GRAY2RGBA);
  } else if (m.channels() == 3) {
    cv::cvtColor(m, rgba, cv::COLOR_BGR2RGBA);
  } else if (m.channels() == 4) {
    cv::cvtColor(m, rgba, cv::COLOR_BGRA2RGBA);
  } else {  // grey + alpha: OpenCV has no conversion code for two channels
    rgba.create(m.rows, m.cols, CV_8UC4);
    for (int y = 0; y < m.rows; ++y)
      for (int x = 0; x < m.cols; ++x) {
        const cv::Vec2b g = m.at<cv::Vec2b>(y, x);
        rgba.at<cv::Vec4b>(y, x) = cv::Vec4b(g[0], g[0], g[0], g[1]);
      }
  }
  Texture t;
  t.name = name;
  t.width = rgba.cols;
  t.height = rgba.rows;
  t.rgba.assign(rgba.data, rgba.data + rgba.total() * 4);
  return t;
}

}  // namespace sylva

// Multi-channel OpenEXR files (issue "Buffers and renders for compositors and print"), written
// with the OpenEXR library into memory and then atomically into place (core/io/atomic_file.h),
// so a failure leaves no file.
//
// Channels are named as compositors expect (R G B A, N.X, Z, P.X, id, ...) and stored as half,
// float or 32-bit unsigned int; the camera goes into the standard header attributes
// `worldToCamera` and `worldToNDC` (Imath's row-vector convention: p_camera = p_world * M, so
// M is the transpose of the column-vector matrix; camera space is Sylva's view space, looking
// down -z), plus float attributes `near` and `far`; a DPI into `xDensity` (pixels per inch).
#pragma once

#include <glm/mat4x4.hpp>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sylva {

enum class ExrType { Half, Float, Uint };
enum class ExrCompression { None, Zip, Piz };

struct ExrChannel {
  std::string name;
  ExrType type = ExrType::Float;
  cv::Mat plane;  // one channel of the image's size: CV_32FC1 (Half, Float) or CV_32SC1 (Uint)
};

struct ExrCamera {
  glm::mat4 world_to_camera{1.0f};  // column-vector convention (glm): p_view = M * p_world
  glm::mat4 world_to_ndc{1.0f};     // projection * view
  float near_plane = 0.0f, far_plane = 0.0f;
};

struct ExrImage {
  int width = 0, height = 0;
  std::vector<ExrChannel> channels;
  std::optional<ExrCamera> camera;
  double dpi = 0.0;  // 0: no xDensity attribute
  ExrCompression compression = ExrCompression::Zip;
  std::vector<std::pair<std::string, std::string>> strings;  // string attributes, in order
};

// "none", "zip" or "piz"; InputError(option, ...) naming the allowed values otherwise.
ExrCompression parse_exr_compression(const std::string& name, const std::string& option);

// Appends channels to `image` (which fixes the size on the first call): a CV_32FC1/CV_32SC1
// plane as one channel, a CV_32FC3 one as `names[0..2]` (channel 0 = x first).
void add_exr_channels(ExrImage& image, const cv::Mat& plane, const std::vector<std::string>& names,
                      ExrType type);

// The colour of an 8-bit sRGB BGRA image as linear, premultiplied R, G, B and A (half).
void add_exr_colour(ExrImage& image, const cv::Mat& bgra, const std::string& prefix);

// Throws InputError(path, ...) when the file cannot be written; non-finite float values and
// planes of the wrong size or type are programming errors (SYLVA_CHECK).
void write_exr(const std::string& path, const ExrImage& image);

}  // namespace sylva

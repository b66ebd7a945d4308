// Image files: encode a cv::Mat by the file's extension (.png 8/16-bit, .tiff float32 kept
// exactly, .exr) and write it atomically; and 8-bit previews of float G-buffer images.
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace sylva {

// Throws InputError(path, ...) for an unsupported extension or a failed write. Non-finite
// values in float images are a programming error (SYLVA_CHECK): nothing NaN reaches a file.
// PNGs (1-4 channels, BGR(A) order) are written by libpng, fast rather than small (zlib level
// 3, no row filters); the other formats by OpenCV.
void write_image(const std::string& path, const cv::Mat& image);
// The same with a resolution in pixels per inch (> 0; 0 = none): a PNG's pHYs chunk, a TIFF's
// resolution tags (rounded to whole dpi). Other formats ignore it.
void write_image(const std::string& path, const cv::Mat& image, double dpi);

// Reads an image unchanged (cv::IMREAD_UNCHANGED). Throws InputError when unreadable.
cv::Mat read_image(const std::string& path);

// 8-bit BGR previews: normal as (n + 1) / 2; depth mapped near→white, far→dark over its
// range; ids as distinct hashed colours; scalar [0, 1] buffers (ka, AO) as grey. Background
// (0) stays black.
cv::Mat preview_normal(const cv::Mat& normal);
cv::Mat preview_depth(const cv::Mat& depth);
cv::Mat preview_position(const cv::Mat& position);  // each axis over its covered range
cv::Mat preview_ids(const cv::Mat& ids);
cv::Mat preview_scalar(const cv::Mat& values);

bool all_finite(const cv::Mat& image);

}  // namespace sylva

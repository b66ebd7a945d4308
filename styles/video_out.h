// An MP4 written through OpenCV's VideoWriter (FFmpeg) under a temporary name beside the target
// and renamed into place by finish(); destroyed unfinished, it leaves nothing behind. The writer
// lives in the codecs plugin (core/io/codecs.h), loaded when the first VideoOut is made.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>

namespace sylva {

class VideoOut {
 public:
  // Throws InputError("--output", ...) when no MP4 writer opens (avc1, then mp4v), and
  // std::runtime_error when the codecs plugin does not load.
  VideoOut(const std::string& path, double fps, cv::Size size);
  ~VideoOut();
  VideoOut(const VideoOut&) = delete;
  VideoOut& operator=(const VideoOut&) = delete;
  void write(const cv::Mat& bgr);  // 8-bit BGR, the size given
  // Finishes the file and puts it in place; throws InputError(path, ...) when the written file
  // does not hold every frame (nothing is left behind then).
  void finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace sylva

// The entry points of the sylva_codecs plugin (libsylva_codecs.so): OpenCV's imgcodecs and
// videoio behind dlopen(), so the sylva executable and libraries do not link them. Loading those
// two libraries pulls in GDAL, FFmpeg, GStreamer, poppler ... and their static initialisers, about
// 280 ms before main() even for `sylva --version`; now only a command that reads or writes an
// image other than PNG, or a video, pays it. Shared by the plugin (core/io/codecs_plugin.cpp) and
// its loader (core/io/codecs.cpp). Both are built from one tree by one compiler and share
// libopencv_core, so C++ types and cv::Exception cross the boundary.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace sylva {

// Bumped whenever CodecsApi changes; the loader refuses a plugin built for another version.
inline constexpr int kCodecsApiVersion = 5;

// The name of the one symbol the plugin exports: `const CodecsApi* sylva_codecs_api()`.
inline constexpr const char* kCodecsApiSymbol = "sylva_codecs_api";

struct CodecsApi {
  int version;
  // cv::imencode and cv::imdecode: they throw cv::Exception as OpenCV does. What imdecode's
  // decoders print to std::cerr (OpenCV's "can't read header", GDCM's trace) is dropped.
  bool (*encode)(const std::string& ext, const cv::Mat& image, std::vector<uchar>& bytes,
                 const std::vector<int>& params);
  cv::Mat (*decode)(const cv::Mat& bytes, int flags);
  // A cv::VideoWriter through FFmpeg with the four-character `codec` ("avc1"); null when it
  // does not open. video_close releases the writer (finishing the file) and frees it.
  void* (*video_open)(const std::string& path, const char* codec, double fps, cv::Size size);
  void (*video_write)(void* writer, const cv::Mat& frame);
  void (*video_close)(void* writer);
  // The number of frames a video file holds (cv::VideoCapture through FFmpeg: the container's
  // count), or -1 when it does not open: how an MP4 cut short by a full disk is caught.
  int (*video_frames)(const std::string& path);
  // FFmpeg's error messages since the last call, one line each ("[mp4] moov atom not found",
  // without the context's address), and forgets them: the plugin routes FFmpeg's log here
  // instead of stderr, so they reach the user inside Sylva's own error or warning line.
  std::string (*take_log)();
  // The libraries behind the plugin and their versions ("OpenCV 4.6.0 imgcodecs and videoio,
  // FFmpeg 5.1.4"), for `sylva --version --verbose`.
  std::string (*versions)();
};

}  // namespace sylva

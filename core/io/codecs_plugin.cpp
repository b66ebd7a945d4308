// The sylva_codecs plugin (a CMake MODULE, libsylva_codecs.so): the only code that links
// opencv_imgcodecs and opencv_videoio. Loaded on first use by core/io/codecs.cpp; see
// core/io/codecs_api.h for why.
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "core/io/codecs_api.h"

namespace {

bool encode(const std::string& ext, const cv::Mat& image, std::vector<uchar>& bytes,
            const std::vector<int>& params) {
  return cv::imencode(ext, image, bytes, params);
}

cv::Mat decode(const cv::Mat& bytes, int flags) {
  return cv::imdecode(bytes, flags);
}

void* video_open(const std::string& path, const char* codec, double fps, cv::Size size) {
  auto writer = std::make_unique<cv::VideoWriter>();
  const int fourcc = cv::VideoWriter::fourcc(codec[0], codec[1], codec[2], codec[3]);
  if (!writer->open(path, cv::CAP_FFMPEG, fourcc, fps, size)) return nullptr;
  return writer.release();
}

void video_write(void* writer, const cv::Mat& frame) {
  static_cast<cv::VideoWriter*>(writer)->write(frame);
}

void video_close(void* writer) {
  auto* w = static_cast<cv::VideoWriter*>(writer);
  w->release();
  delete w;
}

constexpr sylva::CodecsApi kApi = {
    sylva::kCodecsApiVersion, encode, decode, video_open, video_write, video_close};

}  // namespace

extern "C" __attribute__((visibility("default"))) const sylva::CodecsApi* sylva_codecs_api() {
  return &kApi;
}

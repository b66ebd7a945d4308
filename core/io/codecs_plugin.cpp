// The sylva_codecs plugin (a CMake MODULE, libsylva_codecs.so): the only code that links
// opencv_imgcodecs and opencv_videoio. Loaded on first use by core/io/codecs.cpp; see
// core/io/codecs_api.h for why.
#include <sched.h>

#include <cstdarg>
#include <cstdint>
#include <iostream>
#include <memory>
#include <mutex>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/codecs_api.h"

extern "C" {
#include <libavutil/avutil.h>
#include <libavutil/log.h>
}

namespace {

std::mutex g_log_mutex;
std::string g_log;  // FFmpeg's error lines not yet taken

// FFmpeg's log callback: errors are kept for take_log(), everything else is dropped (OpenCV
// leaves FFmpeg at AV_LOG_ERROR, so nothing more used to be printed either).
void log_callback(void* context, int level, const char* format, va_list args) {
  if (level > AV_LOG_ERROR) return;
  char line[1024];
  int print_prefix = 1;
  av_log_format_line2(context, level, format, args, line, sizeof line, &print_prefix);
  std::string text = line;
  const size_t at = text.find(" @ 0x");  // "[mov,mp4 @ 0x55c5c9650f80] ..." -> "[mov,mp4] ..."
  if (at != std::string::npos && text.find(']', at) != std::string::npos)
    text.erase(at, text.find(']', at) - at);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
    text.pop_back();
  if (text.empty()) return;
  const std::lock_guard<std::mutex> lock(g_log_mutex);
  g_log += text + "\n";
}

std::string take_log() {
  const std::lock_guard<std::mutex> lock(g_log_mutex);
  std::string out;
  out.swap(g_log);
  return out;
}

bool encode(const std::string& ext, const cv::Mat& image, std::vector<uchar>& bytes,
            const std::vector<int>& params) {
  return cv::imencode(ext, image, bytes, params);
}

// While alive, what is written to std::cerr goes into a string that is then dropped (one at a
// time: the stream is global). OpenCV's imdecode prints there when a decoder throws ("can't read
// header"), and so does GDCM's trace for data that is not DICOM; the empty image says enough.
class CerrDropped {
 public:
  CerrDropped() : m_lock(s_mutex), m_saved(std::cerr.rdbuf(m_text.rdbuf())) {}
  ~CerrDropped() { std::cerr.rdbuf(m_saved); }
  CerrDropped(const CerrDropped&) = delete;
  CerrDropped& operator=(const CerrDropped&) = delete;

 private:
  static std::mutex s_mutex;
  std::lock_guard<std::mutex> m_lock;
  std::ostringstream m_text;
  std::streambuf* m_saved;
};
std::mutex CerrDropped::s_mutex;

cv::Mat decode(const cv::Mat& bytes, int flags) {
  const CerrDropped quiet;
  return cv::imdecode(bytes, flags);
}

// While alive, the calling thread may run on one CPU only (the first it may use), so an encoder
// opened meanwhile counts one CPU: libx264 then encodes in one thread (OpenCV's VideoWriter has
// no option for the thread count), whose output is a function of its input alone; with its
// frame threads, the MP4's bytes changed under load.
class OneCpu {
 public:
  OneCpu() {
    m_pinned = sched_getaffinity(0, sizeof m_saved, &m_saved) == 0;
    if (!m_pinned) return;
    cpu_set_t one;
    CPU_ZERO(&one);
    for (int c = 0; c < CPU_SETSIZE; ++c)
      if (CPU_ISSET(c, &m_saved)) {
        CPU_SET(c, &one);
        break;
      }
    m_pinned = sched_setaffinity(0, sizeof one, &one) == 0;
  }
  ~OneCpu() {
    if (m_pinned) sched_setaffinity(0, sizeof m_saved, &m_saved);
  }
  OneCpu(const OneCpu&) = delete;
  OneCpu& operator=(const OneCpu&) = delete;

 private:
  cpu_set_t m_saved;
  bool m_pinned = false;
};

// A writer and the buffer its frames are copied into. OpenCV hands a frame to FFmpeg's swscale
// in place unless its end lies near a page boundary, and swscale's SIMD reads a little past the
// end: from a frame wherever the caller's allocator put it, those bytes were whatever lay there,
// and the MP4's bytes changed from run to run (seen with libx264 at 64x64). Every frame is
// copied into one buffer whose rows are 32-byte aligned and which ends in 4 KiB of zeros.
struct Video {
  cv::VideoWriter writer;
  std::vector<uchar> storage;
  cv::Mat padded;
};

void* video_open(const std::string& path, const char* codec, double fps, cv::Size size) {
  auto video = std::make_unique<Video>();
  const int fourcc = cv::VideoWriter::fourcc(codec[0], codec[1], codec[2], codec[3]);
  {
    const OneCpu one_cpu;
    if (!video->writer.open(path, cv::CAP_FFMPEG, fourcc, fps, size)) return nullptr;
  }
  const size_t step = (size_t(size.width) * 3 + 31) / 32 * 32;
  video->storage.assign(step * size_t(size.height) + 4096 + 64, 0);
  uchar* start = video->storage.data();
  start += (64 - reinterpret_cast<uintptr_t>(start) % 64) % 64;
  video->padded = cv::Mat(size, CV_8UC3, start, step);
  return video.release();
}

void video_write(void* writer, const cv::Mat& frame) {
  auto* video = static_cast<Video*>(writer);
  frame.copyTo(video->padded);  // same size and type: no reallocation
  video->writer.write(video->padded);
}

void video_close(void* writer) {
  auto* video = static_cast<Video*>(writer);
  video->writer.release();
  delete video;
}

int video_frames(const std::string& path) {
  cv::VideoCapture capture;
  if (!capture.open(path, cv::CAP_FFMPEG)) return -1;
  return static_cast<int>(capture.get(cv::CAP_PROP_FRAME_COUNT));
}

// What the plugin loaded, for `sylva --version --verbose`.
std::string versions() {
  return "OpenCV " + cv::getVersionString() + " imgcodecs and videoio, FFmpeg " + av_version_info();
}

constexpr sylva::CodecsApi kApi = {sylva::kCodecsApiVersion,
                                   encode,
                                   decode,
                                   video_open,
                                   video_write,
                                   video_close,
                                   video_frames,
                                   take_log,
                                   versions};

}  // namespace

extern "C" __attribute__((visibility("default"))) const sylva::CodecsApi* sylva_codecs_api() {
  static std::once_flag routed;
  std::call_once(routed, [] { av_log_set_callback(log_callback); });
  return &kApi;
}

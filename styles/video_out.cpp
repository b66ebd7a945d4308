#include "styles/video_out.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/io/codecs.h"

namespace fs = std::filesystem;

namespace sylva {
namespace {

// FFmpeg's first error line since the last call, as "; FFmpeg: <line>", or "".
std::string ffmpeg_reason(const CodecsApi& api) {
  const std::string log = api.take_log();
  return log.empty() ? "" : "; FFmpeg: " + log.substr(0, log.find('\n'));
}

}  // namespace

struct VideoOut::Impl {
  const CodecsApi& api = codecs();
  std::string path, temp;
  void* writer = nullptr;  // a cv::VideoWriter in the plugin
  int frames = 0;
  bool done = false;

  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() { close(); }
  void close() {  // releases the writer, which finishes the file
    if (writer) api.video_close(writer);
    writer = nullptr;
  }
};

VideoOut::VideoOut(const std::string& path, double fps, cv::Size size)
    : m_impl(std::make_unique<Impl>()) {
  m_impl->path = path;
  const fs::path p(path);
  std::string name = ".";  // built by appending: `"." + string&&` trips GCC 12's -Wrestrict
  name += p.stem().string();
  name += ".partial-" + std::to_string(getpid()) + ".mp4";
  m_impl->temp = (p.parent_path() / name).string();
  for (const char* codec : {"avc1", "mp4v"}) {
    m_impl->writer = m_impl->api.video_open(m_impl->temp, codec, fps, size);
    if (m_impl->writer) return;
  }
  throw InputError("--output", "cannot open an MP4 writer for '" + path + "' (FFmpeg)" +
                                   ffmpeg_reason(m_impl->api));
}

VideoOut::~VideoOut() {
  if (!m_impl->done) {
    m_impl->close();
    std::error_code ec;
    fs::remove(m_impl->temp, ec);
  }
}

void VideoOut::write(const cv::Mat& bgr) {
  m_impl->api.video_write(m_impl->writer, bgr);
  ++m_impl->frames;
}

void VideoOut::finish() {
  m_impl->close();
  std::error_code ec;
  // FFmpeg does not report a failed write through OpenCV: a file that does not hold every
  // frame (a full disk, a removed folder) is not put in place.
  if (m_impl->api.video_frames(m_impl->temp) != m_impl->frames)
    throw InputError(m_impl->path, "cannot write: the MP4 came out incomplete (is the disk full?)" +
                                       ffmpeg_reason(m_impl->api));
  // Errors FFmpeg reported along a video that came out whole: one warning line.
  if (const std::string reason = ffmpeg_reason(m_impl->api); !reason.empty())
    std::fprintf(stderr, "sylva: warning: %s: %s\n", m_impl->path.c_str(),
                 reason.substr(2).c_str());
  fs::rename(m_impl->temp, m_impl->path, ec);
  if (ec) throw InputError("--output", "cannot write '" + m_impl->path + "': " + ec.message());
  m_impl->done = true;
}

}  // namespace sylva

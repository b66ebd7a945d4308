#include "styles/frame_encode.h"

#include <filesystem>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/io/codecs_png.h"
#include "core/io/gif_writer.h"
#include "core/progress.h"
#include "styles/frame_folder.h"
#include "styles/video_out.h"

namespace fs = std::filesystem;

namespace sylva {

namespace {

using EncodeOptions = EncodeRequest;

// The number of frames to encode: --frames, or the highest frame index + 1. Throws when the
// folder holds no PNG frame (naming the other frame formats it holds).
int frames_in_folder(const EncodeOptions& o) {
  std::error_code ec;
  if (!fs::is_directory(o.dir, ec)) throw InputError(o.dir, "not a folder of frames");
  int highest = -1;
  std::string other;
  for (const auto& entry : fs::directory_iterator(o.dir, ec)) {
    const std::string name = entry.path().filename().string();
    highest = std::max(highest, frame_index_of(name, FrameFormat::Png));
    for (FrameFormat format : {FrameFormat::Exr, FrameFormat::Svg, FrameFormat::Pdf})
      if (frame_index_of(name, format) >= 0) other = name;
  }
  if (ec) throw InputError(o.dir, "cannot read the folder: " + ec.message());
  if (o.frames > 0) return o.frames;
  if (highest >= 0) return highest + 1;
  throw InputError(o.dir, other.empty() ? "holds no frame-NNNNN.png frames"
                                        : "encode reads PNG frames; the folder holds " + other);
}

std::string frame_path(const EncodeOptions& o, int i) {
  return (fs::path(o.dir) / frame_file_name(i)).string();
}

InputError missing_frame(const EncodeOptions& o, int i, int count) {
  return InputError(frame_path(o, i), "missing frame (" + std::to_string(count) +
                                          " frames are encoded: frame-00000.png to " +
                                          frame_file_name(count - 1) + ")");
}

// Frame i as 8-bit BGRA. Throws InputError naming the frame when it is missing or partial.
cv::Mat read_frame(const EncodeOptions& o, int i, int count) {
  const std::string path = frame_path(o, i);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw missing_frame(o, i, count);
  const std::string bytes = read_file_bytes(path);
  DecodeReport report;
  cv::Mat image =
      decode_png(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), &report);
  if (image.empty())
    throw InputError(
        path, "partial or damaged frame" + (report.error.empty() ? "" : " (" + report.error + ")"));
  if (image.depth() != CV_8U || (image.channels() != 3 && image.channels() != 4))
    throw InputError(path, "an 8-bit RGB or RGBA frame is expected");
  if (image.channels() == 3) cv::cvtColor(image, image, cv::COLOR_BGR2BGRA);
  return image;
}

void check_size(const EncodeOptions& o, int i, const cv::Mat& image, const cv::Mat& first) {
  if (image.size() != first.size())
    throw InputError(frame_path(o, i), "is " + std::to_string(image.cols) + "x" +
                                           std::to_string(image.rows) + ", frame 0 is " +
                                           std::to_string(first.cols) + "x" +
                                           std::to_string(first.rows));
}

}  // namespace

EncodeResult encode_frames(const EncodeRequest& o) {
  SYLVA_CHECK(o.fps >= 1 && o.fps <= 240 && o.frames >= 0 && o.frames <= 100000,
              "encode_frames: fps or frames outside their range");
  const int count = frames_in_folder(o);
  for (int i = 0; i < count; ++i)  // a missing frame is named before any work
    if (std::error_code ec; !fs::is_regular_file(frame_path(o, i), ec))
      throw missing_frame(o, i, count);
  const cv::Mat first = read_frame(o, 0, count);
  for (int i = 1; i < count; ++i)  // and a partial one, or one of another size
    check_size(o, i, read_frame(o, i, count), first);
  const bool gif = fs::path(o.out).extension() == ".gif";
  std::unique_ptr<GifWriter> gif_out;
  std::unique_ptr<VideoOut> video;
  if (gif)
    gif_out = std::make_unique<GifWriter>(o.out, o.fps, first.size(), count);
  else
    video = std::make_unique<VideoOut>(o.out, o.fps, first.size());
  ProgressOptions po;
  po.quiet = o.quiet;
  Progress progress("encode", static_cast<size_t>(count), po);
  for (int i = 0; i < count; ++i) {
    const cv::Mat image = i == 0 ? first : read_frame(o, i, count);
    check_size(o, i, image, first);  // the folder may change while it is encoded
    if (gif_out) {
      gif_out->write(image);
    } else {
      cv::Mat bgr;
      cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
      video->write(bgr);
    }
    progress.step("frame " + std::to_string(i));
  }
  progress.finish();
  if (gif_out) gif_out->finish();
  if (video) video->finish();
  return {count, first.cols, first.rows};
}
}  // namespace sylva

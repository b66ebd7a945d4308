#include "core/io/exr_writer.h"

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>

#include <array>
#include <cstring>
#include <deque>
#include <mutex>
#include <thread>

#include "core/color.h"
#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/io/image_io.h"

namespace sylva {

ExrCompression parse_exr_compression(const std::string& name, const std::string& option) {
  if (name == "none") return ExrCompression::None;
  if (name == "zip") return ExrCompression::Zip;
  if (name == "piz") return ExrCompression::Piz;
  throw InputError(option, "unknown compression '" + name + "' (allowed: none, zip, piz)");
}

void add_exr_channels(ExrImage& image, const cv::Mat& plane, const std::vector<std::string>& names,
                      ExrType type) {
  SYLVA_CHECK(!plane.empty() && size_t(plane.channels()) == names.size(),
              "add_exr_channels: one name per channel");
  SYLVA_CHECK(plane.depth() == (type == ExrType::Uint ? CV_32S : CV_32F),
              "add_exr_channels: float planes for half/float, int32 for uint");
  if (image.channels.empty()) {
    image.width = plane.cols;
    image.height = plane.rows;
  }
  SYLVA_CHECK(plane.cols == image.width && plane.rows == image.height,
              "add_exr_channels: every plane of the image's size");
  std::vector<cv::Mat> split;
  cv::split(plane, split);
  for (size_t i = 0; i < names.size(); ++i)
    image.channels.push_back({names[i], type, split[i]});
}

void add_exr_colour(ExrImage& image, const cv::Mat& bgra, const std::string& prefix) {
  SYLVA_CHECK(bgra.type() == CV_8UC4, "add_exr_colour: 8-bit BGRA");
  std::array<float, 256> linear{};
  for (int v = 0; v < 256; ++v)
    linear[size_t(v)] = srgb_to_linear(float(v) / 255.0f);
  cv::Mat rgba(bgra.size(), CV_32FC4);
  bgra.forEach<cv::Vec4b>([&](const cv::Vec4b& c, const int* at) {
    const float a = float(c[3]) / 255.0f;
    rgba.at<cv::Vec4f>(at[0], at[1]) = {linear[c[2]] * a, linear[c[1]] * a, linear[c[0]] * a, a};
  });
  add_exr_channels(image, rgba, {prefix + "R", prefix + "G", prefix + "B", prefix + "A"},
                   ExrType::Half);
}

namespace {

// zlib level of ZIP compression: on every buffer of the 100k-leaf sample at 1024² (perf_buffers)
// level 1 writes 10.4 MB in 243 ms, level 4 9.9 MB in 286 ms.
constexpr int kZipLevel = 1;

// OpenEXR compresses blocks of scanlines on its own thread pool (the file's bytes do not
// depend on the thread count); one thread per core.
void start_exr_threads() {
  static std::once_flag once;
  std::call_once(once, [] { Imf::setGlobalThreadCount(int(std::thread::hardware_concurrency())); });
}

// The file's bytes in memory (OpenEXR seeks back to fill in the offset table), reserved once.
class StringStream : public Imf::OStream {
 public:
  explicit StringStream(size_t reserve) : Imf::OStream("memory") { m_bytes.reserve(reserve); }
  void write(const char c[], int n) override {
    if (m_at + size_t(n) > m_bytes.size()) m_bytes.resize(m_at + size_t(n));
    std::memcpy(m_bytes.data() + m_at, c, size_t(n));
    m_at += size_t(n);
  }
  uint64_t tellp() override { return m_at; }
  void seekp(uint64_t pos) override { m_at = size_t(pos); }
  std::string& bytes() { return m_bytes; }

 private:
  std::string m_bytes;
  size_t m_at = 0;
};

Imf::PixelType pixel_type(ExrType t) {
  switch (t) {
    case ExrType::Half:
      return Imf::HALF;
    case ExrType::Uint:
      return Imf::UINT;
    case ExrType::Float:
      break;
  }
  return Imf::FLOAT;
}

Imf::Compression compression(ExrCompression c) {
  switch (c) {
    case ExrCompression::None:
      return Imf::NO_COMPRESSION;
    case ExrCompression::Piz:
      return Imf::PIZ_COMPRESSION;
    case ExrCompression::Zip:
      break;
  }
  return Imf::ZIP_COMPRESSION;
}

// glm (column-major, column vectors) to Imath (row vectors): Imath's x[i][j] is glm's m[i][j].
Imath::M44f imath_matrix(const glm::mat4& m) {
  Imath::M44f r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      r[i][j] = m[i][j];
  return r;
}

Imf::Header make_header(const ExrImage& image) {
  Imf::Header header(image.width, image.height);
  header.compression() = compression(image.compression);
  header.zipCompressionLevel() = kZipLevel;
  for (const ExrChannel& c : image.channels)
    header.channels().insert(c.name, Imf::Channel(pixel_type(c.type)));
  if (image.camera) {
    Imf::addWorldToCamera(header, imath_matrix(image.camera->world_to_camera));
    Imf::addWorldToNDC(header, imath_matrix(image.camera->world_to_ndc));
    header.insert("near", Imf::FloatAttribute(image.camera->near_plane));
    header.insert("far", Imf::FloatAttribute(image.camera->far_plane));
  }
  if (image.dpi > 0.0) Imf::addXDensity(header, float(image.dpi));
  for (const auto& [key, value] : image.strings)
    header.insert(key, Imf::StringAttribute(value));
  return header;
}

// The frame buffer over the channels' planes; half channels are converted into `halves`
// (OpenCV's CV_16F is IEEE binary16, as OpenEXR's half), which must outlive the write.
Imf::FrameBuffer frame_buffer(const ExrImage& image, std::deque<cv::Mat>& halves) {
  Imf::FrameBuffer fb;
  for (const ExrChannel& c : image.channels) {
    SYLVA_CHECK(c.plane.isContinuous(), "write_exr: continuous planes");
    const cv::Mat* plane = &c.plane;
    if (c.type == ExrType::Half) {
      c.plane.convertTo(halves.emplace_back(), CV_16F);
      plane = &halves.back();
    }
    const size_t stride = plane->elemSize();
    fb.insert(c.name, Imf::Slice(pixel_type(c.type), reinterpret_cast<char*>(plane->data), stride,
                                 stride * size_t(image.width)));
  }
  return fb;
}

}  // namespace

void write_exr(const std::string& path, const ExrImage& image) {
  SYLVA_CHECK(image.width > 0 && image.height > 0 && !image.channels.empty(),
              "write_exr: an image with channels");
  for (const ExrChannel& c : image.channels) {
    SYLVA_CHECK(c.plane.cols == image.width && c.plane.rows == image.height,
                "write_exr: every channel of the image's size");
    SYLVA_CHECK(all_finite(c.plane), "write_exr: non-finite values in channel " + c.name);
  }
  start_exr_threads();
  size_t raw = 4096;
  for (const ExrChannel& c : image.channels)
    raw += c.plane.total() * (c.type == ExrType::Half ? 2 : 4);
  StringStream stream(raw + raw / 8);
  try {
    const Imf::Header header = make_header(image);
    std::deque<cv::Mat> halves;
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(frame_buffer(image, halves));
    file.writePixels(image.height);
  } catch (const Iex::BaseExc& e) {
    throw InputError(path, std::string("cannot encode EXR: ") + e.what());
  }
  write_file_atomic(path, stream.bytes());
}

}  // namespace sylva

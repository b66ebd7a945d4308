#include "core/io/gif_writer.h"

#include <gif_lib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "core/error.h"
#include "core/io/atomic_file.h"

namespace sylva {

namespace {

// Pixels handed to the median cut at most: enough for a stable palette, bounded work.
constexpr size_t kPaletteSamples = size_t(1) << 20;

uint32_t key(const uint8_t* bgr) {
  return uint32_t(bgr[2]) << 16 | uint32_t(bgr[1]) << 8 | bgr[0];
}

struct Palette {
  std::vector<GifColorType> colors;
  std::vector<int16_t> index;  // 24-bit RGB key -> palette index, -1 = not looked up yet

  uint8_t lookup(uint32_t k) {
    int16_t& i = index[k];
    if (i < 0) {
      const int r = int(k >> 16), g = int(k >> 8 & 255), b = int(k & 255);
      int best = 0, best_d = 1 << 30;
      for (size_t c = 0; c < colors.size(); ++c) {
        const int dr = r - colors[c].Red, dg = g - colors[c].Green, db = b - colors[c].Blue;
        const int d = dr * dr + dg * dg + db * db;
        if (d < best_d) best_d = d, best = int(c);
      }
      i = int16_t(best);
    }
    return uint8_t(i);
  }
};

// The frames' colours exactly when there are at most 256, in RGB order; else a median cut of
// pixels sampled with an even stride over all frames.
Palette build_palette(const std::vector<cv::Mat>& frames) {
  Palette p;
  p.index.assign(size_t(1) << 24, -1);
  std::vector<uint64_t> seen(size_t(1) << 18, 0);
  size_t distinct = 0;
  for (const cv::Mat& f : frames) {
    for (int y = 0; y < f.rows && distinct <= 256; ++y) {
      const uint8_t* row = f.ptr<uint8_t>(y);
      for (int x = 0; x < f.cols; ++x) {
        const uint32_t k = key(row + 3 * x);
        uint64_t& word = seen[k >> 6];
        if (!(word >> (k & 63) & 1)) word |= uint64_t(1) << (k & 63), ++distinct;
      }
    }
  }
  if (distinct <= 256) {
    for (uint32_t w = 0; w < seen.size(); ++w)
      for (uint32_t b = 0; b < 64; ++b)
        if (seen[w] >> b & 1) {
          const uint32_t k = w << 6 | b;
          p.index[k] = int16_t(p.colors.size());
          p.colors.push_back(
              GifColorType{GifByteType(k >> 16), GifByteType(k >> 8 & 255), GifByteType(k & 255)});
        }
    return p;
  }
  const size_t per_frame = size_t(frames[0].rows) * size_t(frames[0].cols);
  const size_t total = per_frame * frames.size();
  const size_t stride = (total + kPaletteSamples - 1) / kPaletteSamples;
  std::vector<GifByteType> r, g, b;
  for (size_t i = 0; i < total; i += stride) {
    const uint8_t* px = frames[i / per_frame].ptr<uint8_t>() + 3 * (i % per_frame);
    r.push_back(px[2]), g.push_back(px[1]), b.push_back(px[0]);
  }
  int size = 256;
  std::vector<GifByteType> out(r.size());
  std::array<GifColorType, 256> map{};
  if (GifQuantizeBuffer(unsigned(r.size()), 1, &size, r.data(), g.data(), b.data(), out.data(),
                        map.data()) != GIF_OK)
    throw std::runtime_error("GIF palette: median cut failed");
  p.colors.assign(map.begin(), map.begin() + std::clamp(size, 1, 256));
  // The median cut averages its boxes, so a flat white ground would come out 248 grey. An
  // entry most of whose pixels share one exact colour takes that colour.
  std::vector<uint64_t> pairs(r.size());
  for (size_t i = 0; i < r.size(); ++i)
    pairs[i] = uint64_t(out[i]) << 24 | uint32_t(r[i]) << 16 | uint32_t(g[i]) << 8 | b[i];
  std::sort(pairs.begin(), pairs.end());
  for (size_t i = 0; i < pairs.size();) {
    const uint64_t entry = pairs[i] >> 24;
    size_t end = i, best_count = 0;
    uint32_t best = 0;
    while (end < pairs.size() && pairs[end] >> 24 == entry) {
      size_t run = end;
      while (run < pairs.size() && pairs[run] == pairs[end])
        ++run;
      if (run - end > best_count) best_count = run - end, best = uint32_t(pairs[end] & 0xffffff);
      end = run;
    }
    if (entry < p.colors.size() && 2 * best_count > end - i)
      p.colors[entry] = GifColorType{GifByteType(best >> 16), GifByteType(best >> 8 & 255),
                                     GifByteType(best & 255)};
    i = end;
  }
  return p;
}

int put_bytes(GifFileType* gif, const GifByteType* bytes, int n) {
  static_cast<std::string*>(gif->UserData)->append(reinterpret_cast<const char*>(bytes), size_t(n));
  return n;
}

}  // namespace

int gif_delay_centiseconds(double fps) {
  return std::max(2, int(std::lround(100.0 / fps)));
}

GifWriter::GifWriter(std::string path, double fps, cv::Size size, int frames,
                     const std::string& option)
    : m_path(std::move(path)), m_delay(gif_delay_centiseconds(fps)), m_size(size) {
  SYLVA_CHECK(fps >= 1 && fps <= 240, "GIF frame rate out of range");
  if (size.width < 1 || size.height < 1 || size.width > 65535 || size.height > 65535)
    throw InputError(option, "a GIF is at most 65535 pixels on a side");
  const double bytes = double(size.width) * size.height * 3 * std::max(frames, 1);
  if (bytes > double(kMaxBytes))
    throw InputError(option, "a GIF of " + std::to_string(frames) + " frames at " +
                                 std::to_string(size.width) + "x" + std::to_string(size.height) +
                                 " needs " + std::to_string(int(bytes / (1 << 20))) +
                                 " MB of frames in memory (at most 2048); write an .mp4 or a "
                                 "folder of PNGs instead");
  m_frames.reserve(size_t(std::max(frames, 0)));
}

void GifWriter::write(const cv::Mat& frame) {
  SYLVA_CHECK(frame.depth() == CV_8U && frame.size() == m_size &&
                  (frame.channels() == 3 || frame.channels() == 4),
              "GIF frames are 8-bit BGR(A) of the writer's size");
  cv::Mat bgr;
  if (frame.channels() == 4)
    cv::cvtColor(frame, bgr, cv::COLOR_BGRA2BGR);
  else
    bgr = frame.clone();
  m_frames.push_back(std::move(bgr));
}

void GifWriter::finish() {
  if (m_frames.empty()) throw InputError(m_path, "no frame to write");
  Palette palette = build_palette(m_frames);
  // A GIF colour table has a power-of-two size (2 to 256); pad with black.
  const int bits = std::max(1, GifBitSize(int(palette.colors.size())));
  std::vector<GifColorType> table = palette.colors;
  table.resize(size_t(1) << bits, GifColorType{0, 0, 0});
  ColorMapObject* map = GifMakeMapObject(int(table.size()), table.data());
  SYLVA_CHECK(map != nullptr, "GIF colour map");

  std::string bytes;
  int error = 0;
  GifFileType* gif = EGifOpen(&bytes, put_bytes, &error);
  SYLVA_CHECK(gif != nullptr, "GIF encoder");
  bool ok = true;
  EGifSetGifVersion(gif, true);
  ok = ok && EGifPutScreenDesc(gif, m_size.width, m_size.height, 8, 0, map) == GIF_OK;
  // NETSCAPE2.0 application extension: loop forever (count 0).
  const unsigned char loop[3] = {1, 0, 0};
  ok = ok && EGifPutExtensionLeader(gif, APPLICATION_EXT_FUNC_CODE) == GIF_OK &&
       EGifPutExtensionBlock(gif, 11, "NETSCAPE2.0") == GIF_OK &&
       EGifPutExtensionBlock(gif, 3, loop) == GIF_OK && EGifPutExtensionTrailer(gif) == GIF_OK;
  GraphicsControlBlock gcb{};
  gcb.DisposalMode = DISPOSE_DO_NOT;
  gcb.UserInputFlag = false;
  gcb.DelayTime = m_delay;
  gcb.TransparentColor = NO_TRANSPARENT_COLOR;
  GifByteType ext[4];
  const size_t ext_size = EGifGCBToExtension(&gcb, ext);
  std::vector<GifPixelType> line(size_t(m_size.width));
  for (const cv::Mat& f : m_frames) {
    ok = ok && EGifPutExtension(gif, GRAPHICS_EXT_FUNC_CODE, int(ext_size), ext) == GIF_OK &&
         EGifPutImageDesc(gif, 0, 0, m_size.width, m_size.height, false, nullptr) == GIF_OK;
    for (int y = 0; ok && y < m_size.height; ++y) {
      const uint8_t* row = f.ptr<uint8_t>(y);
      for (int x = 0; x < m_size.width; ++x)
        line[size_t(x)] = palette.lookup(key(row + 3 * x));
      ok = EGifPutLine(gif, line.data(), m_size.width) == GIF_OK;
    }
  }
  if (!ok) error = gif->Error;
  int close_error = 0;
  if (EGifCloseFile(gif, &close_error) != GIF_OK && ok) ok = false, error = close_error;
  GifFreeMapObject(map);
  if (!ok) throw InputError(m_path, std::string("cannot encode the GIF: ") + GifErrorString(error));
  write_file_atomic(m_path, bytes);
  m_frames.clear();
}

}  // namespace sylva

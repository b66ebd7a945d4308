// Animated GIFs: read back with giflib, frames keep their count, size, delay and loop; few
// colours come back exactly, gradients within a few levels and a flat ground exactly; same
// frames, same bytes; bad sizes, too many frames and unwritable paths are input errors that
// leave nothing behind.
#include <gif_lib.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/io/gif_writer.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

struct Gif {
  std::vector<cv::Mat> frames;  // 8-bit BGR
  std::vector<int> delays;      // centiseconds
  int colors = 0;               // global colour table size
  bool loops = false;           // NETSCAPE2.0, loop count 0
};

Gif read_gif(const std::string& path) {
  int error = 0;
  GifFileType* gif = DGifOpenFileName(path.c_str(), &error);
  EXPECT_NE(gif, nullptr) << path;
  Gif out;
  if (!gif) return out;
  EXPECT_EQ(DGifSlurp(gif), GIF_OK) << GifErrorString(gif->Error);
  EXPECT_NE(gif->SColorMap, nullptr);
  out.colors = gif->SColorMap ? gif->SColorMap->ColorCount : 0;
  for (int i = 0; i < gif->ImageCount; ++i) {
    const SavedImage& im = gif->SavedImages[i];
    EXPECT_EQ(im.ImageDesc.ColorMap, nullptr) << "frame " << i << " has a local palette";
    const ColorMapObject* map = im.ImageDesc.ColorMap ? im.ImageDesc.ColorMap : gif->SColorMap;
    cv::Mat f(im.ImageDesc.Height, im.ImageDesc.Width, CV_8UC3);
    for (int p = 0; p < f.rows * f.cols; ++p) {
      const GifColorType c = map->Colors[im.RasterBits[p]];
      f.at<cv::Vec3b>(p / f.cols, p % f.cols) = cv::Vec3b(c.Blue, c.Green, c.Red);
    }
    out.frames.push_back(f);
    GraphicsControlBlock gcb{};
    EXPECT_EQ(DGifSavedExtensionToGCB(gif, i, &gcb), GIF_OK);
    out.delays.push_back(gcb.DelayTime);
    for (int e = 0; e + 1 < im.ExtensionBlockCount; ++e) {
      const ExtensionBlock& b = im.ExtensionBlocks[e];
      const ExtensionBlock& next = im.ExtensionBlocks[e + 1];
      if (b.Function == APPLICATION_EXT_FUNC_CODE && b.ByteCount == 11 &&
          std::memcmp(b.Bytes, "NETSCAPE2.0", 11) == 0 && next.ByteCount == 3 &&
          next.Bytes[0] == 1 && next.Bytes[1] == 0 && next.Bytes[2] == 0)
        out.loops = true;
    }
  }
  DGifCloseFile(gif, &error);
  return out;
}

// A white ground with a coloured gradient disc that moves with `t`: thousands of colours.
cv::Mat gradient_frame(int t) {
  cv::Mat f(48, 64, CV_8UC3, cv::Scalar(255, 255, 255));
  for (int y = 0; y < f.rows; ++y)
    for (int x = 0; x < f.cols; ++x) {
      const int dx = x - 28 - 2 * t, dy = y - 24;
      if (dx * dx + dy * dy < 18 * 18)
        f.at<cv::Vec3b>(y, x) = cv::Vec3b(uchar(20 + 3 * x), uchar(90 + 2 * y), uchar(40 + x + y));
    }
  return f;
}

TEST(GifWriter, FewColoursRoundTripExactlyWithDelayAndLoop) {
  const std::string dir = temp_dir("gif-few");
  std::vector<cv::Mat> frames;
  for (int t = 0; t < 3; ++t) {
    cv::Mat f(30, 41, CV_8UC4, cv::Scalar(255, 255, 255, 0));
    cv::rectangle(f, cv::Rect(3 + 5 * t, 4, 10, 12), cv::Scalar(10, 120, 30, 255), -1);
    cv::line(f, cv::Point(0, 29), cv::Point(40, 0), cv::Scalar(0, 0, 0, 255), 1);
    frames.push_back(f);
  }
  GifWriter w(dir + "/few.gif", 30, cv::Size(41, 30), 3);
  for (const cv::Mat& f : frames)
    w.write(f);
  w.finish();
  const Gif back = read_gif(dir + "/few.gif");
  ASSERT_EQ(back.frames.size(), 3u);
  EXPECT_TRUE(back.loops);
  EXPECT_EQ(back.colors, 4);  // white, green, black, padded to a power of two
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back.delays[i], 3);
    cv::Mat bgr;
    cv::cvtColor(frames[i], bgr, cv::COLOR_BGRA2BGR);
    EXPECT_EQ(cv::norm(back.frames[i], bgr, cv::NORM_INF), 0.0) << "frame " << i;
  }
}

TEST(GifWriter, ManyColoursStayCloseAndTheGroundStaysExact) {
  const std::string dir = temp_dir("gif-many");
  GifWriter w(dir + "/many.gif", 12, cv::Size(64, 48), 4);
  for (int t = 0; t < 4; ++t)
    w.write(gradient_frame(t));
  w.finish();
  const Gif back = read_gif(dir + "/many.gif");
  ASSERT_EQ(back.frames.size(), 4u);
  EXPECT_EQ(back.colors, 256);
  for (int t = 0; t < 4; ++t) {
    const cv::Mat want = gradient_frame(t);
    cv::Mat diff;
    cv::absdiff(back.frames[size_t(t)], want, diff);
    EXPECT_LT(cv::mean(diff)[0], 3.0) << "frame " << t;
    EXPECT_LE(cv::norm(diff, cv::NORM_INF), 16.0) << "frame " << t;
    EXPECT_EQ(back.frames[size_t(t)].at<cv::Vec3b>(0, 0), cv::Vec3b(255, 255, 255));
    EXPECT_EQ(back.delays[size_t(t)], 8);  // 100 / 12 = 8.3 hundredths
  }
}

TEST(GifWriter, SameFramesSameBytes) {
  const std::string dir = temp_dir("gif-same");
  for (const char* name : {"/a.gif", "/b.gif"}) {
    GifWriter w(dir + name, 30, cv::Size(64, 48), 2);
    w.write(gradient_frame(0));
    w.write(gradient_frame(3));
    w.finish();
  }
  EXPECT_EQ(read_file(dir + "/a.gif"), read_file(dir + "/b.gif"));
}

TEST(GifWriter, DelayIsWholeHundredthsAtLeastTwo) {
  EXPECT_EQ(gif_delay_centiseconds(1), 100);
  EXPECT_EQ(gif_delay_centiseconds(25), 4);
  EXPECT_EQ(gif_delay_centiseconds(30), 3);
  EXPECT_EQ(gif_delay_centiseconds(50), 2);
  EXPECT_EQ(gif_delay_centiseconds(100), 2);
  EXPECT_EQ(gif_delay_centiseconds(240), 2);
}

TEST(GifWriter, BadSizesTooManyFramesAndUnwritablePathsAreInputErrors) {
  const std::string dir = temp_dir("gif-bad");
  EXPECT_THROW(GifWriter(dir + "/x.gif", 30, cv::Size(65536, 4), 1), InputError);
  EXPECT_THROW(GifWriter(dir + "/x.gif", 30, cv::Size(0, 4), 1), InputError);
  EXPECT_NO_THROW(GifWriter(dir + "/x.gif", 30, cv::Size(65535, 1), 1));
  // 1024 x 1024 x 3 bytes x 683 frames = 2049 MB > 2 GiB; 682 frames fit.
  EXPECT_NO_THROW(GifWriter(dir + "/x.gif", 30, cv::Size(1024, 1024), 682));
  EXPECT_THROW(GifWriter(dir + "/x.gif", 30, cv::Size(1024, 1024), 683), InputError);
  GifWriter empty(dir + "/empty.gif", 30, cv::Size(8, 8), 1);
  EXPECT_THROW(empty.finish(), InputError);
  GifWriter lost(dir + "/missing/x.gif", 30, cv::Size(64, 48), 1);
  lost.write(gradient_frame(0));
  EXPECT_THROW(lost.finish(), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace sylva::test

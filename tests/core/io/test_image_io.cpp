// Image files: PNGs (written through libpng) read back exactly as written, for every bit depth
// and channel count the renderer writes; nothing is left behind when a write fails.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "core/error.h"
#include "core/io/image_io.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

TEST(ImageIo, PngRoundTripsEveryDepthAndChannelCount) {
  const std::string dir = temp_dir("image-io");
  cv::RNG rng(5);
  for (int depth : {CV_8U, CV_16U})
    for (int channels : {1, 3, 4}) {
      // Odd sizes and a view into a larger image (rows not contiguous).
      cv::Mat big(40, 53, CV_MAKETYPE(depth, channels));
      rng.fill(big, cv::RNG::UNIFORM, 0, depth == CV_8U ? 256 : 65536);
      const cv::Mat image = big(cv::Rect(3, 2, 37, 29));
      const std::string path =
          dir + "/x" + std::to_string(depth) + std::to_string(channels) + ".png";
      write_image(path, image);
      const cv::Mat back = cv::imread(path, cv::IMREAD_UNCHANGED);
      ASSERT_EQ(back.type(), image.type()) << path;
      ASSERT_EQ(back.size(), image.size()) << path;
      EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0.0) << path;
      EXPECT_EQ(cv::norm(read_image(path), image, cv::NORM_INF), 0.0) << path;
    }
}

TEST(ImageIo, UnwritablePngIsAnInputErrorAndLeavesNothing) {
  const std::string dir = temp_dir("image-io-bad");
  const cv::Mat image(4, 4, CV_8UC4, cv::Scalar(1, 2, 3, 4));
  EXPECT_THROW(write_image(dir + "/missing/x.png", image), InputError);
  EXPECT_THROW(write_image(dir + "/x.bmp", image), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace sylva::test

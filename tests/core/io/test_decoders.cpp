// The in-process image decoders (libpng, libjpeg): the same pixels as cv::imdecode on real
// textures and on every layout a glTF texture comes in, and a damaged image reported in the
// DecodeReport (error or warning) with nothing printed to stderr.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "core/io/codecs.h"
#include "core/io/codecs_jpeg.h"
#include "core/io/codecs_png.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

const unsigned char* data_of(const std::string& s) {
  return reinterpret_cast<const unsigned char*>(s.data());
}

std::string encode(const std::string& ext, const cv::Mat& image) {
  std::vector<uchar> bytes;
  EXPECT_TRUE(cv::imencode(ext, image, bytes));
  return std::string(bytes.begin(), bytes.end());
}

cv::Mat opencv_decode(const std::string& bytes) {
  return cv::imdecode(cv::Mat(1, int(bytes.size()), CV_8U, const_cast<char*>(bytes.data())),
                      cv::IMREAD_UNCHANGED);
}

void expect_same(const cv::Mat& a, const cv::Mat& b, const std::string& what) {
  ASSERT_EQ(a.type(), b.type()) << what;
  ASSERT_EQ(a.size(), b.size()) << what;
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0) << what;
}

// The embedded images of a .glb: (mime type, bytes).
std::vector<std::pair<std::string, std::string>> glb_images(const std::string& path) {
  const std::string glb = read_file(path);
  uint32_t json_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  const auto j = nlohmann::json::parse(glb.substr(20, json_length));
  const size_t bin = 20 + json_length + 8;
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& image : j.value("images", nlohmann::json::array())) {
    const auto& view = j["bufferViews"][image["bufferView"].get<size_t>()];
    out.emplace_back(
        image.value("mimeType", ""),
        glb.substr(bin + view.value("byteOffset", size_t(0)), view["byteLength"].get<size_t>()));
  }
  return out;
}

TEST(Decoders, SharedTreeTexturesMatchOpenCv) {
  int jpegs = 0, pngs = 0;
  for (const char* name : {"polyhaven_fern_02.glb", "eztree_ash_medium_s5.glb"})
    for (const auto& [mime, bytes] : glb_images(shared_dir() + "/assets/" + name)) {
      DecodeReport report;
      const cv::Mat ours = decode_image(data_of(bytes), bytes.size(), &report);
      expect_same(ours, opencv_decode(bytes), std::string(name) + " " + mime);
      EXPECT_TRUE(report.error.empty() && report.warnings.empty()) << name;
      (mime == "image/jpeg" ? jpegs : pngs)++;
    }
  EXPECT_EQ(jpegs, 5);
  EXPECT_EQ(pngs, 1);
}

TEST(Decoders, JpegLayoutsMatchOpenCv) {
  cv::RNG rng(3);
  cv::Mat colour(37, 53, CV_8UC3), grey(29, 41, CV_8UC1);
  rng.fill(colour, cv::RNG::UNIFORM, 0, 256);
  rng.fill(grey, cv::RNG::UNIFORM, 0, 256);
  for (const cv::Mat& image : {colour, grey}) {
    const std::string bytes = encode(".jpg", image);
    expect_same(decode_jpeg(data_of(bytes), bytes.size()), opencv_decode(bytes),
                std::to_string(image.channels()) + " channels");
  }
}

TEST(Decoders, DamagedJpegIsReportedNotPrinted) {
  cv::Mat image(64, 64, CV_8UC3);
  cv::RNG(4).fill(image, cv::RNG::UNIFORM, 0, 256);
  const std::string bytes = encode(".jpg", image);
  testing::internal::CaptureStderr();
  DecodeReport truncated, garbage;
  const cv::Mat half = decode_jpeg(data_of(bytes), bytes.size() / 2, &truncated);
  const std::string junk = bytes.substr(0, 3) + std::string(200, '\x11');
  const cv::Mat none = decode_jpeg(data_of(junk), junk.size(), &garbage);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(half.size(), image.size());  // libjpeg fills the rest: a warning, not an error
  ASSERT_EQ(truncated.warnings.size(), 1u);
  EXPECT_NE(truncated.warnings[0].find("Premature end of JPEG file"), std::string::npos);
  EXPECT_TRUE(none.empty());
  EXPECT_FALSE(garbage.error.empty());
}

// The offset of the CRC of the first chunk of `type` (after its 4-byte length, type and data).
size_t chunk_crc(const std::string& png, const char* type) {
  const size_t at = png.find(type);
  const auto byte = [&](size_t i) { return size_t(uint8_t(png[at - 4 + i])); };
  return at + 4 + (byte(0) << 24 | byte(1) << 16 | byte(2) << 8 | byte(3));
}

TEST(Decoders, DamagedPngIsReportedNotPrinted) {
  cv::Mat image(32, 32, CV_8UC4);
  cv::RNG(6).fill(image, cv::RNG::UNIFORM, 0, 256);
  std::string png;
  ASSERT_TRUE(encode_png(image, {3, false, false, 300.0}, png));
  std::string bad_idat = png, bad_phys = png;
  bad_idat[chunk_crc(png, "IDAT")] ^= 0x40;  // a critical chunk: an error
  bad_phys[chunk_crc(png, "pHYs")] ^= 0x40;  // an ancillary one: a warning, the chunk dropped
  testing::internal::CaptureStderr();
  DecodeReport idat, phys;
  const cv::Mat none = decode_png(data_of(bad_idat), bad_idat.size(), &idat);
  const cv::Mat kept = decode_png(data_of(bad_phys), bad_phys.size(), &phys);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(idat.error, "IDAT: CRC error");
  expect_same(kept, image, "pHYs CRC");
  ASSERT_EQ(phys.warnings.size(), 1u);
  EXPECT_EQ(phys.warnings[0], "pHYs: CRC error");
}

// A JPEG of more pixels than the bound is decoded at the largest of 1/2, 1/4, 1/8 that fits, with
// a warning; one that even 1/8 does not fit is an error. The 542-byte JPEG the texture fuzz
// harness found declares 20036 x 18757 pixels: at a 2^26 bound it comes out at 1/4, nothing near
// its 375 M pixels allocated.
TEST(Decoders, JpegBeyondThePixelBoundIsDecodedSmallerOrRefused) {
  cv::Mat image(64, 48, CV_8UC3);
  cv::RNG(7).fill(image, cv::RNG::UNIFORM, 0, 256);
  const std::string jpeg = encode(".jpg", image);
  DecodeReport half;
  EXPECT_EQ(decode_jpeg(data_of(jpeg), jpeg.size(), &half, 64 * 48 / 4).size(), cv::Size(24, 32));
  ASSERT_EQ(half.warnings.size(), 1u);
  EXPECT_EQ(half.warnings[0], "48x64 is beyond 768 pixels: decoded at 1/2 of its size");
  DecodeReport eighth;
  EXPECT_EQ(decode_jpeg(data_of(jpeg), jpeg.size(), &eighth, 48).size(), cv::Size(6, 8));
  DecodeReport refused;
  EXPECT_TRUE(decode_jpeg(data_of(jpeg), jpeg.size(), &refused, 47).empty());
  EXPECT_EQ(refused.error, "48x64 is beyond 64 x 47 pixels");

  const std::string found =
      read_file(source_dir() + "/tests/fuzz/regressions/texture/oom-20036x18757-jpeg-in-542-bytes");
  DecodeReport report;
  EXPECT_EQ(decode_jpeg(data_of(found), found.size(), &report, 1ull << 26).size(),
            cv::Size(5009, 4690));
  EXPECT_EQ(report.warnings.size(), 1u);  // libjpeg's "Corrupt JPEG data" came first
}

// A PNG whose header declares more pixels than the bound is refused before its pixels are read.
TEST(Decoders, PngBeyondThePixelBoundIsRefused) {
  std::string png;
  ASSERT_TRUE(encode_png(cv::Mat(4, 4, CV_8UC3, cv::Scalar(1, 2, 3)), kOpenCvPng, png));
  DecodeReport within, beyond;
  EXPECT_FALSE(decode_png(data_of(png), png.size(), &within, 16).empty());
  EXPECT_TRUE(decode_png(data_of(png), png.size(), &beyond, 15).empty());
  EXPECT_EQ(beyond.error, "4x4 is beyond 15 pixels");
}

}  // namespace
}  // namespace sylva::test

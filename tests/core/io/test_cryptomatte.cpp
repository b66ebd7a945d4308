// The Cryptomatte encoder on synthetic id samples: the specification's example ids ("bunny"
// 13851a76, "default" 42c9679f), the exponent clamp, ranks by coverage with ties broken by the
// float id, coverages as shares of the block's samples (background counts as nothing), the
// layer names and the metadata.
#include <gtest/gtest.h>

#include <cstring>

#include "core/io/cryptomatte.h"

namespace sylva {
namespace {

TEST(Cryptomatte, SpecificationExampleIds) {
  EXPECT_EQ(cryptomatte_hex(cryptomatte_id(murmur3_32("bunny"))), "13851a76");
  EXPECT_EQ(cryptomatte_hex(cryptomatte_id(murmur3_32("default"))), "42c9679f");
  // Exponent 0 and 255 are clamped to 1 and 254: no denormal, inf or NaN ids.
  EXPECT_EQ(cryptomatte_hex(cryptomatte_id(0x00000005u)), "00800005");
  EXPECT_EQ(cryptomatte_hex(cryptomatte_id(0xffffffffu)), "ff7fffff");
}

const ExrChannel& channel(const ExrImage& exr, const std::string& name) {
  for (const ExrChannel& c : exr.channels)
    if (c.name == name) return c;
  ADD_FAILURE() << "no channel " << name;
  return exr.channels.front();
}

TEST(Cryptomatte, RanksBlocksBySamples) {
  // Two pixels of 2 x 2 samples: {a, a, b, 0} and {b, c, c, b} (ids 1 = a, 2 = b, 3 = c).
  cv::Mat samples = (cv::Mat_<int32_t>(2, 4) << 1, 1, 2, 3, 2, 0, 3, 2);
  ExrImage exr;
  add_cryptomatte(exr, {"CryptoObject", {"a", "b", "c"}}, samples, 2, 4);
  EXPECT_EQ(exr.width, 2);
  EXPECT_EQ(exr.height, 1);
  ASSERT_EQ(exr.channels.size(), 8u);
  const float a = cryptomatte_id(murmur3_32("a")), b = cryptomatte_id(murmur3_32("b")),
              c = cryptomatte_id(murmur3_32("c"));
  const cv::Mat& r0 = channel(exr, "CryptoObject00.R").plane;
  const cv::Mat& c0 = channel(exr, "CryptoObject00.G").plane;
  const cv::Mat& r1 = channel(exr, "CryptoObject00.B").plane;
  const cv::Mat& c1 = channel(exr, "CryptoObject00.A").plane;
  EXPECT_EQ(r0.at<float>(0, 0), a);
  EXPECT_EQ(c0.at<float>(0, 0), 0.5f);
  EXPECT_EQ(r1.at<float>(0, 0), b);
  EXPECT_EQ(c1.at<float>(0, 0), 0.25f);  // the background sample covers nothing
  EXPECT_EQ(channel(exr, "CryptoObject01.G").plane.at<float>(0, 0), 0.0f);
  // b and c tie at 2 samples: the smaller float id ranks first.
  EXPECT_EQ(r0.at<float>(0, 1), std::min(b, c));
  EXPECT_EQ(r1.at<float>(0, 1), std::max(b, c));
  EXPECT_EQ(c0.at<float>(0, 1) + c1.at<float>(0, 1), 1.0f);
  ASSERT_EQ(exr.strings.size(), 4u);
  EXPECT_EQ(exr.strings[0].second, "CryptoObject");
  EXPECT_EQ(exr.strings[1].second, "MurmurHash3_32");
  EXPECT_EQ(exr.strings[2].second, "uint32_to_float32");
  EXPECT_NE(exr.strings[3].second.find("\"a\":\"" + cryptomatte_hex(a) + "\""), std::string::npos);
  char key[9];
  std::snprintf(key, sizeof key, "%08x", murmur3_32("CryptoObject"));
  EXPECT_EQ(exr.strings[0].first, "cryptomatte/" + std::string(key, 7) + "/name");
}

}  // namespace
}  // namespace sylva

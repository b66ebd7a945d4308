// Cryptomatte in `sylva buffers --format exr` (issue "Buffers and renders for compositors and
// print"), read through OpenImageIO and exrheader: every manifest hash is MurmurHash3_32 of its
// name by this test's own implementation (and the specification's example "default" is
// 42c9679f); the pixels whose rank-0 id is an entry's with coverage > 0.5 are exactly one id's
// pixels of the id buffer, for objects, materials and clusters; together they cover the plant;
// with --ssaa 4 the coverages along edges are fractional and the 6 ranks' sum to the pixel's
// alpha (1 where every sample is covered).
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <regex>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

// MurmurHash3_x86_32, seed 0, written here from the algorithm's description so that the
// program's hash (libmurmurhash) is checked against an independent one.
uint32_t reference_murmur3(const std::string& s) {
  auto rotl = [](uint32_t x, int r) { return (x << r) | (x >> (32 - r)); };
  const uint32_t c1 = 0xcc9e2d51, c2 = 0x1b873593;
  uint32_t h = 0;
  const size_t blocks = s.size() / 4;
  auto mix = [&](uint32_t k) {
    k *= c1;
    k = rotl(k, 15);
    return k * c2;
  };
  for (size_t i = 0; i < blocks; ++i) {
    uint32_t k = 0;
    for (int b = 3; b >= 0; --b)
      k = (k << 8) | uint8_t(s[4 * i + size_t(b)]);
    h ^= mix(k);
    h = rotl(h, 13) * 5 + 0xe6546b64;
  }
  uint32_t tail = 0;
  for (size_t i = s.size() & 3; i > 0; --i)
    tail = (tail << 8) | uint8_t(s[4 * blocks + i - 1]);
  if (s.size() & 3) h ^= mix(tail);
  h ^= uint32_t(s.size());
  h ^= h >> 16;
  h *= 0x85ebca6b;
  h ^= h >> 13;
  h *= 0xc2b2ae35;
  return h ^ (h >> 16);
}

// The specification's uint32_to_float32: the exponent clamped to [1, 254]; as float bits.
uint32_t reference_id_bits(const std::string& name) {
  const uint32_t h = reference_murmur3(name);
  uint32_t exponent = (h >> 23) & 0xff;
  exponent = std::min(std::max(exponent, 1u), 254u);
  return (h & 0x807fffffu) | (exponent << 23);
}

float bits_float(uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

// Layer name -> manifest (name -> hex), from exrheader's listing.
std::map<std::string, nlohmann::json> manifests(const std::string& exr) {
  const RunResult h = run_command("exrheader " + exr);
  EXPECT_EQ(h.status, 0) << h.output;
  std::map<std::string, std::string> names, json;
  const std::regex line(R"re(cryptomatte/([0-9a-f]+)/(name|manifest) \(type string\): "(.*)")re");
  std::istringstream lines(h.output);
  for (std::string l; std::getline(lines, l);) {
    std::smatch m;
    if (!std::regex_search(l, m, line)) continue;
    (m[2] == "name" ? names : json)[m[1]] = m[3];
  }
  std::map<std::string, nlohmann::json> out;
  for (const auto& [key, name] : names)
    out[name] = nlohmann::json::parse(json[key]);
  return out;
}

TEST(Cryptomatte, ReferenceHashMatchesTheSpecificationsExample) {
  EXPECT_EQ(reference_id_bits("default"), 0x42c9679fu);
  EXPECT_EQ(reference_id_bits("bunny"), 0x13851a76u);
}

struct Layer {
  const char* id_kind;
  const char* name;
};

// For each manifest entry: the pixels of rank 0 with coverage > 0.5 are one id's pixels of the
// id buffer, every entry a different id; their union covers the plant (IoU >= 0.98).
void expect_mattes_are_id_buffer(const std::string& scene, const Layer& layer) {
  const std::string dir = temp_dir(std::string("crypto-") + layer.id_kind);
  const RunResult r = run_sylva("buffers " + scene + " --size 160x128 --format exr --id " +
                                layer.id_kind + " --buffers color,depth,id --out-dir " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string exr = dir + "/buffers.exr";
  const std::map<std::string, nlohmann::json> all = manifests(exr);
  ASSERT_EQ(all.size(), 3u);
  ASSERT_TRUE(all.count(layer.name)) << layer.name;
  const cv::Mat rank0 =
      oiio_channels(exr, std::string(layer.name) + "00.R," + layer.name + "00.G", dir);
  const cv::Mat id = oiio_channels(exr, "id", dir), depth = oiio_channels(exr, "Z", dir);
  ASSERT_FALSE(rank0.empty() || id.empty() || depth.empty());
  cv::Mat matted = cv::Mat::zeros(id.size(), CV_8UC1);
  std::map<int32_t, std::string> id_of_entry;
  for (const auto& [name, hex] : all.at(layer.name).items()) {
    const uint32_t bits = reference_id_bits(name);
    char expected[9];
    std::snprintf(expected, sizeof expected, "%08x", bits);
    EXPECT_EQ(hex.get<std::string>(), expected) << name;
    const float want = bits_float(bits);
    int count = 0;
    int32_t the_id = -1;
    bool one_id = true;
    for (int y = 0; y < id.rows; ++y)
      for (int x = 0; x < id.cols; ++x) {
        const cv::Vec2f p = rank0.at<cv::Vec2f>(y, x);
        if (std::memcmp(&p[0], &want, 4) != 0 || p[1] <= 0.5f) continue;
        ++count;
        matted.at<uint8_t>(y, x) = 255;
        const int32_t here = id.at<int32_t>(y, x);
        one_id = one_id && (the_id < 0 || here == the_id);
        the_id = here;
      }
    if (count == 0) continue;  // not in view
    EXPECT_TRUE(one_id) << name;
    EXPECT_EQ(cv::countNonZero(id == the_id), count) << name;
    EXPECT_FALSE(id_of_entry.count(the_id)) << name << " and " << id_of_entry[the_id];
    id_of_entry[the_id] = name;
  }
  const cv::Mat plant = depth > 0.0f;
  const double inter = cv::countNonZero(plant & matted), uni = cv::countNonZero(plant | matted);
  EXPECT_GE(inter / uni, 0.98) << layer.name;
  std::printf("%s: %zu entries, %zu in view, IoU with the plant %.4f\n", layer.name,
              all.at(layer.name).size(), id_of_entry.size(), inter / uni);
}

TEST(Cryptomatte, MattesAreTheIdBufferOnTheSampleTree) {
  for (const Layer& l : {Layer{"object", "CryptoObject"}, Layer{"material", "CryptoMaterial"},
                         Layer{"cluster", "CryptoAsset"}})
    expect_mattes_are_id_buffer(small_tree(), l);
}

TEST(Cryptomatte, MattesAreTheIdBufferOnASharedTree) {
  for (const Layer& l : {Layer{"object", "CryptoObject"}, Layer{"cluster", "CryptoAsset"}})
    expect_mattes_are_id_buffer(shared_dir() + "/assets/eztree_ash_medium_s5.glb", l);
}

// --ssaa 4: fractional coverages along edges; per pixel the 6 ranks' coverages sum to alpha.
TEST(Cryptomatte, SupersampledCoveragesSumToAlpha) {
  const std::string dir = temp_dir("crypto-ssaa");
  const RunResult r = run_sylva("buffers " + small_tree() +
                                " --size 128 --ssaa 4 --background transparent --format exr "
                                "--cryptomatte object,asset --buffers color --out-dir " +
                                dir);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string exr = dir + "/buffers.exr";
  EXPECT_EQ(manifests(exr).size(), 2u);
  const cv::Mat alpha = oiio_channels(exr, "A", dir);
  ASSERT_FALSE(alpha.empty());
  for (const char* layer : {"CryptoObject", "CryptoAsset"}) {
    const std::string l(layer);
    std::string names;
    for (const char* rank : {"00", "01", "02"})
      for (const char* c : {".G", ".A"})
        names += (names.empty() ? "" : ",") + l + rank + c;
    const cv::Mat c = oiio_channels(exr, names, dir);  // the 6 ranks' coverages
    ASSERT_EQ(c.channels(), 6);
    int fractional = 0, full = 0, short_of_alpha = 0;
    double worst_full = 0.0;
    for (int y = 0; y < c.rows; ++y)
      for (int x = 0; x < c.cols; ++x) {
        const cv::Vec6f v = c.at<cv::Vec6f>(y, x);
        const float sum = v[0] + v[1] + v[2] + v[3] + v[4] + v[5], a = alpha.at<float>(y, x);
        fractional += v[0] > 0.0f && v[0] < 1.0f;
        // alpha is the colour's 8-bit coverage (within 0.5 / 255) stored as half
        EXPECT_LE(sum, a + 0.5 / 255 + 1e-3) << layer << " at " << x << "," << y;
        short_of_alpha += sum < a - (0.5 / 255 + 1e-3);  // more than 6 ids in the pixel
        if (a < 1.0f) continue;
        ++full;
        worst_full = std::max(worst_full, double(std::abs(sum - 1.0f)));
      }
    EXPECT_GT(fractional, 100) << layer;
    EXPECT_GT(full, 500) << layer;
    EXPECT_LT(worst_full, 1e-3) << layer;
    EXPECT_LT(short_of_alpha, c.rows * c.cols / 1000) << layer;
    std::printf(
        "%s: %d pixels with fractional rank-0 coverage, %d fully covered (worst |sum - 1| "
        "%.2g), %d with more ids than 6 ranks\n",
        layer, fractional, full, worst_full, short_of_alpha);
  }
}

TEST(Cryptomatte, BadListIsAnError) {
  const std::string dir = temp_dir("crypto-bad");
  expect_input_error("buffers " + small_tree() + " --size 64 --format exr --cryptomatte shape " +
                         "--out-dir " + dir + "/out",
                     "object, material, asset");
}

}  // namespace
}  // namespace sylva::test

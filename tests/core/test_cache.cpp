// The result cache: content keys separate different inputs, entries round-trip, and damaged,
// foreign or truncated files are misses rather than crashes.
#include <gtest/gtest.h>

#include <filesystem>
#include <glm/glm.hpp>

#include "core/cache/content_hash.h"
#include "core/cache/result_cache.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

std::string key_of(const std::vector<glm::vec3>& points, double param) {
  ContentHash h;
  h.add(points);
  h.add(param);
  return h.hex();
}

TEST(ContentHash, SameInputSameKeyAndAnyChangeMovesIt) {
  const std::vector<glm::vec3> a = {{0, 0, 0}, {1, 2, 3}};
  std::vector<glm::vec3> b = a;
  EXPECT_EQ(key_of(a, 0.5), key_of(b, 0.5));
  EXPECT_EQ(key_of(a, 0.5).size(), 32u);
  b[1].z = std::nextafter(3.0f, 4.0f);
  EXPECT_NE(key_of(a, 0.5), key_of(b, 0.5));
  EXPECT_NE(key_of(a, 0.5), key_of(a, std::nextafter(0.5, 1.0)));
  EXPECT_EQ(key_of(a, 0.0), key_of(a, -0.0));  // equal parameters, equal keys
}

TEST(ContentHash, FieldBoundariesCount) {
  // "ab" + "c" and "a" + "bc" are different inputs.
  ContentHash x, y;
  x.add(std::string("ab"));
  x.add(std::string("c"));
  y.add(std::string("a"));
  y.add(std::string("bc"));
  EXPECT_NE(x.hex(), y.hex());
}

TEST(ResultCache, RoundTripAndMisses) {
  const std::string dir = temp_dir("cache") + "/nested/folder";  // created on store
  ResultCache cache(dir);
  EXPECT_FALSE(cache.load("foliage", "k1").has_value());
  std::string payload(1000, '\0');
  for (size_t i = 0; i < payload.size(); ++i)
    payload[i] = char(i * 7);
  ASSERT_TRUE(cache.store("foliage", "k1", payload));
  ASSERT_EQ(cache.load("foliage", "k1").value(), payload);
  EXPECT_FALSE(cache.load("foliage", "k2").has_value());
  EXPECT_FALSE(cache.load("other", "k1").has_value());

  // A file renamed to another key's name is not that key's entry.
  std::filesystem::copy_file(cache.path("foliage", "k1"), cache.path("foliage", "k3"));
  EXPECT_FALSE(cache.load("foliage", "k3").has_value());

  // Truncated or extended entries are misses.
  const std::string bytes = read_file(cache.path("foliage", "k1"));
  write_file(cache.path("foliage", "k1"), bytes.substr(0, bytes.size() - 1));
  EXPECT_FALSE(cache.load("foliage", "k1").has_value());
  write_file(cache.path("foliage", "k1"), bytes + "x");
  EXPECT_FALSE(cache.load("foliage", "k1").has_value());
  write_file(cache.path("foliage", "k1"), "");
  EXPECT_FALSE(cache.load("foliage", "k1").has_value());
}

TEST(ResultCache, UnwritableFolderIsReportedNotThrown) {
  const std::string file = temp_dir("cache-file") + "/plain";
  write_file(file, "x");
  ResultCache cache(file + "/sub");  // a folder under a regular file cannot exist
  std::string why;
  EXPECT_FALSE(cache.store("foliage", "k", "payload", &why));
  EXPECT_FALSE(why.empty());
}

TEST(ByteReader, ShortAndOversizedArraysFail) {
  ByteWriter w;
  w.put(std::vector<float>{1, 2, 3});
  std::string bytes = w.take();
  std::vector<float> v;
  {
    ByteReader r(bytes);
    ASSERT_TRUE(r.get(v));
    EXPECT_EQ(v, (std::vector<float>{1, 2, 3}));
    EXPECT_TRUE(r.done());
  }
  const std::string shorter = bytes.substr(0, bytes.size() - 1);
  ByteReader r2(shorter);
  EXPECT_FALSE(r2.get(v));
  std::string huge = bytes;
  huge[7] = char(0x7f);  // element count ~ 2^62
  ByteReader r3(huge);
  EXPECT_FALSE(r3.get(v));
}

// Found by fuzz_cache under UBSan: an empty array passed a null data() to memcpy.
TEST(ByteReader, EmptyArraysRoundTrip) {
  ByteWriter w;
  w.put(std::vector<float>{});
  w.put(uint32_t(7));
  const std::string bytes = w.take();
  EXPECT_EQ(bytes.size(), sizeof(uint64_t) + sizeof(uint32_t));
  ByteReader r(bytes);
  std::vector<float> v{1, 2};
  ASSERT_TRUE(r.get(v));
  EXPECT_TRUE(v.empty());
  uint32_t after = 0;
  ASSERT_TRUE(r.get(after));
  EXPECT_EQ(after, 7u);
  EXPECT_TRUE(r.done());
}

}  // namespace
}  // namespace sylva::test

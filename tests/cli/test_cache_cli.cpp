// The preprocessing cache seen from the command line: the second render of a scene reads the
// result (and draws the same bytes), --no-cache neither reads nor writes it, and a cache that
// cannot be written only warns.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

size_t files_in(const std::string& dir) {
  size_t n = 0;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  for (const auto& e : fs::directory_iterator(dir))
    n += e.is_regular_file();
  return n;
}

TEST(CacheCli, SecondRenderReadsTheCache) {
  const std::string dir = temp_dir("cache-cli");
  const std::string scene = dir + "/t.glb";
  ASSERT_EQ(run_sylva("sample tree --leaves 800 --seed 2 -o " + scene).status, 0);
  const std::string cache = dir + "/cache";
  const std::string base =
      "render " + scene + " --style expressive --size 96 --grid 32 --cache-dir " + cache + " -o ";
  RunResult a = run_sylva(base + dir + "/a.png");
  ASSERT_EQ(a.status, 0) << a.output;
  EXPECT_EQ(a.output.find("read from the cache"), std::string::npos) << a.output;
  EXPECT_EQ(files_in(cache), 1u);
  RunResult b = run_sylva(base + dir + "/b.png");
  ASSERT_EQ(b.status, 0) << b.output;
  EXPECT_NE(b.output.find("read from the cache"), std::string::npos) << b.output;
  EXPECT_EQ(read_file(dir + "/a.png"), read_file(dir + "/b.png"));

  // Another parameter is another entry.
  ASSERT_EQ(run_sylva(base + dir + "/c.png --ka-min 0.3").status, 0);
  EXPECT_EQ(files_in(cache), 2u);

  // --no-cache recomputes and stores nothing.
  const std::string unused = dir + "/unused";
  RunResult n = run_sylva("render " + scene + " --style expressive --size 96 --grid 32 " +
                          "--no-cache --cache-dir " + unused + " -o " + dir + "/n.png");
  ASSERT_EQ(n.status, 0) << n.output;
  EXPECT_EQ(n.output.find("read from the cache"), std::string::npos);
  EXPECT_FALSE(fs::exists(unused));
  EXPECT_EQ(read_file(dir + "/a.png"), read_file(dir + "/n.png"));

  // The standard style never runs the preprocessing, so it never touches the cache.
  const std::string standard = dir + "/standard-cache";
  ASSERT_EQ(
      run_sylva("render " + scene + " --size 96 --cache-dir " + standard + " -o " + dir + "/s.png")
          .status,
      0);
  EXPECT_FALSE(fs::exists(standard));
}

TEST(CacheCli, UnwritableCacheWarnsAndStillRenders) {
  const std::string dir = temp_dir("cache-cli-bad");
  const std::string scene = dir + "/t.glb";
  ASSERT_EQ(run_sylva("sample tree --leaves 300 -o " + scene).status, 0);
  write_file(dir + "/file", "x");
  RunResult r = run_sylva("render " + scene + " --style expressive --size 64 --grid 24 " +
                          "--cache-dir " + dir + "/file/sub -o " + dir + "/x.png");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("warning: result cache not written"), std::string::npos) << r.output;
  EXPECT_TRUE(file_exists(dir + "/x.png"));
}

}  // namespace
}  // namespace sylva::test

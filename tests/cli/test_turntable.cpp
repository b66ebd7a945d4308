// sylva turntable end to end: PNG frames and MP4, slices equal to the full run byte for
// byte, resume after lost frames, the coherence report, and bad input (exit 2, nothing
// written).
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> listing(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(Turntable, SlicesAndResumeEqualTheFullRun) {
  const std::string dir = temp_dir("turntable");
  const std::string args =
      "turntable " + small_tree() + " --style expressive --frames 6 --size 48 -q ";
  const RunResult full = run_sylva(args + "--report " + dir + "/c.csv -o " + dir + "/full/");
  ASSERT_EQ(full.status, 0) << full.output;
  ASSERT_EQ(listing(dir + "/full").size(), 6u);
  const RunResult slice = run_sylva(args + "--frame-range 2:5 -o " + dir + "/slice");
  ASSERT_EQ(slice.status, 0) << slice.output;
  EXPECT_EQ(listing(dir + "/slice"),
            (std::vector<std::string>{"frame-00002.png", "frame-00003.png", "frame-00004.png"}));
  for (const std::string& name : listing(dir + "/slice"))
    EXPECT_EQ(read_file(dir + "/slice/" + name), read_file(dir + "/full/" + name)) << name;
  // Frames 1 and 4 lost (a killed job): --resume renders only those, with the same bytes.
  const std::string f1 = read_file(dir + "/full/frame-00001.png");
  const std::string f4 = read_file(dir + "/full/frame-00004.png");
  EXPECT_NE(f1, f4);  // the camera turned
  fs::remove(dir + "/full/frame-00001.png");
  fs::remove(dir + "/full/frame-00004.png");
  const RunResult resumed = run_sylva(args + "--resume -o " + dir + "/full/");
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("2 frame(s), 4 kept"), std::string::npos) << resumed.output;
  EXPECT_EQ(read_file(dir + "/full/frame-00001.png"), f1);
  EXPECT_EQ(read_file(dir + "/full/frame-00004.png"), f4);
  // The report: a header and one row per frame; the first has no predecessor.
  const std::string csv = read_file(dir + "/c.csv");
  EXPECT_EQ(count_lines(csv), 7) << csv;
  EXPECT_EQ(csv.rfind("frame,seconds,flicker\n0,", 0), 0u) << csv;
  EXPECT_EQ(csv.find("nan"), std::string::npos);
}

TEST(Turntable, WritesAnMp4) {
  const std::string dir = temp_dir("turntable-mp4");
  const RunResult r = run_sylva("turntable " + small_tree() +
                                " --style toon --frames 5 --size 64 -q -o " + dir + "/t.mp4");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(listing(dir), std::vector<std::string>{"t.mp4"});  // no temporary left
  const RunResult probe = run_sylva(
      "--version >/dev/null && ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=nb_read_frames,width,height -of csv=p=0 " +
      dir + "/t.mp4");
  ASSERT_EQ(probe.status, 0) << probe.output;
  EXPECT_EQ(probe.output, "64,64,5\n");
}

TEST(Turntable, BadInputExitsTwoAndWritesNothing) {
  const std::string dir = temp_dir("turntable-bad");
  const std::string base = "turntable " + small_tree() + " --size 32 ";
  expect_input_error(base + "--frames 0 -o " + dir + "/a/", "--frames");
  expect_input_error(base + "--axis w -o " + dir + "/a/", "--axis");
  expect_input_error(base + "--zoom 0 -o " + dir + "/a/", "--zoom");
  expect_input_error(base + "--degrees 40000 -o " + dir + "/a/", "--degrees");
  expect_input_error(base + "--fps 0 -o " + dir + "/a.mp4", "--fps");
  expect_input_error(base + "--frames 4 --frame-range 3:2 -o " + dir + "/a/", "--frame-range");
  expect_input_error(base + "--frame-range 0:2 -o " + dir + "/a.mp4", "--frame-range");
  expect_input_error(base + "--resume -o " + dir + "/a.mp4", "--resume");
  expect_input_error(base + "-o " + dir + "/a.gif", "--output");
  expect_input_error(base + "--report " + dir + "/r.txt -o " + dir + "/a/", "--report");
  expect_input_error(base + "--style ink --set edges.width=0 -o " + dir + "/a/", "edges.width");
  expect_input_error(base + "-o " + dir + "/missing/deeper/", "--output");
  EXPECT_TRUE(listing(dir).empty());
}

}  // namespace
}  // namespace sylva::test

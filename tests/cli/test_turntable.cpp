// sylva turntable end to end: PNG frames, MP4 and GIF, slices equal to the full run byte for
// byte, resume after lost frames, the coherence report, and bad input (exit 2, nothing
// written).
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

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
  EXPECT_EQ(csv.rfind("frame,seconds,flicker,reprojection_error,line_pop\n0,", 0), 0u) << csv;
  EXPECT_EQ(csv.find("nan"), std::string::npos);
}

// Keyframed blobs (Dudley §5.1): slices and a second job reading the keyframe cache equal the
// full run byte for byte, a keyframe frame equals the per-frame blobs, and the report gains
// the outline jitter.
TEST(Turntable, BlobKeyframesSliceAndCache) {
  const std::string dir = temp_dir("turntable-blobs");
  const std::string args = "turntable " + small_tree() +
                           " --style blobs --frames 9 --degrees 40 --size 64 -q --clusters 6 ";
  const RunResult full =
      run_sylva(args + "--keyframe-every 4 --report " + dir + "/c.csv -o " + dir + "/full/");
  ASSERT_EQ(full.status, 0) << full.output;
  ASSERT_EQ(listing(dir + "/full").size(), 9u);
  const RunResult slice =
      run_sylva(args + "--keyframe-every 4 --frame-range 5:8 --keyframe-cache " + dir +
                "/keys -o " + dir + "/slice");
  ASSERT_EQ(slice.status, 0) << slice.output;
  // Frames 5..7 need keyframes 0..2 (frames 0, 4, 8: the last is the last frame).
  EXPECT_EQ(listing(dir + "/keys"),
            (std::vector<std::string>{"key-00000.txt", "key-00001.txt", "key-00002.txt"}));
  for (const std::string& name : listing(dir + "/slice"))
    EXPECT_EQ(read_file(dir + "/slice/" + name), read_file(dir + "/full/" + name)) << name;
  // A second job over the same cache reads the keys (a stale key would differ: the cache is
  // only trusted for the same signature, checked by the unit tests).
  const std::string key1 = read_file(dir + "/keys/key-00001.txt");
  const RunResult again =
      run_sylva(args + "--keyframe-every 4 --frame-range 4:6 --keyframe-cache " + dir +
                "/keys -o " + dir + "/again");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(read_file(dir + "/keys/key-00001.txt"), key1);
  for (const std::string& name : listing(dir + "/again"))
    EXPECT_EQ(read_file(dir + "/again/" + name), read_file(dir + "/full/" + name)) << name;
  // Keyframe frames use the shrink-wrap of their own raster: frame 4 equals per-frame blobs.
  const RunResult each = run_sylva(args + "--frame-range 4:5 -o " + dir + "/each");
  ASSERT_EQ(each.status, 0) << each.output;
  EXPECT_EQ(read_file(dir + "/each/frame-00004.png"), read_file(dir + "/full/frame-00004.png"));
  // Between keyframes the outlines differ from per-frame ones.
  const RunResult each2 = run_sylva(args + "--frame-range 2:3 -o " + dir + "/each2");
  ASSERT_EQ(each2.status, 0) << each2.output;
  EXPECT_NE(read_file(dir + "/each2/frame-00002.png"), read_file(dir + "/full/frame-00002.png"));
  const std::string csv = read_file(dir + "/c.csv");
  EXPECT_EQ(csv.rfind("frame,seconds,flicker,reprojection_error,line_pop,jitter\n0,", 0), 0u)
      << csv;
  EXPECT_EQ(count_lines(csv), 10) << csv;
  EXPECT_EQ(csv.find("nan"), std::string::npos);
  expect_input_error(args + "--keyframe-every 0 -o " + dir + "/x/", "--keyframe-every");
  expect_input_error(
      "turntable " + small_tree() + " --style toon --frames 4 --keyframe-every 2 -o " + dir + "/y/",
      "--keyframe-every");
  EXPECT_FALSE(fs::exists(dir + "/x"));
}

// The report's coherence with the motion taken out (styles/reprojection.h): a camera that does
// not move gives exactly 0; a turning one a reprojection error well under the plain flicker.
TEST(Turntable, ReportsReprojectionErrorAndLinePop) {
  const std::string dir = temp_dir("turntable-coherence");
  const std::string args = "turntable " + small_tree() + " --style ink --size 128 -q ";
  ASSERT_EQ(run_sylva(args + "--frames 3 --degrees 0 --report " + dir + "/still.csv -o " + dir +
                      "/still/")
                .status,
            0);
  const std::string still = read_file(dir + "/still.csv");
  EXPECT_NE(still.find("\n1,"), std::string::npos);
  for (const std::string row : {"1,", "2,"}) {
    const size_t at = still.find("\n" + row);
    ASSERT_NE(at, std::string::npos) << still;
    const std::string line = still.substr(at + 1, still.find('\n', at + 1) - at - 1);
    EXPECT_TRUE(line.ends_with(",0,0,0")) << line;  // flicker, reprojection, pop
  }
  ASSERT_EQ(run_sylva(args + "--frames 90 --frame-range 0:3 --report " + dir + "/turn.csv -o " +
                      dir + "/turn/")
                .status,
            0);
  std::istringstream rows(read_file(dir + "/turn.csv"));
  std::string line;
  std::getline(rows, line);
  std::getline(rows, line);  // frame 0
  while (std::getline(rows, line)) {
    std::vector<double> v;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');)
      v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 5u) << line;
    EXPECT_GT(v[2], 0.0);   // flicker
    EXPECT_LT(v[3], v[2]);  // the motion taken out
    EXPECT_GE(v[4], 0.0);   // line pop
    EXPECT_LE(v[4], 1.0);
  }
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

// A GIF: every frame, the size, one global palette; its frames match the PNG frames of the
// same turntable within a level or two (the palette has 256 colours).
TEST(Turntable, WritesAGifMatchingThePngFrames) {
  const std::string dir = temp_dir("turntable-gif");
  const std::string args = "turntable " + small_tree() + " --style toon --frames 5 --size 64 -q ";
  const RunResult r = run_sylva(args + "-o " + dir + "/t.gif");
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_EQ(run_sylva(args + "-o " + dir + "/png/").status, 0);
  EXPECT_EQ(listing(dir), (std::vector<std::string>{"png", "t.gif"}));  // no temporary left
  const RunResult probe = run_sylva(
      "--version >/dev/null && ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=nb_read_frames,width,height -of csv=p=0 " +
      dir + "/t.gif && ffmpeg -v error -i " + dir + "/t.gif -vf 'select=eq(n\\,3)' -frames:v 1 " +
      dir + "/f3.png");
  ASSERT_EQ(probe.status, 0) << probe.output;
  EXPECT_EQ(probe.output, "64,64,5\n");
  const cv::Mat gif = cv::imread(dir + "/f3.png", cv::IMREAD_COLOR);
  const cv::Mat png = cv::imread(dir + "/png/frame-00003.png", cv::IMREAD_COLOR);
  ASSERT_EQ(gif.size(), png.size());
  cv::Mat diff;
  cv::absdiff(gif, png, diff);
  EXPECT_LT(cv::mean(diff)[0], 2.0);
  EXPECT_GT(cv::norm(png, cv::imread(dir + "/png/frame-00000.png", cv::IMREAD_COLOR), cv::NORM_L1),
            0.0);  // the frames differ, so frame 3 was picked out
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
  expect_input_error(base + "-o " + dir + "/a.avi", "--output");
  expect_input_error(base + "--frame-range 0:2 -o " + dir + "/a.gif", "--frame-range");
  // 4096 x 4096 x 3 bytes x 50 frames = 2.4 GB of frames: more than a GIF may hold in memory.
  expect_input_error("turntable " + small_tree() + " --size 4096 --frames 50 -o " + dir + "/a.gif",
                     "--output");
  expect_input_error(base + "--report " + dir + "/r.txt -o " + dir + "/a/", "--report");
  expect_input_error(base + "--style ink --set edges.width=0 -o " + dir + "/a/", "edges.width");
  expect_input_error(base + "-o " + dir + "/missing/deeper/", "--output");
  EXPECT_TRUE(listing(dir).empty());
}

}  // namespace
}  // namespace sylva::test

// sylva encode (a frame folder into the video turntable would have written), turntable
// --resume with damaged frames and a killed run's temporary files, --keyframes-only, and
// sylva farm slurm's scripts run as plain bash (SLURM_ARRAY_TASK_ID set by hand): the frames and
// the video equal a one-machine run. The real Slurm runs are in tests/farm.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "cli/farm_scripts.h"
#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

const std::string& frames_24() {  // a one-machine turntable of 24 frames into a folder
  static const std::string dir = [] {
    const std::string d = temp_dir("encode-frames") + "/frames";
    const RunResult r =
        run_sylva("turntable " + small_tree() + " --style toon --frames 24 --size 64 -q -o " + d);
    EXPECT_EQ(r.status, 0) << r.output;
    return d;
  }();
  return dir;
}

TEST(Encode, WritesTheVideoTurntableWouldHave) {
  const std::string dir = temp_dir("encode");
  const std::string tt = "turntable " + small_tree() + " --style toon --frames 24 --size 64 -q ";
  for (const std::string ext : {"gif", "mp4"}) {
    ASSERT_EQ(run_sylva(tt + "--fps 12 -o " + dir + "/direct." + ext).status, 0);
    const RunResult r =
        run_sylva("encode " + frames_24() + " --fps 12 -q -o " + dir + "/encoded." + ext);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("24 frame(s), 64x64, 12 fps"), std::string::npos) << r.output;
    // The same palette rule, or the same encoder fed the same way, over the same pixels.
    EXPECT_EQ(read_file(dir + "/encoded." + ext), read_file(dir + "/direct." + ext)) << ext;
    const std::string frames = decoded_frames(dir + "/encoded." + ext);
    EXPECT_EQ(count_lines(frames), 24) << frames;
    EXPECT_EQ(frames, decoded_frames(dir + "/direct." + ext)) << ext;
  }
  EXPECT_EQ(listing(dir),
            (std::vector<std::string>{"direct.gif", "direct.mp4", "encoded.gif", "encoded.mp4"}));
  // A turntable's MP4 is deterministic: encoded after the render, not interleaved with it.
  ASSERT_EQ(run_sylva(tt + "--fps 12 -o " + dir + "/again.mp4").status, 0);
  EXPECT_EQ(read_file(dir + "/again.mp4"), read_file(dir + "/direct.mp4"));
}

TEST(Encode, RefusesAMissingOrPartialFrameNamingIt) {
  const std::string dir = temp_dir("encode-bad");
  const std::string frames = dir + "/frames";
  fs::copy(frames_24(), frames);
  fs::remove(frames + "/frame-00007.png");
  expect_input_error("encode " + frames + " -o " + dir + "/a.mp4", "frame-00007.png");
  fs::copy_file(frames_24() + "/frame-00007.png", frames + "/frame-00007.png");
  // --frames asks for more frames than there are: the first absent one is named.
  expect_input_error("encode " + frames + " --frames 30 -o " + dir + "/a.mp4", "frame-00024.png");
  const std::string png = read_file(frames + "/frame-00011.png");
  write_file(frames + "/frame-00011.png", png.substr(0, png.size() / 2));
  expect_input_error("encode " + frames + " -o " + dir + "/a.gif", "frame-00011.png");
  EXPECT_NE(run_sylva("encode " + frames + " -o " + dir + "/a.gif").output.find("partial"),
            std::string::npos);
  fs::copy_file(frames_24() + "/frame-00011.png", frames + "/frame-00011.png",
                fs::copy_options::overwrite_existing);
  EXPECT_EQ(run_sylva("encode " + frames + " -q -o " + dir + "/ok.gif").status, 0);
  // Extremes: --fps at both ends and just outside, --frames 1 and 0 (all).
  EXPECT_EQ(run_sylva("encode " + frames + " --fps 1 --frames 1 -q -o " + dir + "/f1.gif").status,
            0);
  EXPECT_EQ(run_sylva("encode " + frames + " --fps 240 -q -o " + dir + "/f240.mp4").status, 0);
  expect_input_error("encode " + frames + " --fps 0.5 -o " + dir + "/a.mp4", "--fps");
  expect_input_error("encode " + frames + " --fps 241 -o " + dir + "/a.mp4", "--fps");
  expect_input_error("encode " + frames + " --frames -1 -o " + dir + "/a.mp4", "--frames");
  expect_input_error("encode " + frames + " --frames 100001 -o " + dir + "/a.mp4", "--frames");
  expect_input_error("encode " + frames + " -o " + dir + "/a.avi", "--output");
  expect_input_error("encode " + frames + " -o " + dir + "/missing/a.mp4", "--output");
  expect_input_error("encode " + dir + "/nowhere -o " + dir + "/a.mp4", "not a folder");
  fs::create_directory(dir + "/empty");
  expect_input_error("encode " + dir + "/empty -o " + dir + "/a.mp4", "no frame-NNNNN.png");
  fs::create_directory(dir + "/exr");
  write_file(dir + "/exr/frame-00000.exr", "x");
  expect_input_error("encode " + dir + "/exr -o " + dir + "/a.mp4", "frame-00000.exr");
  // Frames of two sizes.
  fs::create_directory(dir + "/sizes");
  ASSERT_EQ(
      run_sylva("turntable " + small_tree() + " --frames 2 --size 32 -q -o " + dir + "/sizes/")
          .status,
      0);
  fs::copy_file(frames_24() + "/frame-00001.png", dir + "/sizes/frame-00001.png",
                fs::copy_options::overwrite_existing);
  expect_input_error("encode " + dir + "/sizes -o " + dir + "/a.mp4", "frame 0 is 32x32");
  EXPECT_EQ(listing(dir), (std::vector<std::string>{"empty", "exr", "f1.gif", "f240.mp4", "frames",
                                                    "ok.gif", "sizes"}));
}

// --resume renders again a frame that is damaged (a partial copy) and removes the temporary
// file a killed run left; the folder ends byte-identical to an uninterrupted run.
TEST(Encode, ResumeRepairsDamagedFramesAndRemovesStaleTemporaries) {
  const std::string dir = temp_dir("resume-damaged") + "/frames";
  fs::copy(frames_24(), dir);
  const std::string f5 = read_file(dir + "/frame-00005.png");
  write_file(dir + "/frame-00005.png", f5.substr(0, f5.size() - 20));
  write_file(dir + "/.frame-00009.png.tmpAbC123", "half a frame");
  write_file(dir + "/.frame-00030.png.tmpAbC123", "not this run's");  // outside the range
  const RunResult r = run_sylva("turntable " + small_tree() +
                                " --style toon --frames 24 --size 64 --frame-range 0:24 "
                                "--resume -o " +
                                dir);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("1 frame(s), 23 kept"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("frame 5 in the output folder is damaged"), std::string::npos);
  EXPECT_EQ(read_file(dir + "/frame-00005.png"), f5);
  EXPECT_FALSE(file_exists(dir + "/.frame-00009.png.tmpAbC123"));
  EXPECT_TRUE(file_exists(dir + "/.frame-00030.png.tmpAbC123"));
  for (const std::string& name : listing(frames_24()))
    EXPECT_EQ(read_file(dir + "/" + name), read_file(frames_24() + "/" + name)) << name;
}

TEST(FarmScripts, SplitCoversEveryFrameOnceInEvenChunks) {
  for (int frames : {1, 7, 24, 100000})
    for (int tasks : {1, 2, 3, 7, frames}) {
      if (tasks > frames) continue;
      const std::vector<FrameRange> chunks = cli::split_frames(frames, tasks);
      ASSERT_EQ(int(chunks.size()), tasks);
      int next = 0, smallest = frames, largest = 0;
      for (const FrameRange& c : chunks) {
        EXPECT_EQ(c.begin, next);
        next = c.end;
        smallest = std::min(smallest, c.end - c.begin);
        largest = std::max(largest, c.end - c.begin);
      }
      EXPECT_EQ(next, frames);
      EXPECT_LE(largest - smallest, 1);
      EXPECT_GE(smallest, 1);
    }
}

TEST(FarmScripts, ShellQuotingSurvivesBash) {
  for (const std::string text : {"plain", "two words", "it's", "'$HOME' \"x\" `y` \\ ;|&"}) {
    const RunResult r = run_command("printf %s " + cli::shell_quote(text));
    EXPECT_EQ(r.output, text);
  }
}

// The scripts of `farm slurm` run as plain bash, task by task, then the encode: the frames
// equal a one-machine turntable's and the MP4 decodes to the same frames.
TEST(FarmScripts, RunAsPlainBashTheyEqualAOneMachineRun) {
  const std::string dir = temp_dir("farm-bash");
  const RunResult w =
      run_sylva("farm slurm " + small_tree() +
                " --style toon --frames 24 --size 64 --tasks 5 --max-running 2 --partition debug "
                "--time 0:10:00 --mem 1G --cpus-per-task 1 -o " +
                dir + "/t.mp4");
  ASSERT_EQ(w.status, 0) << w.output;
  EXPECT_NE(w.output.find("submit with: bash"), std::string::npos) << w.output;
  const std::string job = dir + "/t.farm";
  EXPECT_EQ(listing(job), (std::vector<std::string>{"encode.sbatch", "frames", "logs",
                                                    "render.sbatch", "submit.sh"}));
  const std::string render = read_file(job + "/render.sbatch");
  for (const char* line :
       {"#SBATCH --array=0-4%2\n", "#SBATCH --partition=debug\n", "#SBATCH --time=0:10:00\n",
        "#SBATCH --mem=1G\n", "#SBATCH --cpus-per-task=1\n", "  4) range=20:24 ;;\n"})
    EXPECT_NE(render.find(line), std::string::npos) << line << render;
  EXPECT_NE(read_file(job + "/submit.sh").find("afterok"), std::string::npos);
  for (int task = 4; task >= 0; --task) {  // any order
    const RunResult t = run_command("cd / && SLURM_ARRAY_TASK_ID=" + std::to_string(task) +
                                    " bash " + job + "/render.sbatch");
    ASSERT_EQ(t.status, 0) << t.output;
  }
  EXPECT_NE(run_command("SLURM_ARRAY_TASK_ID=5 bash " + job + "/render.sbatch").status, 0);
  ASSERT_EQ(run_command("cd / && bash " + job + "/encode.sbatch").status, 0);
  for (const std::string& name : listing(frames_24()))
    EXPECT_EQ(read_file(job + "/frames/" + name), read_file(frames_24() + "/" + name)) << name;
  ASSERT_EQ(run_sylva("encode " + frames_24() + " -q -o " + dir + "/one.mp4").status, 0);
  EXPECT_EQ(decoded_frames(dir + "/t.mp4"), decoded_frames(dir + "/one.mp4"));
}

// Keyframed blobs: keys.sbatch fills the cache (each keyframe once), the render tasks read it.
TEST(FarmScripts, KeyframedBlobsFillTheCacheFirst) {
  const std::string dir = temp_dir("farm-keys");
  const std::string tt = small_tree() + " --style blobs --keyframe-every 3 --frames 12 --size 48";
  ASSERT_EQ(run_sylva("turntable " + tt + " -q -o " + dir + "/one/").status, 0);
  ASSERT_EQ(run_sylva("farm slurm " + tt + " --tasks 3 -o " + dir + "/farm/").status, 0);
  const std::string job = dir + "/farm.farm";
  EXPECT_EQ(listing(job),
            (std::vector<std::string>{"keys.sbatch", "logs", "render.sbatch", "submit.sh"}));
  EXPECT_LT(read_file(job + "/submit.sh").find("keys.sbatch"),
            read_file(job + "/submit.sh").find("render.sbatch"));
  int shrink_wrapped = 0;
  for (int task = 0; task < 3; ++task) {
    const RunResult k = run_command("SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash " + job +
                                    "/keys.sbatch");
    ASSERT_EQ(k.status, 0) << k.output;
    const size_t at = k.output.find("keyframe(s): ");
    ASSERT_NE(at, std::string::npos) << k.output;
    shrink_wrapped += std::stoi(k.output.substr(at + 13));
  }
  EXPECT_EQ(shrink_wrapped, 5);  // keyframes 0, 3, 6, 9, 12: each once
  EXPECT_EQ(listing(job + "/keys").size(), 5u);
  for (int task = 0; task < 3; ++task)
    ASSERT_EQ(run_command("SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash " + job +
                          "/render.sbatch")
                  .status,
              0);
  for (const std::string& name : listing(dir + "/one"))
    EXPECT_EQ(read_file(dir + "/farm/" + name), read_file(dir + "/one/" + name)) << name;
}

TEST(FarmScripts, BadInputExitsTwoAndWritesNothing) {
  const std::string dir = temp_dir("farm-bad");
  const std::string base = "farm slurm " + small_tree() + " --frames 8 --size 32 ";
  const std::string out = " -o " + dir + "/t.mp4";
  expect_input_error(base + "--tasks 0" + out, "--tasks");
  expect_input_error(base + "--tasks 9" + out, "--tasks");
  expect_input_error(base + "--tasks 2 --max-running -1" + out, "--max-running");
  expect_input_error(base + "--tasks 2 --cpus-per-task -1" + out, "--cpus-per-task");
  expect_input_error(base + "--tasks 2 --cpus-per-task 4097" + out, "--cpus-per-task");
  expect_input_error(base + "--tasks 2 --partition 'a b'" + out, "--partition");
  expect_input_error(base + "--tasks 2 --time soon" + out, "--time");
  expect_input_error(base + "--tasks 2 --mem 4X" + out, "--mem");
  expect_input_error(base + "--tasks 2 --frame-range 0:4" + out, "--frame-range");
  expect_input_error(base + "--tasks 2 --resume" + out, "--resume");
  expect_input_error(base + "--tasks 2 --report " + dir + "/r.csv" + out, "--report");
  expect_input_error(base + "--tasks 2 --fps 0" + out, "--fps");
  expect_input_error(base + "--tasks 2 -o " + dir + "/t.avi", "--output");
  expect_input_error(base + "--tasks 2 -o " + dir + "/missing/t.mp4", "--output");
  expect_input_error("farm slurm " + dir + "/none.glb --tasks 1 -o " + dir + "/t.mp4", "none.glb");
  write_file(dir + "/file", "a file, not a folder");
  expect_input_error(base + "--tasks 2 --job-dir " + dir + "/file/job" + out, "--job-dir");
  expect_input_error("farm " + small_tree(), "subcommand");
  EXPECT_EQ(listing(dir), std::vector<std::string>{"file"});
  // Both ends of --tasks are accepted.
  EXPECT_EQ(run_sylva(base + "--tasks 1 -o " + dir + "/a/").status, 0);
  EXPECT_EQ(run_sylva(base + "--tasks 8 -o " + dir + "/b/").status, 0);
}

}  // namespace
}  // namespace sylva::test

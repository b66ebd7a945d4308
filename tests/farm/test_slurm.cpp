// sylva farm slurm on a real Slurm: a single-node cluster (tests/farm/slurm_up.sh: munged,
// slurmctld and slurmd as root, everything in a temporary folder, stopped by their pids at the
// end, also when a test fails). Each submitted turntable's frames must equal a one-machine run
// byte for byte and its video must decode (ffmpeg) to the same frames; a task requeued in the
// middle of its chunk continues from the frames it had written.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

// The cluster of this test program: started once, stopped at exit.
class Cluster {
 public:
  Cluster() : m_dir(temp_dir("slurm")) {
    const RunResult up = run_command(source_dir() + "/tests/farm/slurm_up.sh " + m_dir);
    m_up = up.status == 0;
    m_log = up.output;
    if (m_up) setenv("SLURM_CONF", (m_dir + "/slurm.conf").c_str(), 1);
  }
  ~Cluster() { run_command(source_dir() + "/tests/farm/slurm_down.sh " + m_dir); }
  bool up() const { return m_up; }
  const std::string& log() const { return m_log; }

 private:
  std::string m_dir, m_log;
  bool m_up = false;
};

Cluster& cluster() {
  static Cluster c;
  return c;
}

bool wait_for(const std::string& path, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (fs::exists(path)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// "render job 12" in submit.sh's output → "12".
std::string job_id(const std::string& output, const std::string& name) {
  const std::string key = name + " job ";
  const size_t at = output.find(key);
  if (at == std::string::npos) return "";
  return output.substr(at + key.size(), output.find('\n', at) - at - key.size());
}

void expect_same_frames(const std::string& farm, const std::string& one) {
  int count = 0;
  for (const auto& e : fs::directory_iterator(one)) {
    const std::string name = e.path().filename().string();
    EXPECT_EQ(read_file(farm + "/" + name), read_file(one + "/" + name)) << name;
    ++count;
  }
  int farm_count = 0;
  for (const auto& e : fs::directory_iterator(farm))
    farm_count += e.path().filename().string().starts_with("frame-") ? 1 : 0;
  EXPECT_EQ(farm_count, count);
}

class Slurm : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(cluster().up()) << cluster().log(); }
};

TEST_F(Slurm, SubmittedTurntableEqualsAOneMachineRun) {
  const std::string dir = temp_dir("slurm-mp4");
  const std::string tt = small_tree() + " --style toon --frames 24 --size 96";
  ASSERT_EQ(run_sylva("turntable " + tt + " -q -o " + dir + "/one/").status, 0);
  ASSERT_EQ(run_sylva("turntable " + tt + " -q -o " + dir + "/one.mp4").status, 0);
  const RunResult s = run_sylva("farm slurm " + tt + " --tasks 4 --submit -o " + dir + "/t.mp4");
  ASSERT_EQ(s.status, 0) << s.output;
  EXPECT_NE(job_id(s.output, "render"), "") << s.output;
  EXPECT_NE(job_id(s.output, "encode"), "") << s.output;
  ASSERT_TRUE(wait_for(dir + "/t.mp4", 240)) << read_file(dir + "/t.farm/logs/render-0.log");
  expect_same_frames(dir + "/t.farm/frames", dir + "/one");
  EXPECT_EQ(decoded_frames(dir + "/t.mp4"), decoded_frames(dir + "/one.mp4"));
  for (int task = 0; task < 4; ++task)
    EXPECT_NE(
        read_file(dir + "/t.farm/logs/render-" + std::to_string(task) + ".log").find("6 frame(s)"),
        std::string::npos);
}

// One task requeued while it renders its chunk (Slurm kills it and runs it again) continues with
// --resume from the frames it wrote; a partial frame and a killed run's temporary file left in
// frames/ beforehand are rendered again. The result equals the one-machine run.
TEST_F(Slurm, ARequeuedTaskAndAPartialFrameLoseNothing) {
  const std::string dir = temp_dir("slurm-requeue");
  const std::string tt = small_tree() + " --style pen --frames 24 --size 512";
  ASSERT_EQ(run_sylva("turntable " + tt + " -q -o " + dir + "/one/").status, 0);
  ASSERT_EQ(
      run_sylva("farm slurm " + tt + " --tasks 2 --max-running 1 -o " + dir + "/t.mp4").status, 0);
  const std::string frames = dir + "/t.farm/frames";
  const std::string f20 = read_file(dir + "/one/frame-00020.png");
  write_file(frames + "/frame-00020.png", f20.substr(0, f20.size() / 3));
  write_file(frames + "/.frame-00021.png.tmpXyZ123", "killed mid-write");
  const RunResult s = run_command("bash " + dir + "/t.farm/submit.sh");
  ASSERT_EQ(s.status, 0) << s.output;
  const std::string task0 = job_id(s.output, "render") + "_0";
  ASSERT_TRUE(wait_for(frames + "/frame-00002.png", 120));
  const RunResult rq = run_command("scontrol requeue " + task0 +
                                   " && sleep 0.5 && "
                                   "scontrol update JobId=" +
                                   task0 + " StartTime=now");
  ASSERT_EQ(rq.status, 0) << rq.output;
  ASSERT_TRUE(wait_for(dir + "/t.mp4", 240)) << read_file(dir + "/t.farm/logs/render-0.log");
  const std::string log0 = read_file(dir + "/t.farm/logs/render-0.log");
  EXPECT_NE(log0.find("DUE TO JOB REQUEUE"), std::string::npos) << log0;
  EXPECT_NE(log0.find(" kept, "), std::string::npos) << log0;  // the second run kept frames
  const std::string log1 = read_file(dir + "/t.farm/logs/render-1.log");
  EXPECT_NE(log1.find("frame 20 in the output folder is damaged"), std::string::npos) << log1;
  EXPECT_FALSE(file_exists(frames + "/.frame-00021.png.tmpXyZ123"));
  expect_same_frames(frames, dir + "/one");
}

// Keyframed blobs: the keys array fills the keyframe cache, then the render array reads it.
TEST_F(Slurm, KeyframedBlobsRunTheKeysJobFirst) {
  const std::string dir = temp_dir("slurm-blobs");
  const std::string tt = small_tree() + " --style blobs --keyframe-every 4 --frames 24 --size 96";
  ASSERT_EQ(run_sylva("turntable " + tt + " -q -o " + dir + "/one/").status, 0);
  ASSERT_EQ(run_sylva("turntable " + tt + " -q -o " + dir + "/one.gif").status, 0);
  const RunResult s = run_sylva("farm slurm " + tt + " --tasks 3 --submit -o " + dir + "/t.gif");
  ASSERT_EQ(s.status, 0) << s.output;
  EXPECT_NE(job_id(s.output, "keys"), "") << s.output;
  ASSERT_TRUE(wait_for(dir + "/t.gif", 240)) << read_file(dir + "/t.farm/logs/render-0.log");
  expect_same_frames(dir + "/t.farm/frames", dir + "/one");
  EXPECT_EQ(read_file(dir + "/t.gif"), read_file(dir + "/one.gif"));
  int keys = 0;
  for (const auto& e : fs::directory_iterator(dir + "/t.farm/keys"))
    keys += e.path().extension() == ".txt" ? 1 : 0;
  EXPECT_EQ(keys, 7);  // keyframes 0, 4, ..., 24
  for (int task = 0; task < 3; ++task) {
    const std::string log = read_file(dir + "/t.farm/logs/keys-" + std::to_string(task) + ".log");
    EXPECT_NE(log.find("shrink-wrapped"), std::string::npos) << log;
  }
}

}  // namespace
}  // namespace sylva::test

// Faults that must lose nothing: a full disk while writing every kind of output (a small tmpfs,
// mounted by the test as root) is one error line, exit 2, and nothing half-written or temporary
// left; SIGINT and SIGTERM during long commands exit 130 / 143 with nothing temporary left, and
// a turntable resumed after either ends byte-identical to an uninterrupted run.
#include <gtest/gtest.h>
#include <sys/mount.h>

#include <csignal>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

// A 64 KiB tmpfs with a filler file leaving about 4 KiB free; unmounted when destroyed.
class FullDisk {
 public:
  FullDisk() : m_dir(temp_dir("full-disk") + "/mnt") {
    fs::create_directory(m_dir);
    m_mounted = mount("tmpfs", m_dir.c_str(), "tmpfs", 0, "size=64k") == 0;
    if (m_mounted) write_file(m_dir + "/.filler", std::string(60 * 1024, 'x'));
  }
  ~FullDisk() {
    if (m_mounted) umount(m_dir.c_str());
  }
  FullDisk(const FullDisk&) = delete;
  FullDisk& operator=(const FullDisk&) = delete;
  bool mounted() const { return m_mounted; }
  const std::string& dir() const { return m_dir; }
  std::vector<std::string> left() const {  // everything but the filler
    std::vector<std::string> names = listing(m_dir);
    std::erase(names, ".filler");
    return names;
  }

 private:
  std::string m_dir;
  bool m_mounted = false;
};

void expect_disk_full(const std::string& args) {
  const RunResult r = run_sylva(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
  // One error line, the last (a command's information lines, e.g. the foliage report, may come
  // before it).
  int errors = 0;
  for (size_t at = r.output.find("sylva: error: "); at != std::string::npos;
       at = r.output.find("sylva: error: ", at + 1))
    errors += at == 0 || r.output[at - 1] == '\n' ? 1 : 0;
  EXPECT_EQ(errors, 1) << args << "\n" << r.output;
  const size_t last = r.output.rfind('\n', r.output.size() - 2);
  EXPECT_EQ(r.output.compare(last == std::string::npos ? 0 : last + 1, 14, "sylva: error: "), 0)
      << r.output;
  EXPECT_TRUE(r.output.find("No space left on device") != std::string::npos ||
              r.output.find("incomplete") != std::string::npos)
      << r.output;
}

TEST(Faults, AFullDiskLeavesNothingHalfWritten) {
  FullDisk disk;
  ASSERT_TRUE(disk.mounted()) << "mounting a tmpfs needs root";
  const std::string tree = small_tree(), out = disk.dir();
  const std::vector<std::string> commands = {
      "render " + tree + " --size 512 -o " + out + "/r.png",
      "render " + tree + " --size 512 -o " + out + "/r.exr",
      "render " + tree + " --size 512 -o " + out + "/r.tiff",
      "render " + tree + " --style ink --size 512 -o " + out + "/r.svg",
      "render " + tree + " --style pen --size 512 -o " + out + "/r.pdf",
      "buffers " + tree + " --size 256 --out-dir " + out + "/buffers",
      "buffers " + tree + " --size 256 --format exr --out-dir " + out + "/exr",
      "turntable " + tree + " --frames 6 --size 128 -q -o " + out + "/t.mp4",
      "turntable " + tree + " --frames 6 --size 128 -q -o " + out + "/t.gif",
      "bake " + tree + " -o " + out + "/b.glb",
      "sample tree --leaves 2000 -o " + out + "/s.glb",
      "compare " + tree + " --size 128 -q -o " + out + "/c.png",
  };
  for (const std::string& c : commands) {
    expect_disk_full(c);
    EXPECT_EQ(disk.left(), std::vector<std::string>{}) << c;
  }
}

// A frame folder on a disk that fills: the frames written are whole, no temporary file is left,
// and a --resume elsewhere completes a folder byte-identical to an uninterrupted run.
TEST(Faults, FramesCutShortByAFullDiskResumeIdentically) {
  FullDisk disk;
  ASSERT_TRUE(disk.mounted()) << "mounting a tmpfs needs root";
  const std::string tt = "turntable " + small_tree() + " --style toon --frames 12 --size 96 -q ";
  const std::string dir = temp_dir("full-disk-frames");
  ASSERT_EQ(run_sylva(tt + "-o " + dir + "/one/").status, 0);
  fs::remove(disk.dir() + "/.filler");
  write_file(disk.dir() + "/.filler", std::string(40 * 1024, 'x'));
  expect_disk_full(tt + "-o " + disk.dir() + "/frames/");
  const std::vector<std::string> kept = listing(disk.dir() + "/frames");
  EXPECT_GT(kept.size(), 0u);
  EXPECT_LT(kept.size(), 12u);
  for (const std::string& name : kept) {
    EXPECT_FALSE(name.starts_with(".")) << name;  // no temporary file
    EXPECT_EQ(read_file(disk.dir() + "/frames/" + name), read_file(dir + "/one/" + name)) << name;
  }
  fs::copy(disk.dir() + "/frames", dir + "/resumed");
  const RunResult r = run_sylva(tt + "--resume -o " + dir + "/resumed/");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(listing(dir + "/resumed"), listing(dir + "/one"));
  for (const std::string& name : listing(dir + "/one"))
    EXPECT_EQ(read_file(dir + "/resumed/" + name), read_file(dir + "/one/" + name)) << name;
}

// `sylva encode` onto a full disk: FFmpeg's own complaint (it finds no index in the cut MP4)
// comes out inside the one error line, not as a line of its own, and no temporary is left.
TEST(Faults, AnMp4OnAFullDiskCarriesFfmpegsReasonInTheOneLine) {
  FullDisk disk;
  ASSERT_TRUE(disk.mounted()) << "mounting a tmpfs needs root";
  const std::string frames = temp_dir("full-disk-encode") + "/frames/";
  ASSERT_EQ(
      run_sylva("turntable " + small_tree() + " --frames 6 --size 128 -q -o " + frames).status, 0);
  const RunResult r = run_sylva("encode " + frames + " -q -o " + disk.dir() + "/t.mp4");
  expect_disk_full("encode " + frames + " -q -o " + disk.dir() + "/t.mp4");
  EXPECT_NE(r.output.find("; FFmpeg: [mov,mp4"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("\n["), std::string::npos) << r.output;
  EXPECT_EQ(disk.left(), std::vector<std::string>{});
}

// Runs `sylva ARGS` in the background, sends `signal` once its output holds `marker` (or, when
// the marker is empty, once the process has installed its SIGINT and SIGTERM handlers: bits 1
// and 14 of SigCgt in /proc/PID/status), and returns its exit status and output.
RunResult run_and_signal(const std::string& args, const std::string& marker, int signal) {
  const std::string log = temp_dir("signal-log") + "/log";
  const std::string ready = marker.empty()
                                ? "m=$(awk '/SigCgt/ {print $2}' /proc/$pid/status 2>/dev/null); "
                                  "[ $(( 0x${m:-0} & 0x4002 )) -eq $(( 0x4002 )) ]"
                                : "grep -q '" + marker + "' " + log + " 2>/dev/null";
  const std::string wait =
      "i=0; while ! { " + ready + "; } && [ $i -lt 2400 ]; do sleep 0.025; i=$((i+1)); done";
  const RunResult r = run_sylva("--version >/dev/null; " + sylva_binary() + " " + args + " > " +
                                log + " 2>&1 & pid=$!; " + wait + "; kill -" +
                                std::to_string(signal) + " $pid; wait $pid; echo status=$?");
  RunResult out;
  out.output = read_file(log);
  const size_t at = r.output.rfind("status=");
  out.status = at == std::string::npos ? -1 : std::stoi(r.output.substr(at + 7));
  return out;
}

void expect_stopped(const RunResult& r, int signal) {
  EXPECT_EQ(r.status, 128 + signal) << r.output;
  const std::string name = signal == SIGINT ? "SIGINT" : "SIGTERM";
  EXPECT_NE(r.output.find("sylva: interrupted by " + name), std::string::npos) << r.output;
}

TEST(Faults, SignalsStopATurntableThatResumesIdentically) {
  const std::string dir = temp_dir("signals-turntable");
  const std::string tt = "turntable " + small_tree() + " --style toon --frames 40 --size 256 ";
  ASSERT_EQ(run_sylva(tt + "-q -o " + dir + "/one/").status, 0);
  for (int signal : {SIGINT, SIGTERM}) {
    const std::string frames = dir + "/frames-" + std::to_string(signal);
    expect_stopped(run_and_signal(tt + "-o " + frames + "/", "turntable  3/", signal), signal);
    const std::vector<std::string> kept = listing(frames);
    EXPECT_GE(kept.size(), 3u);
    EXPECT_LT(kept.size(), 40u);
    for (const std::string& name : kept)
      EXPECT_FALSE(name.starts_with(".")) << name;
    ASSERT_EQ(run_sylva(tt + "-q --resume -o " + frames + "/").status, 0);
    EXPECT_EQ(listing(frames), listing(dir + "/one"));
    for (const std::string& name : listing(dir + "/one"))
      EXPECT_EQ(read_file(frames + "/" + name), read_file(dir + "/one/" + name)) << name;
    // An MP4 stopped half-way leaves nothing: neither the video nor its frames' folder.
    fs::create_directory(dir + "/video");
    expect_stopped(run_and_signal(tt + "-o " + dir + "/video/t.mp4", "turntable  3/", signal),
                   signal);
    EXPECT_EQ(listing(dir + "/video"), std::vector<std::string>{});
  }
}

TEST(Faults, SignalsStopRenderCompareBakeAndTradeoffLeavingNothing) {
  const std::string big = sampled_scene("faults-big", "tree --leaves 60000 --seed 2");
  const std::string dir = temp_dir("signals");
  struct Case {
    std::string args, marker;
  };
  const std::vector<Case> cases = {
      {"render " + big + " --style pen --size 2048 -o " + dir + "/r.png", "foliage illumination"},
      {"compare " + small_tree() + " --size 384 -o " + dir + "/c.png", "compare  2/"},
      {"bake " + big + " --no-cache -o " + dir + "/b.glb", ""},  // stopped while it loads
      {"tradeoff " + small_tree() + " --study foliage -o " + dir + "/t.csv --plot " + dir +
           "/t.png",
       "foliage study  2/"},
  };
  for (int signal : {SIGINT, SIGTERM})
    for (const Case& c : cases) {
      expect_stopped(run_and_signal(c.args, c.marker, signal), signal);
      EXPECT_EQ(listing(dir), std::vector<std::string>{}) << c.args;
    }
}

TEST(Faults, AnOutputThatIsAFolderIsOneLine) {
  const std::string dir = temp_dir("output-folder");
  fs::create_directory(dir + "/r.png");
  expect_input_error("render " + small_tree() + " --size 64 -o " + dir + "/r.png", "r.png");
  fs::create_directory(dir + "/t.gif");
  // A folder named t.gif is a frame folder (documented), so the turntable writes into it.
  EXPECT_EQ(run_sylva("turntable " + small_tree() + " --frames 2 --size 32 -q -o " + dir + "/t.gif")
                .status,
            0);
  EXPECT_TRUE(file_exists(dir + "/t.gif/frame-00001.png"));
}

}  // namespace
}  // namespace sylva::test

// A real tree whose embedded textures are damaged: libpng and libjpeg speak only through sylva.
// A broken PNG is one "sylva: error:" line naming the image and libpng's reason, with nothing
// written; a damaged but readable JPEG renders with one "sylva: warning:" line; an image that is
// neither (OpenCV would try GDCM, which prints its own lines) is one error line too.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

// The lines of `output` that start with "sylva: " (stdout's "wrote ..." lines left out).
std::string sylva_lines(const std::string& output) {
  std::string out;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("sylva: ", 0) == 0) out += line + "\n";
  return out;
}

// The ash's .glb with `edit` applied to the bytes of embedded image `index`.
std::string damaged_ash(const std::string& dir, size_t index,
                        void (*edit)(char* image, size_t size)) {
  std::string glb = read_file(shared_dir() + "/assets/eztree_ash_medium_s5.glb");
  uint32_t json_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  const auto j = nlohmann::json::parse(glb.substr(20, json_length));
  const auto& view = j["bufferViews"][j["images"][index]["bufferView"].get<size_t>()];
  const size_t at = 20 + json_length + 8 + view.value("byteOffset", size_t(0));
  edit(glb.data() + at, view["byteLength"].get<size_t>());
  const std::string path = dir + "/ash_image" + std::to_string(index) + ".glb";
  write_file(path, glb);
  return path;
}

TEST(DamagedTextures, BrokenPngIsOneErrorLineAndWritesNothing) {
  const std::string dir = temp_dir("damaged-png");
  // Image 2 is the leaves' PNG: a bit flipped inside IDAT breaks the zlib stream, an error.
  const std::string scene = damaged_ash(dir, 2, [](char* png, size_t size) {
    const std::string_view bytes(png, size);
    png[bytes.find("IDAT") + 100] ^= 0x20;
  });
  std::filesystem::create_directory(dir + "/out");
  for (const std::string& command :
       {"info " + scene, "render " + scene + " --size 64 -o " + dir + "/out/a.png"}) {
    const RunResult r = run_sylva(command);
    EXPECT_EQ(r.status, 2) << command << "\n" << r.output;
    EXPECT_EQ(count_lines(r.output), 1) << r.output;
    EXPECT_EQ(r.output.rfind("sylva: error: ", 0), 0u) << r.output;
    EXPECT_NE(r.output.find("image 2"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("): IDAT: "), std::string::npos) << r.output;  // libpng's reason
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir + "/out"));
}

TEST(DamagedTextures, DamagedJpegRendersWithOneWarningLine) {
  const std::string dir = temp_dir("damaged-jpeg");
  // Image 0 is the bark's JPEG: a run of restart markers in the middle of its entropy-coded
  // data is damage libjpeg recovers from, with a warning.
  const std::string scene = damaged_ash(dir, 0, [](char* jpeg, size_t size) {
    for (size_t i = size / 2; i < size / 2 + 64; i += 2) {
      jpeg[i] = char(0xFF);
      jpeg[i + 1] = char(0xD3);
    }
  });
  const RunResult r = run_sylva("render " + scene + " --size 64 -o " + dir + "/a.png");
  EXPECT_EQ(r.status, 0) << r.output;
  const std::string lines = sylva_lines(r.output);
  EXPECT_EQ(count_lines(lines), 1) << r.output;
  EXPECT_EQ(lines.rfind("sylva: warning: " + scene + ": image 0", 0), 0u) << r.output;
  EXPECT_NE(lines.find("Corrupt JPEG data"), std::string::npos) << r.output;
  EXPECT_TRUE(file_exists(dir + "/a.png"));
  // `info` lists the warning in its own output, not on stderr.
  const RunResult info = run_sylva("info " + scene + " 2>/dev/null");
  EXPECT_EQ(info.status, 0);
  EXPECT_NE(info.output.find("warning     image 0"), std::string::npos) << info.output;
}

// Bytes OpenCV would hand to GDCM (a DICOM preamble and magic), whose trace printed ten lines.
std::string dicom_like(size_t size) {
  std::string bytes(128, '\0');
  bytes += "DICM";
  while (bytes.size() < size)
    bytes += char(bytes.size() * 37);
  return bytes.substr(0, size);
}

TEST(DamagedTextures, ImageNeitherPngNorJpegIsOneErrorLine) {
  const std::string dir = temp_dir("dicom-texture");
  const std::string scene = damaged_ash(dir, 2, [](char* image, size_t size) {
    const std::string bytes = dicom_like(size);
    std::memcpy(image, bytes.data(), size);
  });
  const RunResult r = run_sylva("info " + scene);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(count_lines(r.output), 1) << r.output;
  EXPECT_EQ(r.output.rfind("sylva: error: " + scene + ": image 2", 0), 0u) << r.output;
  EXPECT_NE(r.output.find("PNG or JPEG expected"), std::string::npos) << r.output;
}

// watercolor.paper takes other formats through OpenCV: what its decoders print stays inside.
TEST(DamagedTextures, UnreadablePaperImageIsOneErrorLine) {
  const std::string dir = temp_dir("bad-paper");
  std::filesystem::create_directory(dir + "/out");
  write_file(dir + "/scan.dcm", dicom_like(4096));
  write_file(dir + "/broken.tif", std::string("II*\0\x08\0\0\0", 8) + std::string(600, '\xff'));
  write_file(dir + "/broken.bmp", "BM" + std::string(100, '\x7f'));
  for (const char* paper : {"scan.dcm", "broken.tif", "broken.bmp"}) {
    const RunResult r =
        run_sylva("render " + small_tree() + " --style watercolor --size 64 --set " +
                  "watercolor.paper=" + dir + "/" + paper + " -o " + dir + "/out/a.png");
    // Besides the preprocessing's report line, one line: the error.
    std::string said;
    std::istringstream in(r.output);
    for (std::string line; std::getline(in, line);)
      if (line.rfind("foliage illumination: ", 0) != 0) said += line + "\n";
    EXPECT_EQ(r.status, 2) << paper << "\n" << r.output;
    EXPECT_EQ(count_lines(said), 1) << paper << "\n" << r.output;
    EXPECT_EQ(said.rfind("sylva: error: ", 0), 0u) << r.output;
    EXPECT_NE(said.find("not a readable image"), std::string::npos) << r.output;
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir + "/out"));
}

}  // namespace
}  // namespace sylva::test

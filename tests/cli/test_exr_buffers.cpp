// `sylva buffers --format exr` read by tools nobody here wrote (issue "Buffers and renders for
// compositors and print"): OpenEXR's exrheader lists every channel with its type and the camera
// attributes; OpenImageIO's oiiotool extracts each channel, which equals the TIFF buffer
// exactly; a non-OpenCV TIFF reader (oiiotool) sees x in a 3-channel TIFF's R; the colour is
// linear and premultiplied; every compression reads back the same; bad options and an
// unwritable folder are one line, exit 2, nothing left. `render --dpi` writes a PNG's pHYs and an
// EXR's xDensity, `render -o X.exr` the linear, premultiplied colour, `--bit-depth 16` and
// `-o X.tiff` 16-bit files, `turntable --frame-format exr` EXR frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

const char* const kAll = "color,normal,depth,position,id,ka,albedo";

// The largest |a - b| over the image; infinity when the sizes or types differ.
double max_difference(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty() || a.size() != b.size() || a.type() != b.type()) return INFINITY;
  return cv::norm(a, b, cv::NORM_INF);
}

struct BufferSets {
  std::string tiff, exr;
};

BufferSets write_both(const std::string& scene, const std::string& tag, const std::string& size) {
  const std::string dir = temp_dir(tag);
  BufferSets sets{dir + "/tiff", dir + "/exr"};
  const std::string args = "buffers " + scene + " --size " + size + " --buffers " + kAll;
  RunResult r = run_sylva(args + " --out-dir " + sets.tiff);
  EXPECT_EQ(r.status, 0) << r.output;
  r = run_sylva(args + " --format exr --out-dir " + sets.exr);
  EXPECT_EQ(r.status, 0) << r.output;
  return sets;
}

void expect_header(const std::string& exr) {
  const RunResult h = run_command("exrheader " + exr);
  ASSERT_EQ(h.status, 0) << h.output;
  for (const char* c : {"R", "G", "B", "A", "Z", "ka", "albedo.R", "albedo.G", "albedo.B"})
    EXPECT_NE(h.output.find(std::string("    ") + c + ", "), std::string::npos) << c;
  for (const char* c : {"N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z", "Z", "ka"})
    EXPECT_NE(h.output.find(std::string(c) + ", 32-bit floating-point"), std::string::npos) << c;
  EXPECT_NE(h.output.find("id, 32-bit unsigned integer"), std::string::npos);
  EXPECT_NE(h.output.find("R, 16-bit floating-point"), std::string::npos);
  for (const char* a : {"worldToCamera (type m44f)", "worldToNDC (type m44f)", "near (type float)",
                        "far (type float)", "compression (type compression): zip"})
    EXPECT_NE(h.output.find(a), std::string::npos) << a;
  const RunResult info = run_command("oiiotool --info -v " + exr);
  ASSERT_EQ(info.status, 0) << info.output;
  // 16 buffer channels, and one RGBA layer (2 ranks) for each of 3 Cryptomatte kinds.
  EXPECT_NE(info.output.find("28 channel"), std::string::npos) << info.output;
}

// EXR channels against the TIFF set, both read by OpenImageIO, and against OpenCV's reading
// of the TIFFs (B, G, R order: channel 2 = x).
void expect_channels_equal_tiffs(const BufferSets& s) {
  const std::string exr = s.exr + "/buffers.exr", scratch = s.exr;
  const cv::Mat depth = cv::imread(s.tiff + "/depth.tiff", cv::IMREAD_UNCHANGED);
  EXPECT_EQ(max_difference(oiio_channels(exr, "Z", scratch), depth), 0.0);
  EXPECT_EQ(max_difference(oiio_channels(exr, "ka", scratch),
                           cv::imread(s.tiff + "/ka.tiff", cv::IMREAD_UNCHANGED)),
            0.0);
  cv::Mat ids;  // exact 32-bit ids; the TIFF holds them as float32 (exact below 2^24)
  oiio_channels(exr, "id", scratch).convertTo(ids, CV_32F);
  EXPECT_EQ(max_difference(ids, cv::imread(s.tiff + "/id.tiff", cv::IMREAD_UNCHANGED)), 0.0);
  for (const char* buffer : {"normal", "position"}) {
    const std::string tiff = s.tiff + "/" + buffer + ".tiff";
    const char axis_prefix = buffer[0] == 'n' ? 'N' : 'P';
    std::vector<cv::Mat> opencv;
    cv::split(cv::imread(tiff, cv::IMREAD_UNCHANGED), opencv);
    ASSERT_EQ(opencv.size(), 3u) << tiff;
    const char* tiff_channels[] = {"R", "G", "B"};
    for (int i = 0; i < 3; ++i) {
      const std::string name = std::string(1, axis_prefix) + "." + "XYZ"[i];
      const cv::Mat from_exr = oiio_channels(exr, name, scratch);
      EXPECT_EQ(max_difference(from_exr, oiio_channels(tiff, tiff_channels[i], scratch)), 0.0)
          << buffer << " " << name << " against the TIFF's " << tiff_channels[i];
      EXPECT_EQ(max_difference(from_exr, opencv[size_t(2 - i)]), 0.0) << name;
    }
  }
  // P.Z is the negated Z on the plant (view space looks down -z): the axes are not mixed up.
  const cv::Mat pz = oiio_channels(exr, "P.Z", scratch);
  ASSERT_FALSE(pz.empty());
  cv::Mat sum = pz + depth;
  EXPECT_LT(cv::norm(sum, cv::NORM_INF), 1e-3 * cv::norm(depth, cv::NORM_INF));
  EXPECT_GT(cv::countNonZero(depth), depth.rows * depth.cols / 20);
}

// R, G, B linear and premultiplied, A the coverage: color.png (B, G, R, A) through the sRGB
// curve, to half precision.
void expect_linear_colour(const std::string& exr, const std::string& png_path,
                          const std::string& scratch) {
  const cv::Mat rgba = oiio_channels(exr, "R,G,B,A", scratch);
  const cv::Mat png = cv::imread(png_path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(rgba.type(), CV_32FC4);
  ASSERT_EQ(png.type(), CV_8UC4);
  double worst = 0.0;
  for (int y = 0; y < png.rows; ++y)
    for (int x = 0; x < png.cols; ++x) {
      const cv::Vec4b c = png.at<cv::Vec4b>(y, x);
      const cv::Vec4f e = rgba.at<cv::Vec4f>(y, x);
      const double a = c[3] / 255.0;
      worst = std::max(worst, std::abs(e[3] - a));
      for (int k = 0; k < 3; ++k) {
        const double v = c[2 - k] / 255.0;  // e is R, G, B, A
        const double lin = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
        worst = std::max(worst, std::abs(e[k] - lin * a) / std::max(lin * a, 0.01));
      }
    }
  EXPECT_LT(worst, 2e-3);  // half: 11 significant bits
}

TEST(ExrBuffers, SampleTreeChannelsAreTheBuffers) {
  const BufferSets s = write_both(small_tree(), "exr-sample", "160x120");
  expect_header(s.exr + "/buffers.exr");
  expect_channels_equal_tiffs(s);
  expect_linear_colour(s.exr + "/buffers.exr", s.tiff + "/color.png", s.exr);
  EXPECT_TRUE(file_exists(s.exr + "/camera.json"));
  EXPECT_FALSE(file_exists(s.exr + "/normal.tiff"));
}

TEST(ExrBuffers, SharedTreeChannelsAreTheBuffers) {
  const BufferSets s =
      write_both(shared_dir() + "/assets/sapling_small_pine_s2.glb", "exr-pine", "192x256");
  expect_header(s.exr + "/buffers.exr");
  expect_channels_equal_tiffs(s);
}

TEST(ExrBuffers, EveryCompressionReadsBackTheSame) {
  const std::string dir = temp_dir("exr-compression");
  cv::Mat first;
  for (const char* c : {"none", "zip", "piz"}) {
    const std::string out = dir + "/" + c;
    const RunResult r = run_sylva("buffers " + small_tree() +
                                  " --size 96 --buffers depth,normal --format exr --compression " +
                                  c + " --out-dir " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    const cv::Mat n = oiio_channels(out + "/buffers.exr", "N.X,N.Y,N.Z,Z", dir);
    if (first.empty()) first = n;
    EXPECT_EQ(max_difference(n, first), 0.0) << c;
    EXPECT_NE(run_command("exrheader " + out + "/buffers.exr").output.find(c), std::string::npos);
  }
}

TEST(ExrBuffers, BadOptionsAndFoldersWriteNothing) {
  const std::string dir = temp_dir("exr-bad");
  const std::string base = "buffers " + small_tree() + " --size 64 --out-dir " + dir + "/out";
  expect_input_error(base + " --format bmp", "tiff, exr");
  expect_input_error(base + " --format exr --compression lzma", "none, zip, piz");
  EXPECT_FALSE(fs::exists(dir + "/out"));
  // A folder where buffers.exr should go: the write fails, and no temporary file is left.
  fs::create_directories(dir + "/taken/buffers.exr");
  expect_input_error(
      "buffers " + small_tree() + " --size 64 --format exr --out-dir " + dir + "/taken",
      "buffers.exr");
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir + "/taken"))
    entries += e.path().filename() != "camera.json";
  EXPECT_EQ(entries, 1u);
  EXPECT_FALSE(fs::exists(dir + "/taken/camera.json"));
}

// The pHYs chunk of a PNG: pixels per metre in x and y and the unit byte; {0, 0, 0} without.
std::array<uint32_t, 3> png_phys(const std::string& bytes) {
  const size_t at = bytes.find("pHYs");
  if (at == std::string::npos || at + 13 > bytes.size()) return {0, 0, 0};
  auto be32 = [&](size_t i) {
    uint32_t v = 0;
    for (size_t k = 0; k < 4; ++k)
      v = (v << 8) | uint8_t(bytes[i + k]);
    return v;
  };
  return {be32(at + 4), be32(at + 8), uint32_t(uint8_t(bytes[at + 12]))};
}

TEST(RenderOutputs, DpiAndLinearExr) {
  const std::string dir = temp_dir("render-dpi");
  const std::string base = "render " + small_tree() + " --style toon --size 96 ";
  ASSERT_EQ(run_sylva(base + "-o " + dir + "/plain.png").status, 0);
  EXPECT_EQ(png_phys(read_file(dir + "/plain.png"))[0], 0u);  // no pHYs by default
  ASSERT_EQ(run_sylva(base + "--dpi 300 -o " + dir + "/print.png").status, 0);
  EXPECT_EQ(png_phys(read_file(dir + "/print.png")), (std::array<uint32_t, 3>{11811, 11811, 1}));
  const RunResult info = run_command("oiiotool --info -v " + dir + "/print.png");
  EXPECT_NE(info.output.find("ResolutionUnit: \"inch\""), std::string::npos) << info.output;
  // The same picture as linear half RGBA with its density.
  ASSERT_EQ(run_sylva(base + "--dpi 300 -o " + dir + "/linear.exr").status, 0);
  EXPECT_NE(
      run_command("exrheader " + dir + "/linear.exr").output.find("xDensity (type float): 300"),
      std::string::npos);
  expect_linear_colour(dir + "/linear.exr", dir + "/print.png", dir);
  expect_input_error(base + "--dpi 10001 -o " + dir + "/x.png", "--dpi");
  expect_input_error(base + "-o " + dir + "/x.tga", ".exr");
  EXPECT_FALSE(fs::exists(dir + "/x.png"));
}

// --bit-depth 16: a PNG and a TIFF that read back as 16-bit and hold the 8-bit picture widened
// (x 257); OpenImageIO sees the TIFF's R as the picture's red; the TIFF carries --dpi.
TEST(RenderOutputs, SixteenBitPngAndTiff) {
  const std::string dir = temp_dir("render-16");
  const std::string base = "render " + small_tree() + " --style toon --size 96 ";
  ASSERT_EQ(run_sylva(base + "-o " + dir + "/8.png").status, 0);
  ASSERT_EQ(run_sylva(base + "--bit-depth 16 -o " + dir + "/16.png").status, 0);
  ASSERT_EQ(run_sylva(base + "--dpi 300 -o " + dir + "/16.tiff").status, 0);  // 16 by default
  const cv::Mat eight = cv::imread(dir + "/8.png", cv::IMREAD_UNCHANGED);
  ASSERT_EQ(eight.type(), CV_8UC4);
  cv::Mat widened;
  eight.convertTo(widened, CV_16U, 257.0);
  for (const char* name : {"16.png", "16.tiff"}) {
    const cv::Mat wide = cv::imread(dir + "/" + name, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(wide.type(), CV_16UC4) << name;
    EXPECT_EQ(cv::norm(wide, widened, cv::NORM_INF), 0.0) << name;
  }
  const cv::Mat red = oiio_channels(dir + "/16.tiff", "R", dir);  // uint16 read as [0, 1]
  std::vector<cv::Mat> bgra;
  cv::split(widened, bgra);
  cv::Mat expected;
  bgra[2].convertTo(expected, CV_32F, 1.0 / 65535.0);
  EXPECT_LT(max_difference(red, expected), 1e-6);
  const RunResult info = run_command("oiiotool --info -v " + dir + "/16.tiff");
  EXPECT_NE(info.output.find("XResolution: 300"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("uint16"), std::string::npos) << info.output;
  expect_input_error(base + "--bit-depth 12 -o " + dir + "/x.png", "8 or 16");
  expect_input_error(base + "--bit-depth 16 -o " + dir + "/x.jpg", ".png or .tiff");
  EXPECT_FALSE(fs::exists(dir + "/x.png"));
}

TEST(RenderOutputs, TurntableWritesExrFrames) {
  const std::string dir = temp_dir("turntable-exr");
  const std::string args = "turntable " + small_tree() + " --style toon --frames 2 --size 96 -q";
  ASSERT_EQ(run_sylva(args + " -o " + dir + "/png/").status, 0);
  const RunResult r = run_sylva(args + " --frame-format exr --dpi 150 -o " + dir + "/exr/");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* frame : {"frame-00000", "frame-00001"}) {
    const std::string exr = dir + "/exr/" + frame + ".exr";
    expect_linear_colour(exr, dir + "/png/" + frame + ".png", dir);
    EXPECT_NE(run_command("exrheader " + exr).output.find("xDensity (type float): 150"),
              std::string::npos);
  }
  expect_input_error(args + " --frame-format exr -o " + dir + "/t.mp4", "folder");
}

}  // namespace
}  // namespace sylva::test

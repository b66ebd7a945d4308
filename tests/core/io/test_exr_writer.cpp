// The EXR writer read back by the OpenEXR library's own reader: half, float and uint channels
// hold what was written (uint exactly, beyond float's 2^24), the camera attributes are the
// transposed (row-vector) matrices, the density and string attributes are there, the bytes are
// the same twice, and a path that cannot be written is an InputError that leaves no file.
#include <ImfChannelList.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "core/io/exr_writer.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

namespace fs = std::filesystem;

ExrImage sample_image() {
  ExrImage exr;
  cv::Mat xyz(3, 5, CV_32FC3), ids(3, 5, CV_32SC1);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) {
      xyz.at<cv::Vec3f>(y, x) = {float(x) + 0.125f, float(y) - 7.5f, 1e-3f * float(x * y)};
      ids.at<int32_t>(y, x) = int32_t(16'777'217 + x + 10 * y);  // above float's exact range
    }
  add_exr_channels(exr, xyz, {"P.X", "P.Y", "P.Z"}, ExrType::Float);
  add_exr_channels(exr, ids, {"id"}, ExrType::Uint);
  cv::Mat bgra(3, 5, CV_8UC4, cv::Scalar(255, 128, 0, 255));
  bgra.at<cv::Vec4b>(1, 1) = {0, 0, 0, 0};
  add_exr_colour(exr, bgra, "");
  glm::mat4 view(1.0f);
  view[3] = glm::vec4(1.0f, 2.0f, 3.0f, 1.0f);  // a translation: column 3 in glm
  exr.camera = ExrCamera{view, view, 0.5f, 40.0f};
  exr.dpi = 300.0;
  exr.strings = {{"note", "hello"}};
  return exr;
}

TEST(ExrWriter, TheLibraryReadsBackWhatWasWritten) {
  const std::string path = test::temp_dir("exr-writer") + "/a.exr";
  write_exr(path, sample_image());
  Imf::InputFile file(path.c_str());
  const Imf::Header& h = file.header();
  EXPECT_EQ(h.channels().findChannel("P.X")->type, Imf::FLOAT);
  EXPECT_EQ(h.channels().findChannel("id")->type, Imf::UINT);
  EXPECT_EQ(h.channels().findChannel("R")->type, Imf::HALF);
  EXPECT_EQ(h.compression(), Imf::ZIP_COMPRESSION);
  ASSERT_TRUE(Imf::hasWorldToCamera(h));
  const Imath::M44f& m = Imf::worldToCamera(h);
  EXPECT_EQ(m[3][0], 1.0f);  // row vectors: the translation is the last row
  EXPECT_EQ(m[3][2], 3.0f);
  EXPECT_EQ(m[0][3], 0.0f);
  EXPECT_EQ(h.typedAttribute<Imf::FloatAttribute>("far").value(), 40.0f);
  EXPECT_EQ(Imf::xDensity(h), 300.0f);
  EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("note").value(), "hello");
  std::vector<float> px(15), r(15);
  std::vector<uint32_t> id(15);
  Imf::FrameBuffer fb;
  fb.insert("P.X", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data()), 4, 20));
  fb.insert("id", Imf::Slice(Imf::UINT, reinterpret_cast<char*>(id.data()), 4, 20));
  fb.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(r.data()), 4, 20));
  file.setFrameBuffer(fb);
  file.readPixels(0, 2);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) {
      EXPECT_EQ(px[size_t(y * 5 + x)], float(x) + 0.125f);
      EXPECT_EQ(id[size_t(y * 5 + x)], uint32_t(16'777'217 + x + 10 * y));
    }
  EXPECT_EQ(r[0], 0.0f);  // B, G, R = 255, 128, 0: R is 0
  EXPECT_EQ(r[6], 0.0f);
}

TEST(ExrWriter, SameBytesTwiceAndEveryCompression) {
  const std::string dir = test::temp_dir("exr-writer-bytes");
  ExrImage exr = sample_image();
  write_exr(dir + "/a.exr", exr);
  write_exr(dir + "/b.exr", exr);
  EXPECT_EQ(test::read_file(dir + "/a.exr"), test::read_file(dir + "/b.exr"));
  for (const char* c : {"none", "zip", "piz"}) {
    exr.compression = parse_exr_compression(c, "--compression");
    write_exr(dir + "/" + c + ".exr", exr);
    Imf::InputFile file((dir + "/" + c + ".exr").c_str());
    EXPECT_EQ(file.header().compression(), c == std::string("none")  ? Imf::NO_COMPRESSION
                                           : c == std::string("zip") ? Imf::ZIP_COMPRESSION
                                                                     : Imf::PIZ_COMPRESSION);
  }
  EXPECT_EQ(test::where_of([] { parse_exr_compression("lzma", "--compression"); }),
            "--compression");
}

TEST(ExrWriter, UnwritablePathIsAnInputErrorAndLeavesNothing) {
  const std::string dir = test::temp_dir("exr-writer-bad");
  fs::create_directories(dir + "/taken.exr");
  EXPECT_EQ(test::where_of([&] { write_exr(dir + "/taken.exr", sample_image()); }),
            dir + "/taken.exr");
  EXPECT_EQ(test::where_of([&] { write_exr(dir + "/missing/a.exr", sample_image()); }),
            dir + "/missing/a.exr");
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir))
    entries += e.exists();
  EXPECT_EQ(entries, 1u);
}

}  // namespace
}  // namespace sylva

// The GL backend on the command line: --gl and SYLVA_GL on the rendering commands, `sylva info
// --gl`, --verbose, one error line and exit 2 for a bad value or a backend that does not start,
// and the same bytes from both backends for a sheet of every built-in style.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

// The backends this sylva was built with (`sylva info --gl --json`).
std::vector<std::string> built_backends() {
  const RunResult r = run_sylva("info --gl auto --json");
  EXPECT_EQ(r.status, 0) << r.output;
  if (r.status != 0) return {};
  return nlohmann::json::parse(r.output)["gl"]["built"].get<std::vector<std::string>>();
}

bool is_built(const std::string& backend) {
  for (const std::string& b : built_backends())
    if (b == backend) return true;
  return false;
}

TEST(GlCli, BadValuesAreOneErrorLine) {
  const std::string out = " -o " + temp_dir("gl-bad") + "/x.png";
  expect_input_error("render " + small_tree() + " --gl vulkan" + out, "--gl");
  expect_input_error("render " + small_tree() + " --gl egl:x" + out, "--gl");
  expect_input_error("buffers " + small_tree() + " --gl EGL --out-dir " + temp_dir("gl-bad-b"),
                     "--gl");
  expect_input_error("info --gl gpu", "--gl");
  {
    const ScopedEnv env("SYLVA_GL", "vulkan");
    expect_input_error("render " + small_tree() + out, "SYLVA_GL");
    expect_input_error("info --gl", "SYLVA_GL");
  }
  const ScopedEnv device("SYLVA_EGL_DEVICE", "first");
  expect_input_error("render " + small_tree() + " --gl egl" + out, "SYLVA_EGL_DEVICE");
  EXPECT_FALSE(file_exists(temp_dir("gl-bad") + "/x.png"));
}

TEST(GlCli, ABackendThatDoesNotStartIsOneErrorLine) {
  const std::string out = " -o " + temp_dir("gl-none") + "/x.png";
  if (is_built("egl"))
    expect_input_error("render " + small_tree() + " --gl egl:99" + out, "no EGL device 99");
  else
    expect_input_error("render " + small_tree() + " --gl egl" + out, "built without egl");
  if (!is_built("osmesa"))
    expect_input_error("render " + small_tree() + " --gl osmesa" + out, "built without osmesa");
}

TEST(GlCli, InfoSaysWhichBackendAndRenderer) {
  const std::vector<std::string> built = built_backends();
  ASSERT_FALSE(built.empty());
  const ScopedEnv env("SYLVA_GL", std::nullopt);
  const RunResult r = run_sylva("info --gl");
  ASSERT_EQ(r.status, 0) << r.output;
  // auto takes EGL when it is built.
  const std::string first = built.front() == "egl" ? "gl backend  EGL (" : "gl backend  OSMesa";
  EXPECT_EQ(r.output.rfind(first, 0), 0u) << r.output;
  for (const char* line : {"\ngl renderer ", "\ngl version  ", "\ngl vendor   ", "\ngl built    "})
    EXPECT_NE(r.output.find(line), std::string::npos) << line << " in " << r.output;
  for (const std::string& b : built) {
    const RunResult one = run_sylva("info " + small_tree() + " --gl " + b + " --json");
    ASSERT_EQ(one.status, 0) << one.output;
    const nlohmann::json j = nlohmann::json::parse(one.output);
    EXPECT_GT(j["triangles"].get<double>(), 0) << one.output;  // the scene too
    const std::string backend = j["gl"]["backend"].get<std::string>();
    EXPECT_EQ(backend.rfind(b == "egl" ? "EGL" : "OSMesa", 0), 0u) << backend;
    EXPECT_NE(j["gl"]["version"].get<std::string>().find("4."), std::string::npos);
  }
  expect_input_error("info", "scene");
}

TEST(GlCli, VerboseSaysWhichBackendRenders) {
  for (const std::string& b : built_backends()) {
    const std::string out = temp_dir("gl-verbose-" + b) + "/x.png";
    const RunResult r =
        run_sylva("render " + small_tree() + " --size 64 --verbose --gl " + b + " -o " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    const std::string want = b == "egl" ? "sylva: GL backend: EGL (" : "sylva: GL backend: OSMesa";
    EXPECT_NE(r.output.find(want), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("sylva: GL renderer: "), std::string::npos) << r.output;
  }
}

// Every built-in style in one sheet, by each backend and by SYLVA_GL: the same bytes (both are
// llvmpipe here; on a GPU the EGL device would be another renderer).
TEST(GlCli, BothBackendsRenderTheSameBytes) {
  if (!is_built("egl") || !is_built("osmesa")) GTEST_SKIP() << "one backend built";
  const std::string dir = temp_dir("gl-same");
  const std::string args = "compare " + small_tree() + " --size 96 -q -o " + dir;
  for (const char* b : {"egl", "osmesa"}) {
    const RunResult r = run_sylva(args + "/" + b + ".png --gl " + b);
    ASSERT_EQ(r.status, 0) << r.output;
  }
  {
    const ScopedEnv env("SYLVA_GL", "osmesa");
    ASSERT_EQ(run_sylva(args + "/env.png").status, 0);
  }
  const std::string egl = read_file(dir + "/egl.png");
  EXPECT_GT(egl.size(), 1000u);
  EXPECT_TRUE(egl == read_file(dir + "/osmesa.png")) << "egl and osmesa sheets differ";
  EXPECT_TRUE(egl == read_file(dir + "/env.png")) << "SYLVA_GL=osmesa sheet differs";
  const std::string fern = "render " + fern_path() + " --style ink --size 160 -o " + dir;
  ASSERT_EQ(run_sylva(fern + "/fern-egl.png --gl egl").status, 0);
  ASSERT_EQ(run_sylva(fern + "/fern-osmesa.png --gl osmesa").status, 0);
  EXPECT_TRUE(read_file(dir + "/fern-egl.png") == read_file(dir + "/fern-osmesa.png"));
}

}  // namespace
}  // namespace sylva::test

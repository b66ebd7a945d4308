// The GL backends (core/gl/gl_context.h) and the loader table (core/gl/gl_api.h): the choice from
// --gl and the environment, every built backend starting, auto taking EGL first when it is
// built, the two backends giving the same bytes in one process (contexts switched back and
// forth), and the draw limits of a CPU renderer against a GPU's one draw per mesh.
#include <gtest/gtest.h>

#include <cstdio>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <thread>

#include "core/error.h"
#include "core/gl/gl_api.h"
#include "core/gl/rasterizer.h"
#include "tests/core/gl/raster_scenes.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

using namespace sylva::test;

bool built(GlBackend b) {
  for (GlBackend x : built_gl_backends())
    if (x == b) return true;
  return false;
}

std::unique_ptr<GlContext> start(GlBackend b) {
  GlChoice c;
  c.backend = b;
  c.where = "--gl";
  return create_gl_context(c);
}

TEST(GlChoice, ValuesOfTheOptionAndTheEnvironment) {
  const ScopedEnv no_device("SYLVA_EGL_DEVICE", std::nullopt);
  EXPECT_EQ(parse_gl_choice("auto", "--gl").backend, GlBackend::Auto);
  EXPECT_EQ(parse_gl_choice("osmesa", "--gl").backend, GlBackend::Osmesa);
  const GlChoice egl = parse_gl_choice("egl", "--gl");
  EXPECT_EQ(egl.backend, GlBackend::Egl);
  EXPECT_EQ(egl.egl_device, -1);
  const GlChoice two = parse_gl_choice("egl:2", "--gl");
  EXPECT_EQ(two.backend, GlBackend::Egl);
  EXPECT_EQ(two.egl_device, 2);
  for (const char* bad : {"", "EGL", "egl:", "egl:-1", "egl:1x", "egl:1000", "osmesa ", "gpu"})
    EXPECT_EQ(where_of([&] { parse_gl_choice(bad, "--gl"); }), "--gl") << bad;
  {
    const ScopedEnv env("SYLVA_GL", "osmesa");
    EXPECT_EQ(gl_choice_from_option("").backend, GlBackend::Osmesa);
    EXPECT_EQ(gl_choice_from_option("egl").backend, GlBackend::Egl);  // the option wins
  }
  {
    const ScopedEnv env("SYLVA_GL", "vulkan");
    EXPECT_EQ(where_of([] { gl_choice_from_option(""); }), "SYLVA_GL");
    EXPECT_EQ(gl_choice_from_option("auto").backend, GlBackend::Auto);
  }
  {
    const ScopedEnv env("SYLVA_GL", std::nullopt);
    const ScopedEnv device("SYLVA_EGL_DEVICE", "1");
    EXPECT_EQ(gl_choice_from_option("egl").egl_device, 1);
    EXPECT_EQ(gl_choice_from_option("egl:0").egl_device, 0);  // the option wins
  }
  const ScopedEnv device("SYLVA_EGL_DEVICE", "first");
  EXPECT_EQ(where_of([] { gl_choice_from_option("egl"); }), "SYLVA_EGL_DEVICE");
}

TEST(GlContext, EveryBuiltBackendStartsA45CoreContext) {
  ASSERT_FALSE(built_gl_backends().empty());
  for (GlBackend b : built_gl_backends()) {
    const std::unique_ptr<GlContext> c = start(b);
    const GlInfo& i = c->info();
    EXPECT_EQ(i.backend, b);
    EXPECT_FALSE(i.renderer.empty() || i.renderer == "?") << gl_backend_name(b);
    EXPECT_FALSE(i.vendor.empty() || i.vendor == "?") << gl_backend_name(b);
    int major = 0, minor = 0;
    ASSERT_EQ(std::sscanf(i.version.c_str(), "%d.%d", &major, &minor), 2) << i.version;
    EXPECT_GE(major * 10 + minor, 45) << i.version;
    EXPECT_TRUE(i.fallback.empty());
    EXPECT_NE(c->description().find(i.renderer), std::string::npos);
  }
}

// So the suite's renders (SYLVA_GL unset) are EGL's wherever EGL is built: a failing EGL would
// otherwise pass unseen behind OSMesa.
TEST(GlContext, AutoTakesTheFirstBuiltBackend) {
  const ScopedEnv env("SYLVA_GL", std::nullopt);
  const std::unique_ptr<GlContext> c = create_gl_context();
  EXPECT_EQ(c->info().backend, built_gl_backends().front());
  EXPECT_EQ(c->info().fallback, "") << "auto passed over a built backend";
  if (built(GlBackend::Egl)) {
    EXPECT_EQ(c->info().backend, GlBackend::Egl);
  }
}

TEST(GlContext, ABackendNotBuiltOrAMissingDeviceIsAnInputError) {
  for (GlBackend b : {GlBackend::Egl, GlBackend::Osmesa})
    if (!built(b)) {
      EXPECT_EQ(where_of([&] { start(b); }), "--gl");
    }
  if (!built(GlBackend::Egl)) GTEST_SKIP() << "no EGL in this build";
  GlChoice c = parse_gl_choice("egl:999", "--gl");
  EXPECT_EQ(where_of([&] { create_gl_context(c); }), "--gl");
  const ScopedEnv env("SYLVA_GL", "egl");
  const ScopedEnv device("SYLVA_EGL_DEVICE", "999");
  EXPECT_EQ(where_of([] { create_gl_context(); }), "SYLVA_GL");
}

// A gl* call on a thread where no Sylva context was made current reaches no library's export.
TEST(GlContextDeathTest, AGlCallWithNoContextCurrentStops) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(
      {
        std::thread t([] { glFinish(); });
        t.join();
      },
      "no Sylva GL context");
}

std::vector<std::pair<const char*, Scene>> test_scenes() {
  std::vector<std::pair<const char*, Scene>> s;
  s.emplace_back("sphere", sphere_scene(96, 48));
  s.emplace_back("spheres", spheres_scene());
  return s;
}

GBuffer render_all(GlContext& context, const Scene& s, int ssaa,
                   std::optional<DrawLimits> limits = std::nullopt) {
  Rasterizer r(context);
  if (limits) r.set_draw_limits(*limits);
  r.upload(s);
  RasterRequest q = request_of(kAllTargetsMask, IdKind::Primitive, ssaa);
  q.background = glm::vec4(0.2f, 0.3f, 0.4f, 1.0f);
  return r.render(front_camera(s, 96), Lighting::three_point(), q);
}

void expect_same_bytes(const GBuffer& a, const GBuffer& b, const std::string& what) {
  for (Target t : kAllTargets) {
    const cv::Mat& x = target_image(a, t);
    const cv::Mat& y = target_image(b, t);
    ASSERT_EQ(x.size(), y.size()) << what;
    ASSERT_EQ(x.type(), y.type()) << what;
    ASSERT_FALSE(x.empty()) << what;
    cv::Mat differs;
    cv::compare(x.reshape(1), y.reshape(1), differs, cv::CMP_NE);
    EXPECT_EQ(cv::countNonZero(differs), 0) << what << ", target " << int(t);
  }
}

// llvmpipe behind either library: the same bytes, with the contexts used in turn on one thread.
TEST(GlContext, BothBackendsGiveTheSameBytesInOneProcess) {
  if (!built(GlBackend::Egl) || !built(GlBackend::Osmesa)) GTEST_SKIP() << "one backend built";
  const std::unique_ptr<GlContext> egl = start(GlBackend::Egl);
  const std::unique_ptr<GlContext> osmesa = start(GlBackend::Osmesa);
  if (egl->info().renderer != osmesa->info().renderer)
    GTEST_SKIP() << "different renderers: " << egl->info().renderer;
  for (const auto& [name, scene] : test_scenes()) {
    for (int ssaa : {1, 2}) {
      const GBuffer a = render_all(*egl, scene, ssaa);
      const GBuffer b = render_all(*osmesa, scene, ssaa);
      const GBuffer again = render_all(*egl, scene, ssaa);
      expect_same_bytes(a, b, std::string(name) + " egl / osmesa");
      expect_same_bytes(a, again, std::string(name) + " egl after osmesa");
    }
  }
}

// A GPU's one draw per mesh (no limits) and draws far smaller than llvmpipe's draw the same
// triangles in the same order: the same bytes.
TEST(GlContext, DrawLimitsChangeNoPixel) {
  for (const auto& [name, scene] : test_scenes()) {
    const GBuffer cpu = render_all(gl(), scene, 1);
    expect_same_bytes(cpu, render_all(gl(), scene, 1, DrawLimits{}), std::string(name) + " gpu");
    expect_same_bytes(cpu, render_all(gl(), scene, 1, DrawLimits{100, 250}),
                      std::string(name) + " small chunks");
  }
  const DrawLimits cpu = draw_limits_for(gl().info());
  EXPECT_EQ(cpu.chunk_triangles > 0, gl().info().software);
}

}  // namespace
}  // namespace sylva

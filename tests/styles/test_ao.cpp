// Ambient occlusion in the raster pass and the styles (npr/ao_pass.h): the shader's Hegeman
// visibility against npr/hegeman_ao.h at the pixels' positions and normals (leaves: Eq. 4-6;
// bark: the crown's Eq. 7-8, see also test_ao_objects.cpp), the AO target's
// range and background, culling with ao.model = none, the ray-traced pass, and ao.* checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/core.hpp>

#include "core/error.h"
#include "npr/ao_pass.h"
#include "samples/plants.h"
#include "styles/sheet.h"
#include "styles/style.h"
#include "tests/styles/ao_cpu.h"
#include "tests/styles/style_rig.h"

namespace sylva {
namespace {

using AoRig = test::StyleRig;

// The AO target is finite, in [0, 1], 0 exactly where nothing was drawn.
void expect_ao_range(const GBuffer& g) {
  ASSERT_EQ(g.ao.type(), CV_32FC1);
  for (int y = 0; y < g.ao.rows; ++y)
    for (int x = 0; x < g.ao.cols; ++x) {
      const float a = g.ao.at<float>(y, x);
      ASSERT_TRUE(std::isfinite(a));
      ASSERT_GE(a, 0.0f);
      ASSERT_LE(a, 1.0f);
      if (g.depth.at<float>(y, x) == 0.0f) {
        ASSERT_EQ(a, 0.0f);
      }
    }
}

TEST(Ao, ShaderMatchesHegemanVisibilityOnTheCpu) {
  AoRig rig(96);
  const std::vector<glm::vec3> points = foliage_vertices(rig.scene);
  ASSERT_GT(points.size(), 100u);
  const glm::mat4 to_world = glm::inverse(rig.rs.camera.view);
  struct Case {
    bool ellipsoid;
    int k;
  } cases[] = {{false, 1}, {true, 1}, {true, 4}, {false, 7}};
  for (const Case& c : cases) {
    const test::CpuAo cpu = test::make_cpu_ao(points, c.ellipsoid, c.k, 3.0f);
    const std::vector<glm::vec3>& anchors = cpu.uniforms.anchors;
    RasterRequest request;
    request.targets = Target::Ao | Target::Position | Target::Normal | Target::Depth | Target::Id;
    request.id_kind = IdKind::Object;  // mesh 0 (object 1) is the leaves, mesh 1 the bark
    request.ao = cpu.uniforms;
    const GBuffer g = rig.raster->render(rig.rs.camera, rig.rs.lighting, request);
    expect_ao_range(g);
    double max_diff = 0.0;
    int compared = 0;
    float lo = 1.0f;
    for (int y = 0; y < g.ao.rows; ++y)
      for (int x = 0; x < g.ao.cols; ++x) {
        if (g.depth.at<float>(y, x) == 0.0f) continue;
        const cv::Vec3f p = g.position.at<cv::Vec3f>(y, x);
        const cv::Vec3f n = g.normal.at<cv::Vec3f>(y, x);
        const glm::vec3 wp = glm::vec3(to_world * glm::vec4(p[0], p[1], p[2], 1.0f));
        const glm::vec3 wn = glm::mat3(to_world) * glm::vec3(n[0], n[1], n[2]);
        // Skip points almost equidistant from two anchors: rounding may pick either shell.
        std::vector<float> d;
        for (const glm::vec3& a : anchors)
          d.push_back(glm::length(wp - a));
        std::sort(d.begin(), d.end());
        const bool leaf = g.id.at<int>(y, x) == 1;
        if (leaf && d.size() > 1 && d[1] - d[0] < 1e-3f * d[1]) continue;
        // Leaves: Eq. 4-6 in their shell; the bark: the crown's solid angle (Eq. 7-8).
        const float v = leaf ? cpu.visibility(wp, wn) : cpu.object(wp, wn);
        max_diff = std::max(max_diff, double(std::abs(v - g.ao.at<float>(y, x))));
        lo = std::min(lo, g.ao.at<float>(y, x));
        ++compared;
      }
    EXPECT_GT(compared, 96 * 96 / 20) << c.k;
    EXPECT_LT(max_diff, 1e-3) << "ellipsoid " << c.ellipsoid << " k " << c.k;
    EXPECT_LT(lo, 0.5f) << "the AO should darken somewhere";
  }
}

TEST(Ao, ConstantAndLuftDensity) {
  AoRig rig;
  RasterRequest request;
  request.targets = Target::Ao | Target::Ka | Target::Depth;
  request.ao.model = AoShading::Model::Constant;
  request.ao.constant = 0.25f;
  GBuffer g = rig.raster->render(rig.rs.camera, rig.rs.lighting, request);
  expect_ao_range(g);
  cv::Mat covered = g.depth != 0.0f;
  double lo = 0, hi = 0;
  cv::minMaxLoc(g.ao, &lo, &hi, nullptr, nullptr, covered);
  EXPECT_EQ(lo, 0.25);
  EXPECT_EQ(hi, 0.25);
  request.ao.model = AoShading::Model::Ka;
  g = rig.raster->render(rig.rs.camera, rig.rs.lighting, request);
  expect_ao_range(g);
  EXPECT_EQ(cv::norm(g.ao, g.ka, cv::NORM_INF), 0.0);
  request.ao.model = AoShading::Model::None;
  g = rig.raster->render(rig.rs.camera, rig.rs.lighting, request);
  cv::minMaxLoc(g.ao, &lo, &hi, nullptr, nullptr, covered);
  EXPECT_EQ(lo, 1.0);
}

// A style's graph for one scene, through the same plan `sylva render` uses.
struct Planned {
  RenderGraph graph;
  SheetPlan plan;
};
std::unique_ptr<Planned> plan_style(AoRig& rig, const Style& style) {
  auto p = std::make_unique<Planned>();
  SheetScene sheet;
  sheet.raster = rig.rs;
  sheet.scene = &rig.scene;
  sheet.scene_sphere = rig.scene.framing_sphere();
  sheet.foliage = [&rig](const FoliageSettings&) {
    IlluminationSetup is;
    is.scene = &rig.scene;
    return is;
  };
  p->plan = add_sheet_passes(p->graph, {&style}, sheet);
  return p;
}

TEST(Ao, ModelNoneCullsTheAoTargetAndTheShells) {
  AoRig rig;
  const Style plain("standard");
  auto a = plan_style(rig, plain);
  EXPECT_EQ(a->graph.to_dot().find("ao-shells"), std::string::npos);
  a->graph.execute();
  EXPECT_FALSE(has(rig.raster->last_allocated_targets(), Target::Ao));
  const cv::Mat base = a->graph.get<cv::Mat>(a->plan.outputs[0]).clone();

  const Style shaded("standard", {"ao.model=hegeman-sphere", "ao.alpha_rho=auto"});
  auto b = plan_style(rig, shaded);
  b->graph.execute();
  const cv::Mat& dark = b->graph.get<cv::Mat>(b->plan.outputs[0]);
  // The ambient term only darkens: no channel gets brighter, and some get darker.
  cv::Mat brighter, darker;
  cv::compare(dark, base, brighter, cv::CMP_GT);
  cv::compare(dark, base, darker, cv::CMP_LT);
  EXPECT_EQ(cv::countNonZero(brighter.reshape(1)), 0);
  EXPECT_GT(cv::countNonZero(darker.reshape(1)), 64 * 64 / 20);
}

TEST(Ao, AutoAlphaRhoIsFinitePositive) {
  AoRig rig;
  for (const char* model : {"hegeman-sphere", "hegeman-shells"}) {
    AoSettings settings;
    settings.model = parse_ao_model(model, "test");
    settings.alpha_rho = "auto";
    const AoShading ao = scene_ao_shading(rig.scene, settings, 1);
    EXPECT_TRUE(std::isfinite(ao.alpha_rho)) << model;
    EXPECT_GT(ao.alpha_rho, 0.0f) << model;
  }
}

TEST(Ao, RaytracedIsDarkerInsideTheCrownThanAtItsRim) {
  AoRig rig(48);
  RenderGraph graph;
  const GBufferHandles gb = add_raster_pass(graph, rig.rs);
  const auto ao =
      add_raytraced_ao_pass(graph, &rig.scene, gb.position, gb.normal, rig.rs.camera.view, 16, 1);
  graph.present(ao);
  graph.present(gb.depth);
  graph.execute();
  const cv::Mat& v = graph.get<cv::Mat>(ao);
  const cv::Mat& depth = graph.get<cv::Mat>(gb.depth);
  ASSERT_EQ(v.type(), CV_32FC1);
  // Rim: covered pixels next to the background; inside: the farthest quarter of the covered
  // pixels (seen through gaps, deep in the crown).
  std::vector<float> depths;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x) {
      const float a = v.at<float>(y, x);
      ASSERT_TRUE(std::isfinite(a));
      ASSERT_GE(a, 0.0f);
      ASSERT_LE(a, 1.0f);
      if (depth.at<float>(y, x) == 0.0f) {
        ASSERT_EQ(a, 0.0f);
      } else {
        depths.push_back(depth.at<float>(y, x));
      }
    }
  ASSERT_GT(depths.size(), 100u);
  std::sort(depths.begin(), depths.end());
  const float deep = depths[depths.size() * 3 / 4];
  double rim = 0, inside = 0;
  int rims = 0, insides = 0;
  for (int y = 1; y < 47; ++y)
    for (int x = 1; x < 47; ++x) {
      const float d = depth.at<float>(y, x);
      if (d == 0.0f) continue;
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          edge = edge || depth.at<float>(y + dy, x + dx) == 0.0f;
      if (edge) {
        rim += v.at<float>(y, x), ++rims;
      } else if (d >= deep) {
        inside += v.at<float>(y, x), ++insides;
      }
    }
  ASSERT_GT(rims, 10);
  ASSERT_GT(insides, 10);
  EXPECT_LT(inside / insides, rim / rims);
}

// A turntable's frames share an AoMemo: the shells are fitted once per settings and the ray
// tracer's BVH is built once, and the results equal those made without it.
TEST(Ao, MemoFitsOnceAndBuildsTheTracerOnce) {
  AoRig rig(32);
  auto memo = std::make_shared<AoMemo>();
  auto shading = [&](int shells, std::shared_ptr<AoMemo> m) {
    RenderGraph graph;
    AoSetup as;
    as.scene = &rig.scene;
    as.settings.model = AoModel::HegemanShells;
    as.settings.shells = shells;
    as.memo = std::move(m);
    const auto out = add_ao_shading_pass(graph, as);
    graph.present(out);
    graph.execute();
    return graph.get<std::shared_ptr<const AoShading>>(out);
  };
  const auto first = shading(2, memo);
  EXPECT_EQ(shading(2, memo), first);  // the same object: not fitted again
  EXPECT_EQ(memo->shading.size(), 1u);
  const auto other = shading(3, memo);
  EXPECT_NE(other, first);
  EXPECT_EQ(memo->shading.size(), 2u);
  const auto fresh = shading(2, nullptr);
  EXPECT_NE(fresh, first);
  EXPECT_EQ(fresh->alpha_rho, first->alpha_rho);
  EXPECT_EQ(fresh->centres, first->centres);

  auto traced = [&](std::shared_ptr<AoMemo> m) {
    RenderGraph graph;
    const GBufferHandles gb = add_raster_pass(graph, rig.rs);
    const auto ao = add_raytraced_ao_pass(graph, &rig.scene, gb.position, gb.normal,
                                          rig.rs.camera.view, 4, 1, std::move(m));
    graph.present(ao);
    graph.execute();
    return graph.get<cv::Mat>(ao).clone();
  };
  const cv::Mat a = traced(memo);
  ASSERT_NE(memo->tracer, nullptr);
  const AoReferenceScene* tracer = memo->tracer.get();
  const cv::Mat b = traced(memo);
  EXPECT_EQ(memo->tracer.get(), tracer);  // built once
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a, traced(nullptr), cv::NORM_INF), 0.0);
}

TEST(Ao, OutOfRangeValuesNameTheKey) {
  for (const char* bad :
       {"ao.model=foo", "ao.constant=1.5", "ao.constant=-0.1", "ao.alpha_rho=-1", "ao.alpha_rho=x",
        "ao.shells=0", "ao.shells=65", "ao.rays=0", "ao.rays=4097"}) {
    try {
      const Style s("standard", {bad});
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      const std::string key = std::string(bad).substr(0, std::string(bad).find('='));
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
  for (const char* good : {"ao.constant=0", "ao.constant=1", "ao.alpha_rho=0", "ao.alpha_rho=auto",
                           "ao.shells=1", "ao.shells=64", "ao.rays=1", "ao.rays=4096"})
    EXPECT_NO_THROW(Style("standard", {good})) << good;
}

}  // namespace
}  // namespace sylva

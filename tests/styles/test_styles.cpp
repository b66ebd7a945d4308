// Styles build through the render graph, and the graph culls what a style does not read:
// `standard` never allocates or rasterises the ID (or any non-colour) target.
#include <gtest/gtest.h>

#include "core/error.h"
#include "npr/leaf_clusters.h"
#include "samples/plants.h"
#include "styles/sheet.h"
#include "styles/style.h"
#include "tests/styles/style_rig.h"

namespace sylva {
namespace {

using test::StyleRig;

TEST(Styles, StandardNeverAllocatesTheIdTarget) {
  StyleRig s;
  RenderGraph graph;
  GBufferHandles gb = add_raster_pass(graph, s.rs);
  ImageHandle out = Style("standard").build(graph, gb, StyleContext{}).image;
  graph.present(out);
  graph.compile();
  EXPECT_FALSE(graph.is_live(gb.id));
  EXPECT_FALSE(graph.is_live(gb.normal));
  graph.execute();
  EXPECT_EQ(s.raster->last_allocated_targets(), static_cast<TargetMask>(Target::Color));
  const cv::Mat& img = graph.get<cv::Mat>(out);
  EXPECT_EQ(img.type(), CV_8UC4);
  EXPECT_GT(cv::countNonZero(img.reshape(1, static_cast<int>(img.total())).col(3) == 255),
            64 * 64 / 20);
}

// Each built-in style asks the raster pass for only what its passes read: toon never draws
// ids, watercolor draws cluster ids and no normals (its shading comes from the colour target).
TEST(Styles, EachStyleRasterisesOnlyWhatItReads) {
  StyleRig s;
  assign_clusters(s.scene, {});
  struct Expect {
    const char* style;
    TargetMask never;
  } cases[] = {
      {"standard", Target::Id | Target::Normal | Target::Albedo},
      {"toon", Target::Id | Target::Color | Target::Depth},
      // watercolor: positions come from the depth through the frame's camera.
      {"watercolor", Target::Normal | Target::Albedo | Target::Position},
      // blobs: cluster ids, colour, albedo and depth; the preset's silhouettes use no normals.
      {"blobs", Target::Normal | Target::Position | Target::Ka},
  };
  for (const Expect& e : cases) {
    const Style style(e.style);
    RenderGraph graph;
    RasterSetup rs = s.rs;
    style.configure(rs.request);
    IlluminationSetup is;
    is.scene = &s.scene;
    const auto shading = add_foliage_illumination_pass(graph, is);
    if (style.normals() != NormalMode::Original) rs.shading = shading;
    const GBufferHandles gb = add_raster_pass(graph, rs);
    StyleContext context;
    context.lighting = s.rs.lighting;
    context.view = s.rs.camera.view;
    context.camera = s.rs.camera;
    const ImageHandle out = style.build(graph, gb, context).image;
    graph.present(out);
    graph.execute();
    const TargetMask drawn = s.raster->last_allocated_targets();
    EXPECT_EQ(drawn & e.never, 0u) << e.style << " drew " << drawn;
    const cv::Mat& img = graph.get<cv::Mat>(out);
    EXPECT_EQ(img.type(), CV_8UC4) << e.style;
    EXPECT_EQ(img.size(), cv::Size(64, 64)) << e.style;
  }
}

TEST(Styles, PresentingIdsAllocatesThem) {
  StyleRig s;
  RenderGraph graph;
  GBufferHandles gb = add_raster_pass(graph, s.rs);
  graph.present(gb.id);
  graph.execute();
  EXPECT_EQ(s.raster->last_allocated_targets(), static_cast<TargetMask>(Target::Id));
}

// The Luft preprocessing is a scene-level node: declared for every style, run only for the
// ones whose raster pass reads it. `expressive` draws with the density ka (below 1 inside
// the crown) where `standard` has ka = 1 everywhere.
TEST(Styles, PreprocessingRunsOnlyForStylesThatReadIt) {
  StyleRig s;
  assign_clusters(s.scene, {});
  double mean_ka[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const Style style(k == 0 ? "standard" : "expressive");
    RenderGraph graph;
    IlluminationSetup is;
    is.scene = &s.scene;
    const auto shading = add_foliage_illumination_pass(graph, is);
    RasterSetup rs = s.rs;
    if (style.normals() != NormalMode::Original) rs.shading = shading;
    const GBufferHandles gb = add_raster_pass(graph, rs);
    graph.present(style.build(graph, gb, StyleContext{}).image);
    graph.compile();
    EXPECT_EQ(graph.pass_live("foliage-illumination"), k == 1) << style.info().name;
    graph.present(gb.ka);  // a second compile with the ka target added, for the check
    graph.compile();
    graph.execute();
    const cv::Mat& ka = graph.get<cv::Mat>(gb.ka);
    mean_ka[k] = cv::mean(ka, ka > 0)[0];
  }
  EXPECT_NEAR(mean_ka[0], 1.0, 1e-6);
  EXPECT_LT(mean_ka[1], 0.9);
  EXPECT_GT(mean_ka[1], 0.2 - 1e-6);  // ka_min
}

// toon.cast_shadows renders a depth map from the key light and darkens what it cannot see:
// with the sun straight above, the trunk under the crown and the lower leaves go dark.
// Without lights (a headlight along the view) nothing is blocked, so nothing changes.
TEST(Styles, ToonCastShadowsDarkenWhatTheKeyLightCannotSee) {
  PlantOptions po;
  po.kind = PlantKind::Tree;
  po.leaves = 800;
  Scene scene = make_plant(po);
  auto ctx = create_gl_context();
  Rasterizer raster(*ctx);
  raster.upload(scene);
  SheetScene sheet;
  sheet.raster.rasterizer = &raster;
  sheet.raster.camera = make_orbit_camera(scene.framing_sphere(), OrbitParams{}, 96, 96);
  sheet.scene_sphere = scene.framing_sphere();
  sheet.foliage = [&](const FoliageSettings&) {
    IlluminationSetup is;
    is.scene = &scene;
    return is;
  };
  Light sun;
  sun.vector = {0.0f, 1.0f, 0.0f};
  sun.camera_fixed = false;
  auto render = [&](bool shadows, const Lighting& lighting) {
    sheet.raster.lighting = lighting;
    const Style style("toon", {"toon.cast_shadows=" + std::string(shadows ? "true" : "false"),
                               "toon.shadow_map_size=256"});
    RenderGraph graph;
    const SheetPlan plan = add_sheet_passes(graph, {&style}, sheet);
    EXPECT_EQ(graph.has_pass("key-shadow/shadow-map"), shadows);
    EXPECT_EQ(graph.has_pass("key-shadow/raster"), shadows && !lighting.lights.empty());
    graph.execute();
    return graph.get<cv::Mat>(plan.outputs[0]).clone();
  };
  Lighting lit;
  lit.lights = {sun};
  const cv::Mat plain = render(false, lit), shadowed = render(true, lit);
  cv::Mat alpha;
  cv::extractChannel(plain, alpha, 3);
  const double before = cv::mean(plain, alpha > 0)[1], after = cv::mean(shadowed, alpha > 0)[1];
  EXPECT_LT(after, before * 0.95) << before << " -> " << after;
  cv::Mat diff;
  cv::absdiff(plain, shadowed, diff);
  cv::Mat changed;
  cv::extractChannel(diff, changed, 1);
  EXPECT_GT(cv::countNonZero(changed > 0), cv::countNonZero(alpha > 0) / 5);
  const cv::Mat head_plain = render(false, Lighting{}), head_shadowed = render(true, Lighting{});
  cv::absdiff(head_plain, head_shadowed, diff);
  EXPECT_EQ(cv::countNonZero(diff.reshape(1) > 0), 0);
}

TEST(Styles, UnknownStyleIsAnInputError) {
  try {
    Style s("watercolour");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "--style");
    EXPECT_NE(std::string(e.what()).find("standard"), std::string::npos);
  }
}

}  // namespace
}  // namespace sylva

// Styles build through the render graph, and the graph culls what a style does not read:
// `standard` never allocates or rasterises the ID (or any non-colour) target.
#include <gtest/gtest.h>

#include "core/error.h"
#include "samples/plants.h"
#include "styles/style.h"

namespace sylva {
namespace {

struct StyleRig {
  Scene scene;
  std::unique_ptr<GlContext> ctx = create_gl_context();
  std::unique_ptr<Rasterizer> raster;
  RasterSetup rs;
  StyleRig() {
    PlantOptions po;
    po.kind = PlantKind::Bush;
    po.leaves = 300;
    scene = make_plant(po);
    raster = std::make_unique<Rasterizer>(*ctx);
    raster->upload(scene);
    rs.rasterizer = raster.get();
    rs.camera = make_orbit_camera(scene.bounds(), OrbitParams{}, 64, 64);
    rs.lighting = Lighting::three_point();
  }
};

TEST(Styles, StandardNeverAllocatesTheIdTarget) {
  StyleRig s;
  RenderGraph graph;
  GBufferHandles gb = add_raster_pass(graph, s.rs);
  int out = find_style("standard").build(graph, gb);
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

TEST(Styles, PresentingIdsAllocatesThem) {
  StyleRig s;
  RenderGraph graph;
  GBufferHandles gb = add_raster_pass(graph, s.rs);
  graph.present(gb.id);
  graph.execute();
  EXPECT_EQ(s.raster->last_allocated_targets(), static_cast<TargetMask>(Target::Id));
}

TEST(Styles, UnknownStyleIsAnInputError) {
  try {
    find_style("watercolour");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "--style");
    EXPECT_NE(std::string(e.what()).find("standard"), std::string::npos);
  }
}

}  // namespace
}  // namespace sylva

// Alpha-cutout leaves: the ID buffer follows the leaf shape in the base-colour texture's
// alpha, not the card. On the sample plants (leaf silhouettes in alpha) the cut-out coverage
// is a strict subset of the cards'. The shared Poly Haven fern is alpha MASK, but its
// base-colour texture is an RGB JPEG with no alpha channel, so its fronds are cut by their
// geometry only: the loader warns, and coverage equals the geometry's.
#include <gtest/gtest.h>

#include "core/gl/rasterizer.h"
#include "core/scene/load.h"
#include "samples/plants.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

struct Coverage {
  int cut = 0, full = 0, outside = 0;
};

Coverage compare_with_cards(const Scene& scene, float elevation) {
  auto ctx = create_gl_context();
  auto render = [&](const Scene& s) {
    Rasterizer r(*ctx);
    r.upload(s);
    OrbitParams orbit;
    orbit.elevation_deg = elevation;
    Camera cam = make_orbit_camera(s.bounds(), orbit, 256, 256);
    RasterRequest req;
    req.targets = static_cast<TargetMask>(Target::Id);
    return r.render(cam, Lighting::three_point(), req).id;
  };
  cv::Mat cut = render(scene);
  Scene cards = scene;
  for (Material& m : cards.materials)
    m.alpha_mode = AlphaMode::Opaque;
  cv::Mat full = render(cards);
  // Cut-out pixels reveal leaves behind (other ids), so compare coverage, not values.
  return {cv::countNonZero(cut), cv::countNonZero(full),
          cv::countNonZero((cut != 0) & (full == 0))};
}

TEST(AlphaCutout, SampleLeavesFollowTheirAlphaNotTheCard) {
  PlantOptions po;
  po.kind = PlantKind::Bush;
  po.leaves = 400;
  Scene bush = make_plant(po);
  Coverage c = compare_with_cards(bush, 20);
  ASSERT_GT(c.full, 1000);
  EXPECT_LT(c.cut, 0.95 * c.full) << c.cut << " vs " << c.full;
  EXPECT_GT(c.cut, 0.3 * c.full);
  EXPECT_EQ(c.outside, 0);
}

TEST(AlphaCutout, FernWithoutAlphaChannelIsCutByGeometryAndWarned) {
  Scene fern = load_scene(test::fern_path());
  ASSERT_EQ(fern.materials.at(0).alpha_mode, AlphaMode::Mask);
  bool warned = false;
  for (const std::string& w : fern.report.warnings)
    warned = warned ||
             (w.find("fern_02") != std::string::npos && w.find("no alpha") != std::string::npos);
  EXPECT_TRUE(warned) << "expected a warning that fern_02's texture has no alpha";
  Coverage c = compare_with_cards(fern, 60);
  ASSERT_GT(c.full, 1000);
  EXPECT_EQ(c.cut, c.full);
  EXPECT_EQ(c.outside, 0);
}

}  // namespace
}  // namespace sylva

// Alpha-cutout leaves: on the shared Poly Haven fern, whose leaf shapes live only in the
// base-colour texture's alpha, the ID buffer must follow the leaves, not the cards.
#include <gtest/gtest.h>

#include "core/gl/rasterizer.h"
#include "core/scene/load.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

cv::Mat render_ids(GlContext& ctx, const Scene& scene) {
  Rasterizer r(ctx);
  r.upload(scene);
  OrbitParams orbit;
  orbit.elevation_deg = 60;
  Camera cam = make_orbit_camera(scene.bounds(), orbit, 256, 256);
  RasterRequest req;
  req.targets = static_cast<TargetMask>(Target::Id);
  return r.render(cam, Lighting::three_point(), req).id;
}

TEST(FernCutout, IdBufferFollowsLeafAlphaNotTheCard) {
  Scene fern = load_scene(test::fern_path());
  ASSERT_FALSE(fern.materials.empty());
  ASSERT_EQ(fern.materials[0].alpha_mode, AlphaMode::Mask);
  auto ctx = create_gl_context();
  cv::Mat cut = render_ids(*ctx, fern);
  Scene cards = fern;
  for (Material& m : cards.materials) m.alpha_mode = AlphaMode::Opaque;
  cv::Mat full = render_ids(*ctx, cards);
  int n_cut = cv::countNonZero(cut), n_full = cv::countNonZero(full);
  ASSERT_GT(n_full, 1000);
  // The leaves cover visibly less than their cards...
  EXPECT_LT(n_cut, 0.85 * n_full) << n_cut << " vs " << n_full;
  EXPECT_GT(n_cut, 0.05 * n_full);
  // ...and (almost) only where a card is: cut-out pixels reveal cards behind, which have
  // other ids, so compare coverage, not values.
  cv::Mat outside = (cut != 0) & (full == 0);
  EXPECT_EQ(cv::countNonZero(outside), 0);
}

}  // namespace
}  // namespace sylva

// The watercolor's shadow glaze (passes/watercolor_shadow.h): a slab of leaves between the key
// light and part of a wall of leaves shades that part and not the rest; the shadow is soft (it
// changes gradually across the slab's edge) and follows the world, not the pixels; the glaze
// darkens only where there is paint, more where the shadow is deeper, and turns from the
// pigment's neutral darkening to a cool (blue over red) glaze with warm_cool. The positions it
// reads, unprojected from the depth, are the rasteriser's. Every parameter at both ends:
// tests/styles/test_every_parameter.cpp.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "passes/watercolor_shadow.h"
#include "tests/core/gl/raster_scenes.h"

namespace sylva::test {
namespace {

using watercolor_internal::cell_positions;
using watercolor_internal::CellPositions;
using watercolor_internal::glaze_shadow;
using watercolor_internal::key_shadow;

constexpr int kSize = 128;

// Leaves on the plane z = 0 over x, y in [-1, 1] (the wall the camera sees, one sample per
// 0.05 units) and, when `slab`, a slab of leaves at z = 0.5 over x in [0, 1] between the wall
// and a light on +z.
SurfaceSamples leaves(bool slab) {
  SurfaceSamples s;
  auto add = [&](float x, float y, float z) {
    s.positions.push_back({x, y, z});
    s.normals.push_back({0, 0, 1});
    s.areas.push_back(0.0025f);
    s.clusters.push_back(1);
    s.primitives.push_back(1);
  };
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const float x = -1.0f + 0.05f * (float(i) + 0.5f), y = -1.0f + 0.05f * (float(j) + 0.5f);
      add(x, y, 0.0f);
      if (slab && x > 0.0f) add(x, y, 0.5f);
    }
  s.spacing = 0.05f;
  return s;
}

KeyLight light_from_front() {
  KeyLight k;
  k.on = true;
  k.toward = {0.0f, 0.0f, 1.0f};
  k.sphere = Sphere{{0.0f, 0.0f, 0.25f}, 1.6f};
  return k;
}

// The view looks at the wall from +z, identity view: view space = world space, every pixel on
// the wall (the slab is not drawn: the camera sees the wall through it).
struct Wall {
  cv::Mat position, depth;
  Wall() : position(kSize, kSize, CV_32FC3), depth(kSize, kSize, CV_32FC1, cv::Scalar(5.0f)) {
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        position.at<cv::Vec3f>(y, x) = {2.0f * (float(x) + 0.5f) / kSize - 1.0f,
                                        1.0f - 2.0f * (float(y) + 0.5f) / kSize, 0.0f};
  }
};

float at_x(const cv::Mat& shadow, float world_x) {
  const int x = std::clamp(int((world_x + 1.0f) / 2.0f * float(shadow.cols)), 0, shadow.cols - 1);
  return shadow.at<float>(shadow.rows / 2, x);
}

TEST(WatercolorShadow, TheLeavesBetweenTheLightAndTheWallShadeIt) {
  const Wall wall;
  const cv::Mat shadow = key_shadow({wall.position, wall.depth, glm::mat4(1.0f)}, glm::mat4(1.0f),
                                    leaves(true), light_from_front(), 4, 4.0f);
  ASSERT_FALSE(shadow.empty());
  EXPECT_GT(at_x(shadow, 0.7f), 0.3f) << "behind the slab";
  EXPECT_LT(at_x(shadow, -0.7f), 0.1f) << "in the open";
  // Soft: across the slab's edge the shadow grows through intermediate values.
  EXPECT_GT(at_x(shadow, 0.0f), at_x(shadow, -0.7f) + 0.05f);
  EXPECT_LT(at_x(shadow, 0.0f), at_x(shadow, 0.7f) - 0.05f);
  const cv::Mat open = key_shadow({wall.position, wall.depth, glm::mat4(1.0f)}, glm::mat4(1.0f),
                                  leaves(false), light_from_front(), 4, 4.0f);
  EXPECT_LT(at_x(open, 0.7f), 0.1f) << "no slab, no shadow";
  KeyLight off = light_from_front();
  off.on = false;
  EXPECT_TRUE(key_shadow({wall.position, wall.depth, glm::mat4(1.0f)}, glm::mat4(1.0f),
                         leaves(true), off, 4, 4.0f)
                  .empty());
}

TEST(WatercolorShadow, TheShadowFollowsTheWorld) {
  // The same wall seen after the view moved 0.5 units right: positions in view space shift by
  // -0.5 and view_to_world adds it back, so the shadow stays over the same world place.
  Wall moved;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      moved.position.at<cv::Vec3f>(y, x)[0] -= 0.5f;
  const glm::mat4 to_world = glm::translate(glm::mat4(1.0f), {0.5f, 0.0f, 0.0f});
  const cv::Mat shadow = key_shadow({moved.position, moved.depth, glm::mat4(1.0f)}, to_world,
                                    leaves(true), light_from_front(), 4, 4.0f);
  // Image x of world x is now world x - 0.5.
  EXPECT_GT(at_x(shadow, 0.2f), 0.3f) << "world x 0.7, behind the slab";
  EXPECT_LT(at_x(shadow, -0.9f), 0.1f) << "world x -0.4, in the open";
}

TEST(WatercolorShadow, TheGlazeDarkensPaintByTheShadowInItsHue) {
  cv::Mat shadow(4, 4, CV_32F, cv::Scalar(0));
  shadow.colRange(2, 4).setTo(1.0f);  // the right half in full shadow
  cv::Mat density(kSize, kSize, CV_32FC3, cv::Scalar::all(0));
  density.rowRange(0, kSize / 2).setTo(cv::Scalar::all(1.0));  // paint on the top half
  cv::Mat neutral = density.clone(), cool = density.clone();
  glaze_shadow(shadow, 1.0f, 0.0f, neutral);
  glaze_shadow(shadow, 1.0f, 1.0f, cool);
  const cv::Point lit_paint(10, 10), shaded_paint(kSize - 10, 10),
      shaded_paper(kSize - 10, kSize - 10);
  EXPECT_EQ(neutral.at<cv::Vec3f>(lit_paint), cv::Vec3f(1, 1, 1)) << "no shadow, no glaze";
  EXPECT_EQ(neutral.at<cv::Vec3f>(shaded_paper), cv::Vec3f(0, 0, 0)) << "no paint, no glaze";
  const cv::Vec3f n = neutral.at<cv::Vec3f>(shaded_paint), c = cool.at<cv::Vec3f>(shaded_paint);
  EXPECT_GT(n[1], 1.5f) << "the shadow darkens the paint";
  EXPECT_FLOAT_EQ(n[0], n[2]) << "warm_cool 0: the pigment's own hue";
  EXPECT_LT(c[0], c[2]) << "warm_cool 1: more blue passes than red (BGR densities)";
  EXPECT_NEAR(c[0] + c[1] + c[2], n[0] + n[1] + n[2], 1e-4) << "the same amount of glaze";
  cv::Mat none = density.clone();
  glaze_shadow(shadow, 0.0f, 1.0f, none);
  EXPECT_EQ(cv::norm(none, density, cv::NORM_INF), 0.0) << "strength 0";
}

// The view-space positions the shadow and the turbulence read come from the depth through the
// camera (no position buffer): per cell they are the rasteriser's position target, in a
// perspective and an orthographic view of a sphere, in a picture wider than high.
TEST(WatercolorShadow, PositionsFromTheDepthAreTheRasterisersPositions) {
  Mesh ball;
  add_sphere(ball, glm::vec3(0.3f, -0.2f, 0.1f), 1.0f, 48, 24);
  set_ids(ball, 1, 1);
  const Scene scene = scene_of({ball});
  for (bool ortho : {false, true}) {
    OrbitParams p;
    p.azimuth_deg = 30.0f;
    p.elevation_deg = 20.0f;
    p.ortho = ortho;
    const Camera cam = make_orbit_camera(scene.bounds(), p, 96, 64);
    Rasterizer r(gl());
    r.upload(scene);
    const GBuffer g =
        r.render(cam, Lighting::three_point(), request_of(Target::Depth | Target::Position));
    const CellPositions drawn = cell_positions({g.position, g.depth, cam.proj}, 4);
    const CellPositions unprojected = cell_positions({cv::Mat(), g.depth, cam.proj}, 4);
    EXPECT_EQ(cv::norm(drawn.cover, unprojected.cover, cv::NORM_INF), 0.0) << "ortho " << ortho;
    EXPECT_GT(cv::countNonZero(drawn.cover), 50) << "ortho " << ortho;  // of 24 x 16 cells
    // The sphere (radius 1) lies 2-5 units away: 1e-3 is well under a pixel's width there.
    EXPECT_LT(cv::norm(drawn.mean, unprojected.mean, cv::NORM_INF), 1e-3) << "ortho " << ortho;
  }
}

}  // namespace
}  // namespace sylva::test

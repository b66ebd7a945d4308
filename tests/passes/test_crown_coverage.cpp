// Coverage and crown parts from the scene (passes/crown_coverage.h) and the crown field the ink
// outline follows (passes/ink_abstraction.h): a square facing the camera projects to a density
// of about 1 over its own pixels and its area in total; turned edge-on, to nothing; moved by a
// fraction of a pixel, its density moves with it (no jump); parts are painted back to front by
// their mean depth; the crown field fills small holes, drops small pieces, keeps the frame's
// edge outside, and snapping puts points on its level set.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "passes/crown_coverage.h"
#include "passes/ink_abstraction.h"

namespace sylva::test {
namespace {

// Samples of a w x h rectangle in the plane z = `z` (world = view: the camera looks down -z from
// the origin), centred at (cx, cy), cluster `cluster`, spacing `step`.
void add_rectangle(SurfaceSamples& s, float cx, float cy, float z, float w, float h,
                   uint32_t cluster, float step = 0.01f) {
  for (float y = -h / 2 + step / 2; y < h / 2; y += step)
    for (float x = -w / 2 + step / 2; x < w / 2; x += step) {
      s.positions.push_back({cx + x, cy + y, z});
      s.normals.push_back({0, 0, 1});
      s.areas.push_back(step * step);
      s.clusters.push_back(cluster);
    }
}

// An orthographic camera over [-1, 1]² at `size` px.
Camera ortho_camera(int size) {
  Camera c;
  c.view = glm::mat4(1.0f);
  c.proj = glm::mat4(1.0f);
  c.proj[2][2] = -0.1f;  // z in [-10, 10] maps into the clip range
  c.ortho = true;
  c.width = c.height = size;
  return c;
}

TEST(CrownCoverage, AFacingSquareProjectsToItsArea) {
  SurfaceSamples s;
  add_rectangle(s, 0.0f, 0.0f, -1.0f, 1.0f, 1.0f, 1);
  const Camera cam = ortho_camera(100);  // 50 px per unit
  const cv::Mat d = project_surface_density(s, cam);
  // Total: the square's 1 unit² = 2500 px².
  EXPECT_NEAR(cv::sum(d)[0], 2500.0, 1.0);
  // Inside (away from the rim): about one layer.
  const cv::Scalar inside = cv::mean(d(cv::Rect(35, 35, 30, 30)));
  EXPECT_NEAR(inside[0], 1.0, 0.05);
  EXPECT_EQ(cv::countNonZero(d(cv::Rect(0, 0, 20, 20))), 0);
  // Edge-on it covers nothing.
  for (glm::vec3& n : s.normals)
    n = {1, 0, 0};
  EXPECT_NEAR(cv::sum(project_surface_density(s, cam))[0], 0.0, 1e-6);
}

TEST(CrownCoverage, ASkippedClusterCoversNothing) {
  // The wood's cluster left out: the leaves' coverage alone (the watercolor's thin foliage).
  SurfaceSamples s;
  add_rectangle(s, -0.5f, 0.0f, -1.0f, 0.5f, 0.5f, 1);
  add_rectangle(s, 0.5f, 0.0f, -1.0f, 0.5f, 0.5f, 2);
  const Camera cam = ortho_camera(100);
  const double both = cv::sum(crown_coverage(s, cam, {100, 100}, 1.0))[0];
  const double without_2 = cv::sum(crown_coverage(s, cam, {100, 100}, 1.0, 2))[0];
  EXPECT_NEAR(without_2, 0.5 * both, 0.01 * both);
  EXPECT_NEAR(cv::sum(project_surface_density(s, cam, 1))[0], 625.0, 1.0);
  EXPECT_EQ(cv::countNonZero(project_surface_density(s, cam, 1)(cv::Rect(0, 0, 50, 100))), 0);
}

TEST(CrownCoverage, ASubPixelMoveMovesTheDensityASubPixel) {
  SurfaceSamples a, b;
  add_rectangle(a, 0.0f, 0.0f, -1.0f, 0.5f, 0.5f, 1, 0.037f);
  add_rectangle(b, 0.3f / 50.0f, 0.0f, -1.0f, 0.5f, 0.5f, 1, 0.037f);  // 0.3 px to the right
  const Camera cam = ortho_camera(100);
  const cv::Mat da = crown_coverage(a, cam, {100, 100}, 1.0);
  const cv::Mat db = crown_coverage(b, cam, {100, 100}, 1.0);
  // The coverage's centre of mass moves by the same 0.3 px, and no pixel changes by much.
  auto centre_x = [](const cv::Mat& m) {
    const cv::Moments mo = cv::moments(m);
    return mo.m10 / mo.m00;
  };
  EXPECT_NEAR(centre_x(db) - centre_x(da), 0.3, 0.02);
  double worst = 0;
  cv::minMaxLoc(cv::abs(db - da), nullptr, &worst);
  EXPECT_LT(worst, 0.2);
}

TEST(CrownCoverage, PartsArePaintedBackToFront) {
  SurfaceSamples s;
  add_rectangle(s, -0.2f, 0.0f, -3.0f, 0.8f, 0.8f, 5);  // far
  add_rectangle(s, 0.2f, 0.0f, -1.0f, 0.8f, 0.8f, 9);   // near, overlapping its right half
  add_rectangle(s, 0.0f, -0.8f, -2.0f, 0.4f, 0.2f, 7);  // wood, under both
  const Camera cam = ortho_camera(100);
  const CrownParts p = project_crown_parts(s, cam, 1.0, 0.3f, 7);
  ASSERT_EQ(p.order.size(), 2u);  // the wood left out
  EXPECT_EQ(p.order[0].cluster, 5u);
  EXPECT_EQ(p.order[1].cluster, 9u);
  EXPECT_NEAR(p.order[1].centre.x, 60.0f, 0.5f);  // x = 0.2 units
  EXPECT_EQ(p.label.at<int>(50, 50), 9);          // the overlap: the near part
  EXPECT_EQ(p.label.at<int>(50, 30), 5);
  EXPECT_FLOAT_EQ(p.depth.at<float>(50, 50), 1.0f);
  EXPECT_EQ(p.label.at<int>(90, 50), 0);
  // With the wood painted first it shows where no leaf part covers it, and nowhere else.
  const CrownParts w = project_crown_parts(s, cam, 1.0, 0.3f, 7, 0.3f);
  EXPECT_EQ(w.order.front().cluster, 7u);
  EXPECT_EQ(w.label.at<int>(90, 50), 7);
  EXPECT_EQ(w.label.at<int>(50, 50), 9);
}

// The wood's own smoothing (wood_sigma): two branches 6 px apart are one patch of wood at the
// leaves' smoothing and stay two, with bare paper between them, at a narrower one.
TEST(CrownCoverage, TheWoodKeepsItsBranchesApartAtItsOwnSmoothing) {
  SurfaceSamples s;
  add_rectangle(s, -0.06f, 0.0f, -2.0f, 0.06f, 1.0f, 7);  // two vertical branches, 3 px wide
  add_rectangle(s, 0.06f, 0.0f, -2.0f, 0.06f, 1.0f, 7);   // (x in [-0.09, -0.03], [0.03, 0.09])
  add_rectangle(s, 0.8f, 0.8f, -1.0f, 0.2f, 0.2f, 5);     // leaves away from them
  const Camera cam = ortho_camera(100);
  const CrownParts one = project_crown_parts(s, cam, 4.0, 0.3f, 7, 0.3f);
  EXPECT_EQ(one.label.at<int>(50, 50), 7);  // the gap between them painted as wood
  const CrownParts two = project_crown_parts(s, cam, 4.0, 0.3f, 7, 0.3f, 1.0);
  EXPECT_EQ(two.label.at<int>(50, 50), 0);  // the gap bare
  EXPECT_EQ(two.label.at<int>(50, 47), 7);  // each branch wood
  EXPECT_EQ(two.label.at<int>(50, 53), 7);
  EXPECT_EQ(one.label.at<int>(10, 90), 5);  // the leaves (y up) as before
  EXPECT_EQ(two.label.at<int>(10, 90), 5);
}

// In a scene of many plants the plants are the parts: two instances' foliage (clusters 5 and 9 in
// the first, 6 in the second, so clusters do not follow instances), their wood left out.
TEST(CrownCoverage, PlantsArePaintedBackToFrontByInstance) {
  SurfaceSamples s;
  add_rectangle(s, -0.3f, 0.2f, -3.0f, 0.6f, 0.4f, 5);  // instance 1 (far): two clusters
  add_rectangle(s, -0.3f, -0.2f, -3.0f, 0.6f, 0.4f, 9);
  s.instances.assign(s.size(), 1u);
  add_rectangle(s, 0.2f, 0.0f, -1.0f, 0.6f, 0.8f, 6);   // instance 2 (near), over its right side
  add_rectangle(s, 0.2f, -0.8f, -1.0f, 0.1f, 0.2f, 7);  // its trunk (the wood cluster)
  s.instances.resize(s.size(), 2u);
  const Camera cam = ortho_camera(100);
  const CrownParts p = project_plant_parts(s, cam, 1.0, 0.2f, 7);
  ASSERT_EQ(p.order.size(), 2u);
  EXPECT_EQ(p.order[0].cluster, 1u);  // the far plant first
  EXPECT_EQ(p.order[1].cluster, 2u);
  EXPECT_EQ(p.label.at<int>(50, 25), 1);  // one label over both of its clusters
  EXPECT_EQ(p.label.at<int>(40, 25), 1);
  EXPECT_EQ(p.label.at<int>(50, 55), 2);  // the overlap: the near plant
  EXPECT_FLOAT_EQ(p.depth.at<float>(50, 55), 1.0f);
  EXPECT_EQ(p.label.at<int>(90, 60), 0);  // the trunk is no plant part
  // Samples without instance ids (a scene of one plant): no parts.
  SurfaceSamples one = s;
  one.instances.clear();
  EXPECT_TRUE(project_plant_parts(one, cam, 1.0, 0.2f, 7).order.empty());
}

TEST(CrownField, FillsSmallHolesDropsSmallPiecesAndKeepsTheEdgeOut) {
  cv::Mat cover(200, 200, CV_32FC1, cv::Scalar(0));
  cover(cv::Rect(0, 40, 120, 120)).setTo(1.0f);  // cut by the frame's left edge
  cover(cv::Rect(50, 90, 6, 6)).setTo(0.0f);     // a hole smaller than (2 x detail)²
  cover(cv::Rect(20, 60, 36, 36)).setTo(0.0f);   // a hole larger
  cover(cv::Rect(170, 10, 8, 8)).setTo(1.0f);    // a piece smaller than (4 x detail)²
  const CrownField f = crown_field(cover, 10.0);
  EXPECT_NE(f.body.at<uint8_t>(93, 53), 0);   // filled
  EXPECT_EQ(f.body.at<uint8_t>(78, 38), 0);   // kept
  EXPECT_EQ(f.body.at<uint8_t>(14, 174), 0);  // dropped
  EXPECT_EQ(f.body.at<uint8_t>(100, 0), 0);   // the frame's edge is outside
  EXPECT_NE(f.body.at<uint8_t>(100, 1), 0);
  // The outline encloses the plant: it lies outside the solid edge at x = 120.
  int x = 120;
  while (x < 200 && f.body.at<uint8_t>(100, x))
    ++x;
  EXPECT_GT(x, 121);
  EXPECT_LT(x, 127);  // about 0.4 x detail
}

TEST(CrownField, SnappingPutsPointsOnTheLevelSet) {
  cv::Mat field(50, 50, CV_32FC1);
  for (int y = 0; y < 50; ++y)
    for (int x = 0; x < 50; ++x)
      field.at<float>(y, x) = std::clamp((30.0f - (x + 0.5f)) / 10.0f, 0.0f, 1.0f);  // 0.2 at x 28
  std::vector<cv::Point2f> line = {{27.0f, 10.0f}, {29.0f, 20.0f}, {45.0f, 30.0f}};
  snap_to_level(line, field, kCrownLevel, 1.5f);
  EXPECT_NEAR(line[0].x, 28.0f, 0.05f);
  EXPECT_NEAR(line[1].x, 28.0f, 0.05f);
  EXPECT_FLOAT_EQ(line[2].x, 45.0f);  // too far (and on a flat part): stays
  EXPECT_FLOAT_EQ(line[0].y, 10.0f);
}

TEST(CrownField, ThinPartsAreTheLongPiecesAwayFromTheBody) {
  cv::Mat plant(120, 120, CV_8UC1, cv::Scalar(0)), body = plant.clone();
  body(cv::Rect(20, 20, 50, 40)).setTo(255);
  plant(cv::Rect(20, 20, 50, 40)).setTo(255);
  plant(cv::Rect(40, 60, 2, 50)).setTo(255);  // a strand hanging below
  plant(cv::Rect(90, 30, 3, 3)).setTo(255);   // a speck
  plant(cv::Rect(20, 60, 50, 3)).setTo(255);  // a sliver along the body's edge
  const cv::Mat thin = thin_parts(plant, body, 10.0);
  EXPECT_NE(thin.at<uint8_t>(90, 40), 0);
  EXPECT_EQ(thin.at<uint8_t>(31, 91), 0);
  EXPECT_EQ(thin.at<uint8_t>(61, 60), 0);
  EXPECT_EQ(cv::countNonZero(thin_parts(plant, body, 1.0)), 0);
}

}  // namespace
}  // namespace sylva::test

// Blob geometry (Dudley 2005 §4.2.1, §5.1): the closed B-spline (closed, C2), Catmull-Rom
// through its keys, shrink-wrap landing on the mask at every extreme of its parameters, the
// height field's peaks and normals, and outlines found in an id buffer.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "npr/blob_outlines.h"
#include "npr/blob_shape.h"
#include "npr/bspline.h"
#include "npr/shrink_wrap.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

bool on_mask(const cv::Mat& mask, glm::vec2 p) {
  const int x = int(std::floor(p.x)), y = int(std::floor(p.y));
  return x >= 0 && y >= 0 && x < mask.cols && y < mask.rows && mask.at<uint8_t>(y, x) != 0;
}

cv::Mat disc(int size, glm::vec2 c, float r) {
  cv::Mat m = cv::Mat::zeros(size, size, CV_8UC1);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      if (glm::length(glm::vec2(x + 0.5f, y + 0.5f) - c) <= r) m.at<uint8_t>(y, x) = 255;
  return m;
}

// Irregular leaves: a few random ellipses (deterministic).
cv::Mat leafy(int size) {
  cv::Mat m = cv::Mat::zeros(size, size, CV_8UC1);
  cv::RNG rng(7);
  for (int i = 0; i < 25; ++i)
    cv::ellipse(m,
                cv::Point(rng.uniform(size / 4, 3 * size / 4), rng.uniform(size / 4, 3 * size / 4)),
                cv::Size(rng.uniform(2, 8), rng.uniform(1, 4)), rng.uniform(0.0, 180.0), 0, 360,
                cv::Scalar(255), cv::FILLED);
  return m;
}

TEST(BSpline, ClosedAndC2) {
  const std::vector<glm::vec2> p = {{0, 0}, {10, 1}, {12, 9}, {3, 12}, {-4, 6}};
  const double n = double(p.size());
  EXPECT_NEAR(glm::length(closed_bspline_point(p, 0.0) - closed_bspline_point(p, n)), 0.0, 1e-4);
  // At every knot, the left and right first and second derivatives agree (finite differences
  // of step h, which are exact up to O(h) for the jump of a cubic's third derivative).
  const double h = 1e-3;
  for (int k = 0; k < int(p.size()); ++k) {
    auto at = [&](double t) { return glm::dvec2(closed_bspline_point(p, t)); };
    const glm::dvec2 d1l = (at(k) - at(k - h)) / h, d1r = (at(k + h) - at(k)) / h;
    const glm::dvec2 d2l = (at(k) - 2.0 * at(k - h) + at(k - 2 * h)) / (h * h);
    const glm::dvec2 d2r = (at(k + 2 * h) - 2.0 * at(k + h) + at(k)) / (h * h);
    EXPECT_LT(glm::length(d1l - d1r), 0.05) << "knot " << k;
    EXPECT_LT(glm::length(d2l - d2r), 1.0) << "knot " << k;  // float evaluation noise
  }
  // A B-spline stays in the convex hull: its points never leave the control points' box.
  for (const glm::vec2& q : sample_closed_bspline(p, 8)) {
    EXPECT_GE(q.x, -4.0f);
    EXPECT_LE(q.x, 12.0f);
  }
  EXPECT_EQ(sample_closed_bspline(p, 8).size(), 40u);
  // One point: the curve is that point.
  EXPECT_EQ(closed_bspline_point({{3, 4}}, 0.7), glm::vec2(3, 4));
}

TEST(CatmullRom, PassesThroughKeysAndDefinesEnds) {
  const std::vector<glm::vec2> k = {{0, 0}, {1, 2}, {3, 3}, {6, 1}};
  for (size_t i = 0; i < k.size(); ++i)
    EXPECT_NEAR(glm::length(catmull_rom(k, double(i)) - k[i]), 0.0, 1e-6);
  EXPECT_EQ(catmull_rom(k, -5.0), k.front());  // clamped
  EXPECT_EQ(catmull_rom(k, 99.0), k.back());
  // Two keys: linear.
  EXPECT_NEAR(catmull_rom(std::vector<float>{2.0f, 4.0f}, 0.25), 2.5f, 1e-6);
  EXPECT_EQ(catmull_rom(std::vector<float>{7.0f}, 0.5), 7.0f);
}

TEST(ShrinkWrap, DiscGivesANearCircle) {
  const cv::Mat m = disc(101, {50.5f, 50.5f}, 30.0f);
  const ShrinkWrap w = shrink_wrap(m, {});
  ASSERT_EQ(w.points.size(), 20u);
  EXPECT_NEAR(w.center.x, 50.5f, 0.05f);
  EXPECT_NEAR(w.center.y, 50.5f, 0.05f);
  for (const glm::vec2& p : w.points) {
    EXPECT_TRUE(on_mask(m, p));
    // 20 % steps from radius 31 land at most one step (20 % of ~31 px) inside the rim.
    EXPECT_GT(glm::length(p - w.center), 30.0f - 0.2f * 31.0f - 1.0f);
  }
  // Smaller steps hug the rim: within a pixel and a half.
  ShrinkWrapParams fine;
  fine.step = 0.01f;
  for (const glm::vec2& p : shrink_wrap(m, fine).points)
    EXPECT_NEAR(glm::length(p - w.center), 30.0f, 1.5f);
  // Point 0 starts straight up (image y down), and they go clockwise on screen.
  EXPECT_LT(w.points[0].y, w.center.y);
  EXPECT_GT(w.points[5].x, w.center.x);
}

TEST(ShrinkWrap, PointsSitOnTheRimAndMoveWithIt) {
  // Landed points are moved back to the rim by bisection: within a pixel of it at any step, and
  // a disc moved by a fraction of a pixel moves them by about as much, not by whole steps.
  const cv::Mat a = disc(101, {50.5f, 50.5f}, 30.0f), b = disc(101, {52.0f, 50.5f}, 30.0f);
  for (float step : {0.05f, 0.2f, 0.5f}) {
    ShrinkWrapParams p;
    p.step = step;
    const ShrinkWrap wa = shrink_wrap(a, p), wb = shrink_wrap(b, p);
    ASSERT_EQ(wa.points.size(), wb.points.size());
    for (size_t i = 0; i < wa.points.size(); ++i) {
      EXPECT_NEAR(glm::length(wa.points[i] - wa.center), 30.0f, 1.2f) << step;
      EXPECT_LT(glm::length((wb.points[i] - wb.center) - (wa.points[i] - wa.center)), 1.6f) << step;
    }
  }
}

TEST(ShrinkWrap, ExtremesLandOnTheMask) {
  const cv::Mat m = leafy(120);
  for (int n : {3, 20, 200, 512})
    for (float step : {0.01f, 0.2f, 1.0f}) {
      ShrinkWrapParams p;
      p.control_points = n;
      p.step = step;
      const ShrinkWrap w = shrink_wrap(m, p);
      ASSERT_EQ(int(w.points.size()), n);
      for (const glm::vec2& q : w.points)
        EXPECT_TRUE(on_mask(m, q)) << n << " points, step " << step;
    }
  // Step 100 %: every point jumps to the centre, or (off the leaves) the pixel nearest it.
  const cv::Mat ring = disc(64, {32, 32}, 20) - disc(64, {32, 32}, 10);
  ShrinkWrapParams jump;
  jump.step = 1.0f;
  const ShrinkWrap r = shrink_wrap(ring, jump);
  for (const glm::vec2& q : r.points) {
    EXPECT_TRUE(on_mask(ring, q));
    EXPECT_EQ(q, r.points[0]);
  }
}

TEST(ShrinkWrap, OnePixelBorderAndEmpty) {
  cv::Mat one = cv::Mat::zeros(9, 9, CV_8UC1);
  one.at<uint8_t>(0, 8) = 255;  // a single pixel in the image corner
  const ShrinkWrap w = shrink_wrap(one, {});
  ASSERT_EQ(w.points.size(), 20u);
  for (const glm::vec2& q : w.points)
    EXPECT_TRUE(on_mask(one, q));
  // A cluster cut by the image border: start points lie outside the image, still land.
  const cv::Mat cut = disc(40, {2, 20}, 15);
  for (const glm::vec2& q : shrink_wrap(cut, {}).points)
    EXPECT_TRUE(on_mask(cut, q));
  EXPECT_TRUE(shrink_wrap(cv::Mat::zeros(5, 5, CV_8UC1), {}).empty());
}

TEST(ShrinkWrap, ParameterRanges) {
  auto where = [](int n, float step) {
    return test::where_of([&] { validate_shrink_wrap({n, step}, "blobs"); });
  };
  EXPECT_EQ(where(3, 1.0f), "no error");
  EXPECT_EQ(where(512, 0.001f), "no error");
  EXPECT_EQ(where(2, 0.2f), "blobs.control_points");
  EXPECT_EQ(where(513, 0.2f), "blobs.control_points");
  EXPECT_EQ(where(20, 0.0f), "blobs.step");
  EXPECT_EQ(where(20, 1.01f), "blobs.step");
  EXPECT_EQ(where(20, std::nanf("")), "blobs.step");
}

TEST(BlobShape, PeaksAndNormals) {
  std::vector<glm::vec2> pts;
  for (int i = 0; i < 30; ++i) {
    const float a = float(2 * M_PI * i / 30);
    pts.emplace_back(50 + 20 * std::sin(a), 50 - 20 * std::cos(a));
  }
  const glm::vec2 c(50, 50);
  const std::vector<glm::vec2> rc = regional_centers(pts, c, 3);
  ASSERT_EQ(rc.size(), 3u);
  for (const glm::vec2& r : rc)
    EXPECT_NEAR(glm::length(r - c), 0.5f * 20 * 3 / M_PI * std::sin(M_PI / 3), 0.5f);
  EXPECT_EQ(regional_centers(pts, c, 100).size(), 30u);  // clamped to the points
  const BlobShape s = make_blob_shape(pts, c, 3, 0.5f);
  EXPECT_NEAR(s.height, 0.5f * 40.0f, 1e-3f);
  for (const glm::vec2& r : rc)
    EXPECT_LE(blob_height(s, r), s.height + 1e-4f);
  EXPECT_GT(blob_height(s, rc[0]), 0.5f * s.height);
  EXPECT_LT(blob_height(s, {0, 0}), 0.01f * s.height);
  // Right of everything the surface falls to the right: the normal leans right (+x); below
  // the blob in the image (view -y) it leans down.
  EXPECT_GT(blob_normal(s, {80, 50}).x, 0.1f);
  EXPECT_LT(blob_normal(s, {50, 80}).y, -0.1f);
  EXPECT_NEAR(glm::length(blob_normal(s, {61, 37})), 1.0f, 1e-5f);
  const BlobShape flat = make_blob_shape(pts, c, 3, 0.0f);
  EXPECT_EQ(blob_normal(flat, {60, 40}), glm::vec3(0, 0, 1));
}

TEST(BlobOutlines, PerClusterDepthOrderAndExclusion) {
  cv::Mat id = cv::Mat::zeros(64, 64, CV_32SC1), depth = cv::Mat::zeros(64, 64, CV_32FC1);
  cv::circle(id, {20, 20}, 10, cv::Scalar(3), cv::FILLED);
  cv::circle(depth, {20, 20}, 10, cv::Scalar(5.0), cv::FILLED);
  cv::circle(id, {40, 40}, 12, cv::Scalar(1), cv::FILLED);
  cv::circle(depth, {40, 40}, 12, cv::Scalar(2.0), cv::FILLED);
  depth.at<float>(40, 40) = 1.5f;
  cv::rectangle(id, cv::Rect(0, 60, 64, 4), cv::Scalar(9), cv::FILLED);  // trunk
  const auto blobs = find_blob_outlines(id, depth, 9, {});
  ASSERT_EQ(blobs.size(), 2u);
  EXPECT_EQ(blobs[0].cluster, 1u);
  EXPECT_EQ(blobs[1].cluster, 3u);
  EXPECT_FLOAT_EQ(blobs[0].min_depth, 1.5f);
  EXPECT_FLOAT_EQ(blobs[1].min_depth, 5.0f);
  for (const BlobOutline& b : blobs)
    for (const glm::vec2& p : b.wrap.points)
      EXPECT_EQ(uint32_t(id.at<int32_t>(int(p.y), int(p.x))), b.cluster);
  // Farthest first.
  EXPECT_EQ(painter_order(blobs), (std::vector<size_t>{1, 0}));
}

TEST(BlobOutlines, CloseGapsJoinsNearLeavesOnly) {
  cv::Mat m = cv::Mat::zeros(40, 60, CV_8UC1);
  cv::rectangle(m, cv::Rect(5, 10, 20, 20), cv::Scalar(255), cv::FILLED);
  cv::rectangle(m, cv::Rect(31, 10, 20, 20), cv::Scalar(255), cv::FILLED);  // 6 px gap
  EXPECT_EQ(close_gaps(m, 2.0f).at<uint8_t>(20, 28), 0);    // gap wider than 2 r stays
  EXPECT_EQ(close_gaps(m, 4.0f).at<uint8_t>(20, 28), 255);  // gap narrower than 2 r closes
  EXPECT_EQ(cv::countNonZero(close_gaps(m, 0.0f) != m), 0);
  // Closing never removes a pixel, and never grows a convex shape past itself much.
  const cv::Mat c = close_gaps(m, 4.0f);
  EXPECT_EQ(cv::countNonZero(m & ~c), 0);
  EXPECT_EQ(c.at<uint8_t>(5, 28), 0);
  // A cluster cut by the image border keeps its border pixels.
  cv::Mat edge = cv::Mat::zeros(20, 20, CV_8UC1);
  cv::rectangle(edge, cv::Rect(0, 0, 6, 20), cv::Scalar(255), cv::FILLED);
  EXPECT_EQ(cv::countNonZero(close_gaps(edge, 5.0f) != edge), 0);
}

}  // namespace
}  // namespace sylva

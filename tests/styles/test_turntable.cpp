// The turntable's camera path, frame ranges and flicker metric.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "styles/turntable.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

using test::where_of;

Camera base_camera() {
  OrbitParams o;
  o.azimuth_deg = 20.0f;
  o.elevation_deg = 10.0f;
  return make_orbit_camera(Sphere{{1.0f, 2.0f, 3.0f}, 2.0f}, o, 64, 48);
}

TEST(Turntable, CameraTurnsAboutTheAxisThroughTheCentre) {
  const Camera base = base_camera();
  const glm::vec3 centre(1.0f, 2.0f, 3.0f);
  TurntablePath path;
  path.frames = 4;
  const Camera c0 = turntable_camera(base, centre, path, 0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      EXPECT_NEAR(c0.view[i][j], base.view[i][j], 1e-6f);
  for (char axis : {'x', 'y', 'z'}) {
    path.axis = axis;
    const Camera c1 = turntable_camera(base, centre, path, 1);  // 90 degrees
    const glm::vec3 a = base.eye - centre, b = c1.eye - centre;
    EXPECT_NEAR(glm::length(a), glm::length(b), 1e-4f) << axis;
    const int k = axis == 'x' ? 0 : axis == 'y' ? 1 : 2;
    EXPECT_NEAR(a[k], b[k], 1e-4f) << axis;  // the axis component is kept
    glm::vec3 pa = a, pb = b;
    pa[k] = pb[k] = 0.0f;
    EXPECT_NEAR(glm::dot(pa, pb), 0.0f, 1e-3f) << axis;  // a quarter turn in the plane
    // The centre stays where it was on screen.
    const glm::vec4 s0 = base.proj * base.view * glm::vec4(centre, 1.0f);
    const glm::vec4 s1 = c1.proj * c1.view * glm::vec4(centre, 1.0f);
    EXPECT_NEAR(s0.x / s0.w, s1.x / s1.w, 1e-5f);
    EXPECT_NEAR(s0.y / s0.w, s1.y / s1.w, 1e-5f);
  }
  // Zoom magnifies the image about its centre and keeps depth.
  path.axis = 'y';
  path.zoom = 2.0f;
  const Camera z = turntable_camera(base, centre, path, 0);
  const glm::vec3 p = centre + glm::vec3(0.5f, 0.3f, 0.0f);
  const glm::vec4 q0 = base.proj * base.view * glm::vec4(p, 1.0f);
  const glm::vec4 q1 = z.proj * z.view * glm::vec4(p, 1.0f);
  EXPECT_NEAR(q1.x / q1.w, 2.0f * q0.x / q0.w, 1e-5f);
  EXPECT_NEAR(q1.z / q1.w, q0.z / q0.w, 1e-6f);
}

TEST(Turntable, PathLimits) {
  auto check = [](auto set) {
    TurntablePath p;
    set(p);
    return where_of([&] { validate_turntable(p); });
  };
  EXPECT_EQ(check([](TurntablePath& p) { p.frames = 1; }), "no error");
  EXPECT_EQ(check([](TurntablePath& p) { p.frames = 100000; }), "no error");
  EXPECT_EQ(check([](TurntablePath& p) { p.frames = 0; }), "--frames");
  EXPECT_EQ(check([](TurntablePath& p) { p.frames = 100001; }), "--frames");
  EXPECT_EQ(check([](TurntablePath& p) { p.degrees = -36000.0f; }), "no error");
  EXPECT_EQ(check([](TurntablePath& p) { p.degrees = 36001.0f; }), "--degrees");
  EXPECT_EQ(check([](TurntablePath& p) { p.degrees = NAN; }), "--degrees");
  EXPECT_EQ(check([](TurntablePath& p) { p.axis = 'w'; }), "--axis");
  EXPECT_EQ(check([](TurntablePath& p) { p.zoom = 100.0f; }), "no error");
  EXPECT_EQ(check([](TurntablePath& p) { p.zoom = 0.0f; }), "--zoom");
  EXPECT_EQ(check([](TurntablePath& p) { p.zoom = 100.5f; }), "--zoom");
  // Many frames and turns: every camera finite, the last frame just short of the full turn.
  TurntablePath p;
  p.frames = 100000;
  p.degrees = 36000.0f;
  const Camera base = base_camera();
  const Camera last = turntable_camera(base, {1, 2, 3}, p, p.frames - 1);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      EXPECT_TRUE(std::isfinite(last.view[i][j]));
}

TEST(Turntable, FrameRanges) {
  EXPECT_EQ(parse_frame_range("", 10).end, 10);
  EXPECT_EQ(parse_frame_range(":", 10).begin, 0);
  const FrameRange r = parse_frame_range("2:5", 10);
  EXPECT_EQ(r.begin, 2);
  EXPECT_EQ(r.end, 5);
  EXPECT_EQ(parse_frame_range("7:", 10).end, 10);
  EXPECT_EQ(parse_frame_range(":3", 10).begin, 0);
  EXPECT_EQ(parse_frame_range("9:10", 10).begin, 9);
  for (const char* bad : {"5:2", "3:3", "0:11", "-1:3", "a:b", "3", "1:2:3", "1.5:3"})
    EXPECT_EQ(where_of([&] { parse_frame_range(bad, 10); }), "--frame-range") << bad;
}

TEST(Turntable, FlickerIsTheMeanChangeInsideTheMask) {
  cv::Mat a(4, 4, CV_8UC4, cv::Scalar(10, 20, 30, 255)), b = a.clone();
  cv::Mat none = cv::Mat::zeros(4, 4, CV_8UC1), all(4, 4, CV_8UC1, cv::Scalar(1));
  EXPECT_EQ(frame_flicker(a, b, all, all), 0.0);
  b.at<cv::Vec4b>(0, 0) = cv::Vec4b(40, 20, 30, 255);  // +30 in one channel of one pixel
  EXPECT_NEAR(frame_flicker(a, b, all, all), 30.0 / 3.0 / 16.0, 1e-12);
  cv::Mat one = none.clone();
  one.at<uchar>(0, 0) = 1;
  EXPECT_NEAR(frame_flicker(a, b, one, none), 10.0, 1e-12);  // either frame's mask counts
  EXPECT_NEAR(frame_flicker(a, b, none, one), 10.0, 1e-12);
  EXPECT_EQ(frame_flicker(a, b, none, none), 0.0);
  b.at<cv::Vec4b>(3, 3) = cv::Vec4b(0, 0, 0, 0);  // outside the mask: ignored
  EXPECT_NEAR(frame_flicker(a, b, one, one), 10.0, 1e-12);
}

}  // namespace
}  // namespace sylva

// Tone strokes (passes/hatching.h) on a synthetic plane facing the camera: the hatching's
// density rises monotonically with darkness along a shading ramp and crosses only in the
// darkest part, a lit plane gets none, strokes are anchored to the scene (the camera moved by
// a few px moves them with the surface), the result is the same bytes twice, and stipples are
// dots. Every pen.* parameter at both ends of its range: tests/styles/test_every_parameter.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include "core/error.h"
#include "core/stroke_render.h"

#include "passes/hatching.h"

namespace sylva::test {
namespace {

constexpr int kSize = 256;
constexpr double kUnitsPerPx = 0.01;  // the plane is 2.56 scene units across

// A plane at depth 5 facing the camera, shifted by `shift` px to the right on screen; its
// colour's luma falls from 230 at the left edge to 20 at the right (a shading ramp fixed to
// the surface), or is `flat` everywhere.
ToneImages plane(int shift = 0, int flat = -1) {
  ToneImages in;
  in.color = cv::Mat(kSize, kSize, CV_8UC4);
  in.position = cv::Mat(kSize, kSize, CV_32FC3);
  in.id = cv::Mat(kSize, kSize, CV_32SC1, cv::Scalar(1));
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double u = double(x - shift) + 0.5;  // surface coordinate in px
      const int grey = flat >= 0 ? flat : int(std::lround(230.0 - 210.0 * u / kSize));
      const uint8_t g = uint8_t(std::clamp(grey, 0, 255));
      in.color.at<cv::Vec4b>(y, x) = {g, g, g, 255};
      in.position.at<cv::Vec3f>(y, x) = {float((x + 0.5 - kSize / 2) * kUnitsPerPx),
                                         float((kSize / 2 - y - 0.5) * kUnitsPerPx), -5.0f};
    }
  return in;
}

ToneView view(int shift = 0) {
  ToneView v;
  // The camera moved left by `shift` px: world = view + shift px along x.
  v.view = glm::mat4(1.0f);
  v.view[3][0] = float(shift * kUnitsPerPx);
  v.units_per_px = kUnitsPerPx;
  const float half = float(kSize / 2 * kUnitsPerPx);
  v.proj = glm::ortho(-half, half, -half, half, 1.0f, 10.0f);  // the plane's pixels, as drawn
  return v;
}

PenParams hatching() {
  PenParams p;
  p.tone = PenTone::Hatching;
  p.lightest = 0.2f;
  p.angle_jitter = 0.0f;  // one region: hatching at 60 degrees, crossing at 150
  return p;
}

// Strokes whose centre lies in each of `bands` vertical bands, by layer (0 = along pen.angle).
std::vector<int> per_band(const StrokeDrawing& d, int bands, bool crossing = false) {
  std::vector<int> n(size_t(bands), 0);
  for (const Stroke& s : d.strokes) {
    const glm::vec2 c = 0.5f * (s.points.front() + s.points.back());
    const glm::vec2 dir = s.points.back() - s.points.front();
    const bool crosses = std::abs(dir.x) > std::abs(dir.y);  // 150 degrees, not 60
    if (crosses != crossing) continue;
    n[size_t(std::clamp(int(c.x / kSize * bands), 0, bands - 1))]++;
  }
  return n;
}

TEST(Hatching, DensityRisesWithDarknessAlongARamp) {
  const StrokeDrawing d = tone_strokes(plane(), view(), hatching(), 10.0);
  ASSERT_GT(d.strokes.size(), 50u);
  const std::vector<int> n = per_band(d, 4);
  for (size_t i = 1; i < n.size(); ++i)
    EXPECT_GE(n[i], n[i - 1]) << "band " << i;
  EXPECT_GT(n[3], 2 * std::max(1, n[1]));
  const std::vector<int> cross = per_band(d, 4, true);
  EXPECT_EQ(cross[0], 0);
  EXPECT_GT(cross[3], 0);
  for (const Stroke& s : d.strokes) {
    EXPECT_EQ(s.cls, LineClass::Tone);
    EXPECT_EQ(s.points.size(), 2u);
  }
}

TEST(Hatching, AnEvenlyLitPlaneGetsNoTone) {
  // The tone's range comes from the plant's own quantiles: a uniform tone has none.
  EXPECT_TRUE(tone_strokes(plane(0, 128), view(), hatching(), 10.0).strokes.empty());
  PenParams none = hatching();
  none.tone = PenTone::None;
  EXPECT_TRUE(tone_strokes(plane(), view(), none, 10.0).strokes.empty());
}

// Of a's strokes away from the frame's edges (`inside`, where the clipping or the frame do not
// differ), how many reappear in b moved by `shift` px to the right.
int moved_with_the_surface(const StrokeDrawing& a, const StrokeDrawing& b, int shift, int& inside) {
  int found = 0;
  inside = 0;
  for (const Stroke& s : a.strokes) {
    const glm::vec2 c = 0.5f * (s.points.front() + s.points.back());
    if (c.x < 30 || c.x > kSize - 30 || c.y < 30 || c.y > kSize - 30) continue;
    ++inside;
    for (const Stroke& t : b.strokes)
      if (glm::distance(s.points.front() + glm::vec2(shift, 0), t.points.front()) < 0.6f &&
          glm::distance(s.points.back() + glm::vec2(shift, 0), t.points.back()) < 0.6f) {
        ++found;
        break;
      }
  }
  return found;
}

TEST(Hatching, StrokesAreAnchoredToTheSurface) {
  const int shift = 3;
  const StrokeDrawing a = tone_strokes(plane(), view(), hatching(), 10.0);
  const StrokeDrawing b = tone_strokes(plane(shift), view(shift), hatching(), 10.0);
  // Most strokes of a reappear in b moved with the surface.
  int inside = 0;
  const int found = moved_with_the_surface(a, b, shift, inside);
  ASSERT_GT(inside, 20);
  EXPECT_GE(found, inside * 9 / 10) << found << " of " << inside;
}

// The plane's surface as the scene's samples: world z = -5 over |x|, |y| < 2, cluster 1.
std::shared_ptr<const SurfaceSamples> plane_samples() {
  auto s = std::make_shared<SurfaceSamples>();
  const float step = 0.01f;
  for (float y = -2.0f; y < 2.0f; y += step)
    for (float x = -2.0f; x < 2.0f; x += step) {
      s->positions.push_back({x + step / 2, y + step / 2, -5.0f});
      s->normals.push_back({0, 0, 1});
      s->areas.push_back(step * step);
      s->clusters.push_back(1);
    }
  return s;
}

TEST(Hatching, WithSurfaceSamplesTheAnchorsAreTheScenes) {
  // With the scene's samples the cubes come from the scene and the region from its projected
  // crown: the strokes of a moved view are the same strokes, moved with the surface.
  const int shift = 3;
  ToneImages a_in = plane(), b_in = plane(shift);
  a_in.samples = b_in.samples = plane_samples();
  ToneView va = view(), vb = view(shift);
  va.ortho = vb.ortho = true;
  const StrokeDrawing a = tone_strokes(a_in, va, hatching(), 10.0);
  const StrokeDrawing b = tone_strokes(b_in, vb, hatching(), 10.0);
  int inside = 0;
  const int found = moved_with_the_surface(a, b, shift, inside);
  ASSERT_GT(inside, 20);
  EXPECT_GE(found, inside * 95 / 100) << found << " of " << inside;
  // The density still follows the ramp.
  const std::vector<int> n = per_band(a, 4);
  EXPECT_GT(n[3], 2 * std::max(1, n[1]));
}

TEST(Hatching, SameInputSameBytes) {
  const ToneImages in = plane();
  const StrokeDrawing a = tone_strokes(in, view(), hatching(), 10.0);
  const StrokeDrawing b = tone_strokes(in, view(), hatching(), 10.0);
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (size_t i = 0; i < a.strokes.size(); ++i)
    EXPECT_EQ(a.strokes[i].points, b.strokes[i].points);
  PenParams other = hatching();
  other.seed = 2;
  const StrokeDrawing c = tone_strokes(in, view(), other, 10.0);
  EXPECT_FALSE(c.strokes.size() == a.strokes.size() &&
               c.strokes.front().points == a.strokes.front().points);
}

TEST(Hatching, StipplesAreDots) {
  PenParams p = hatching();
  p.tone = PenTone::Stipple;
  const StrokeDrawing d = tone_strokes(plane(), view(), p, 10.0);
  ASSERT_FALSE(d.strokes.empty());
  for (const Stroke& s : d.strokes)
    EXPECT_EQ(s.points.size(), 1u);
  const std::vector<int> n = per_band(d, 4);
  EXPECT_GT(n[3], n[0]);
}

TEST(Hatching, DarkestMustExceedLightest) {
  PenParams p = hatching();
  p.lightest = 0.6f;
  p.darkest = 0.5f;
  EXPECT_THROW(validate_pen_params(p), InputError);
  p.darkest = 0.7f;
  EXPECT_NO_THROW(validate_pen_params(p));
}

}  // namespace
}  // namespace sylva::test

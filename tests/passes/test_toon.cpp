// Toon shading (Decaudin 1996): band count, order and boundaries on an N·L ramp, explicit
// thresholds, the ka weight, parameter validation and extremes, determinism, background,
// key/sum lights, cast shadows from a synthetic shadow map, and graph culling (no ID buffer).
// With SYLVA_TOON_LOOK_DIR set, also writes a ramp and a sphere as PNGs for a visual check.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "passes/toon.h"

namespace sylva::test {
namespace {

constexpr float kPi = 3.14159265358979f;

float decode(uint8_t v) {
  const float c = float(v) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

uint8_t encode(float lin) {
  lin = std::clamp(lin, 0.0f, 1.0f);
  const float c = lin <= 0.0031308f ? lin * 12.92f : 1.055f * std::pow(lin, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(c * 255.0f));
}

// One directional light along view +Z (toward the viewer), camera-fixed.
Lighting headlight() {
  Lighting l;
  Light key;
  key.vector = glm::vec3(0.0f, 0.0f, 1.0f);
  key.color = glm::vec3(1.0f);
  l.lights = {key};
  return l;
}

const cv::Vec4b kAlbedo(60, 170, 120, 255);  // BGRA sRGB, a leaf green

// Normals sweeping from facing away from +Z (x = 0) to facing it (x = width - 1):
// N·L = cos(theta), theta = pi (1 - (x + 0.5) / width), so N·L rises monotonically.
ToonImages ramp(int width = 400, int height = 4, float ka = 1.0f) {
  ToonImages in;
  in.normal.create(height, width, CV_32FC3);
  for (int x = 0; x < width; ++x) {
    const float theta = kPi * (1.0f - (float(x) + 0.5f) / float(width));
    for (int y = 0; y < height; ++y)
      in.normal.at<cv::Vec3f>(y, x) = cv::Vec3f(std::sin(theta), 0.0f, std::cos(theta));
  }
  in.albedo = cv::Mat(height, width, CV_8UC4, kAlbedo);
  in.ka = cv::Mat(height, width, CV_32FC1, cv::Scalar(ka));
  return in;
}

// First pixel where N·L = cos(theta(x)) >= t on the ramp.
int ramp_crossing(float t, int width = 400) {
  return int(std::ceil(float(width) * (1.0f - std::acos(t) / kPi) - 0.5f));
}

struct BandRun {
  int start;
  cv::Vec4b color;
};

std::vector<BandRun> runs(const cv::Mat& img, int row = 0) {
  std::vector<BandRun> r;
  for (int x = 0; x < img.cols; ++x) {
    const cv::Vec4b c = img.at<cv::Vec4b>(row, x);
    if (r.empty() || r.back().color != c) r.push_back({x, c});
  }
  return r;
}

// A unit sphere seen head-on, with analytic normals, 4x4-sample coverage (colour
// premultiplied by coverage in linear light, as the raster pass leaves it), view-space
// positions at distance 5 and a ka darkening toward the bottom, as under a crown.
ToonImages sphere(int size = 160, cv::Vec4b albedo = kAlbedo) {
  ToonImages in;
  in.normal = cv::Mat(size, size, CV_32FC3, cv::Scalar::all(0));
  in.albedo = cv::Mat(size, size, CV_8UC4, cv::Scalar::all(0));
  in.ka = cv::Mat(size, size, CV_32FC1, cv::Scalar(0));
  in.position = cv::Mat(size, size, CV_32FC3, cv::Scalar::all(0));
  const float r = 0.45f * float(size), c = 0.5f * float(size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      int covered = 0;
      glm::vec3 nsum(0.0f);
      for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) {
          const float u = (float(x) + (float(sx) + 0.5f) / 4.0f - c) / r;
          const float v = -(float(y) + (float(sy) + 0.5f) / 4.0f - c) / r;
          if (u * u + v * v >= 1.0f) continue;
          ++covered;
          nsum += glm::vec3(u, v, std::sqrt(1.0f - u * u - v * v));
        }
      if (covered == 0) continue;
      const glm::vec3 n = glm::normalize(nsum);
      const float cov = float(covered) / 16.0f;
      in.normal.at<cv::Vec3f>(y, x) = cv::Vec3f(n.x, n.y, n.z);
      in.position.at<cv::Vec3f>(y, x) = cv::Vec3f(n.x, n.y, n.z - 5.0f);
      in.ka.at<float>(y, x) = 0.45f + 0.275f * (1.0f + n.y);
      cv::Vec4b a;
      for (int ch = 0; ch < 3; ++ch)
        a[ch] = encode(decode(albedo[ch]) * cov);
      a[3] = uint8_t(std::lround(cov * 255.0f));
      in.albedo.at<cv::Vec4b>(y, x) = a;
    }
  return in;
}

// Shadow map of a plane at light depth 10 seen by an orthographic light camera at z = 10
// looking down -Z over [-1, 1]^2, with a square occluder at depth 5 over texels 8..23.
ToonShadowMap square_shadow_map(bool occluder = true) {
  ToonShadowMap m;
  m.depth = cv::Mat(32, 32, CV_32FC1, cv::Scalar(10.0f));
  if (occluder) m.depth(cv::Rect(8, 8, 16, 16)).setTo(5.0f);
  m.light_view = glm::lookAt(glm::vec3(0, 0, 10), glm::vec3(0), glm::vec3(0, 1, 0));
  m.light_proj = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 100.0f);
  return m;
}

// The view-space plane z = -slope x over [-1, 1]^2 (64 x 64 px), facing +Z, with the
// identity view so world = view space.
ToonImages plane(float slope = 0.0f) {
  ToonImages in;
  const int n = 64;
  in.normal.create(n, n, CV_32FC3);
  in.position.create(n, n, CV_32FC3);
  const glm::vec3 normal = glm::normalize(glm::vec3(slope, 0.0f, 1.0f));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float px = (float(x) + 0.5f) / float(n) * 2.0f - 1.0f;
      const float py = 1.0f - (float(y) + 0.5f) / float(n) * 2.0f;
      in.position.at<cv::Vec3f>(y, x) = cv::Vec3f(px, py, -slope * px);
      in.normal.at<cv::Vec3f>(y, x) = cv::Vec3f(normal.x, normal.y, normal.z);
    }
  in.albedo = cv::Mat(n, n, CV_8UC4, kAlbedo);
  return in;
}

bool all_finite(const cv::Mat& m) {
  return cv::checkRange(m);
}

TEST(Toon, RampGivesKBandsInOrderPlusShadow) {
  for (int k = 2; k <= 8; ++k) {
    SCOPED_TRACE("k = " + std::to_string(k));
    ToonParams p;
    p.bands = k;
    const cv::Mat out = toon_shade(ramp(), headlight(), glm::mat4(1.0f), p);
    ASSERT_EQ(out.type(), CV_8UC4);
    const std::vector<BandRun> r = runs(out);
    ASSERT_EQ(int(r.size()), k + 1);  // the shadow tone, then k bands
    const std::vector<float> tones = toon_tones(p);
    for (size_t i = 0; i < r.size(); ++i) {
      if (i > 0) {
        EXPECT_GT(r[i].color[1], r[i - 1].color[1]) << "band " << i;
      }
      // Every row agrees.
      EXPECT_EQ(runs(out, 3).at(i).start, r[i].start);
      const float tone = i == 0 ? tones[0] * p.shadow : tones[i - 1];
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(r[i].color[ch], encode(decode(kAlbedo[ch]) * tone), 1) << "channel " << ch;
      EXPECT_EQ(r[i].color[3], 255);
    }
    EXPECT_NEAR(r[1].start, ramp_crossing(0.0f), 1);  // the terminator at N·L = 0
    for (int j = 1; j < k; ++j)
      EXPECT_NEAR(r[size_t(j) + 1].start, ramp_crossing(float(j) / float(k)), 1);
  }
}

TEST(Toon, DefaultTonesAreTheDocumentedRamp) {
  ToonParams p;
  const std::vector<float> t = toon_tones(p);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_FLOAT_EQ(t[0], 0.55f);
  EXPECT_FLOAT_EQ(t[1], 0.8f);
  EXPECT_FLOAT_EQ(t[2], 1.0f);
  p.bands = 5;
  const std::vector<float> t5 = toon_tones(p);
  ASSERT_EQ(t5.size(), 5u);
  EXPECT_FLOAT_EQ(t5.front(), 0.55f);
  EXPECT_FLOAT_EQ(t5[2], 0.8f);
  EXPECT_FLOAT_EQ(t5.back(), 1.0f);
  p.tones = "0.3,0.4,0.5,0.6,0.7";
  EXPECT_FLOAT_EQ(toon_tones(p)[3], 0.6f);
}

TEST(Toon, ExplicitThresholdsMoveTheBoundaries) {
  {
    ToonParams p;
    p.thresholds = "0.2,0.6";
    const std::vector<BandRun> r = runs(toon_shade(ramp(), headlight(), glm::mat4(1.0f), p));
    ASSERT_EQ(r.size(), 4u);
    EXPECT_NEAR(r[1].start, ramp_crossing(0.0f), 1);
    EXPECT_NEAR(r[2].start, ramp_crossing(0.2f), 1);
    EXPECT_NEAR(r[3].start, ramp_crossing(0.6f), 1);
  }
  {
    // A negative threshold splits the shadow side; the terminator stays at N·L = 0.
    ToonParams p;
    p.thresholds = "-0.5, 0.3";
    const std::vector<BandRun> r = runs(toon_shade(ramp(), headlight(), glm::mat4(1.0f), p));
    ASSERT_EQ(r.size(), 4u);
    EXPECT_NEAR(r[1].start, ramp_crossing(-0.5f), 1);
    EXPECT_NEAR(r[2].start, ramp_crossing(0.0f), 1);
    EXPECT_NEAR(r[3].start, ramp_crossing(0.3f), 1);
    EXPECT_LT(r[0].color[1], r[1].color[1]);
    EXPECT_LT(r[1].color[1], r[2].color[1]);
  }
}

TEST(Toon, KaDarkensProportionallyToItsWeight) {
  const float ka = 0.4f;
  for (float w : {0.0f, 0.25f, 0.5f, 1.0f}) {
    SCOPED_TRACE("ka_weight = " + std::to_string(w));
    ToonParams p;
    p.ka_weight = w;
    const cv::Mat full = toon_shade_linear(ramp(400, 4, 1.0f), headlight(), glm::mat4(1.0f), p);
    const cv::Mat dark = toon_shade_linear(ramp(400, 4, ka), headlight(), glm::mat4(1.0f), p);
    const float expected = 1.0f + w * (ka - 1.0f);
    for (int x = 0; x < full.cols; x += 7)
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(dark.at<cv::Vec4f>(0, x)[ch], full.at<cv::Vec4f>(0, x)[ch] * expected, 1e-6f);
    if (w == 0.0f) {
      const cv::Mat a = toon_shade(ramp(400, 4, 1.0f), headlight(), glm::mat4(1.0f), p);
      const cv::Mat b = toon_shade(ramp(400, 4, ka), headlight(), glm::mat4(1.0f), p);
      EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
    }
  }
}

TEST(Toon, BadThresholdsNameTheKey) {
  for (const char* bad : {"0.6,0.2", "0.2,0.2", "0.5", "0.1,0.2,0.3", "-1,0.5", "0.2,1", "abc", "",
                          "0.2,,0.6", "0.2;0.6", "nan,0.5", "0.2,0.6x", "0.2,inf", ","}) {
    SCOPED_TRACE(std::string("\"") + bad + "\"");
    ToonParams p;
    ParamSet set;
    bind_toon_params(set, p);
    try {
      set.set_text("toon.thresholds", bad, "look.toml");
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("toon.thresholds"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("look.toml"), std::string::npos) << e.what();
    }
    EXPECT_EQ(p.thresholds, "even");  // unchanged
    p.thresholds = bad;
    try {
      validate_toon_params(p);
      ADD_FAILURE() << "validated";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "toon.thresholds");
    }
  }
  ToonParams p;
  ParamSet set;
  bind_toon_params(set, p);
  for (const char* good : {"0.2,0.6", " -0.3 , 0.5 ", "-0.99,0.99", "+0.1,0.2", "even"}) {
    EXPECT_NO_THROW(set.set_text("toon.thresholds", good, "--set")) << good;
    EXPECT_EQ(p.thresholds, good);
  }
  // Changing the band count afterwards makes the list the wrong length: caught when the pass
  // is built.
  set.set_text("toon.thresholds", "0.2,0.6", "--set");
  set.set_number("toon.bands", 4, "--set");
  try {
    RenderGraph g;
    add_toon_pass(g, {}, headlight(), glm::mat4(1.0f), p);
    ADD_FAILURE() << "accepted 2 thresholds for 4 bands";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "toon.thresholds");
  }
}

TEST(Toon, BadTonesNameTheKey) {
  for (const char* bad : {"0.5,0.8", "0.5,0.8,1,1", "-0.1,0.5,1", "0.5,0.8,2.5", "bright"}) {
    ToonParams p;
    ParamSet set;
    bind_toon_params(set, p);
    try {
      set.set_text("toon.tones", bad, "--set");
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("toon.tones"), std::string::npos) << e.what();
    }
  }
}

TEST(Toon, EveryParameterAtBothEndsGivesFiniteOutput) {
  ToonImages in = sphere(64);
  in.shadow = square_shadow_map();
  Lighting lights = Lighting::three_point();
  Light point;
  point.type = Light::Type::Point;
  point.vector = glm::vec3(3.0f, 2.0f, 0.0f);
  point.color = glm::vec3(0.2f);
  lights.lights.push_back(point);
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0));

  ToonParams defaults;
  ParamSet probe;
  bind_toon_params(probe, defaults);
  ASSERT_GE(probe.specs().size(), 12u);
  int runs_done = 0;
  for (const ParamSpec& spec : probe.specs()) {
    std::vector<std::string> values;
    switch (spec.type) {
      case ParamType::Float:
      case ParamType::Int:
        values = {std::to_string(spec.min), std::to_string(spec.max)};
        break;
      case ParamType::Bool:
        values = {"false", "true"};
        break;
      case ParamType::Color:
        values = {"#000000", "#ffffff"};
        break;
      case ParamType::Choice:
        values = spec.choices;
        break;
      case ParamType::Text:
        values = spec.key == "toon.thresholds" ? std::vector<std::string>{"-0.999,0.999"}
                                               : std::vector<std::string>{"0,2,0"};
        break;
    }
    for (const std::string& v : values) {
      SCOPED_TRACE(spec.key + " = " + v);
      ToonParams p;
      p.cast_shadows = true;  // exercise the shadow map too, unless this is the key under test
      ParamSet set;
      bind_toon_params(set, p);
      set.set_from_string(spec.key, v, "test");
      for (const char* mode : {"key", "sum"}) {
        if (spec.key != "toon.light") p.light = mode;
        const cv::Mat lin = toon_shade_linear(in, lights, view, p);
        ASSERT_EQ(lin.type(), CV_32FC4);
        EXPECT_TRUE(all_finite(lin));
        EXPECT_EQ(toon_shade(in, lights, view, p).type(), CV_8UC4);
        ++runs_done;
      }
    }
    // Just outside the range is an input error naming the key.
    if (spec.type == ParamType::Float || spec.type == ParamType::Int) {
      const double step = spec.type == ParamType::Int ? 1.0 : 1e-3;
      for (double v : {spec.min - step, spec.max + step}) {
        ToonParams p;
        ParamSet set;
        bind_toon_params(set, p);
        EXPECT_THROW(set.set_number(spec.key, v, "test"), InputError) << spec.key << " " << v;
      }
    }
  }
  EXPECT_GT(runs_done, 40);
}

TEST(Toon, Deterministic) {
  ToonImages in = sphere(96);
  in.shadow = square_shadow_map();
  ToonParams p;
  p.specular = true;
  p.light = "sum";
  p.cast_shadows = true;
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0));
  const cv::Mat a = toon_shade(in, Lighting::three_point(), view, p);
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  const cv::Mat b = toon_shade(in, Lighting::three_point(), view, p);
  cv::setNumThreads(threads);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

TEST(Toon, BackgroundPixelsAreUntouched) {
  ToonImages in = sphere(64);
  // Garbage under zero coverage: colour bytes and NaN normals must not leak or change.
  int background = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      cv::Vec4b& a = in.albedo.at<cv::Vec4b>(y, x);
      if (a[3] != 0) continue;
      ++background;
      a = cv::Vec4b(uint8_t(x), uint8_t(y), 7, 0);
      in.normal.at<cv::Vec3f>(y, x) = cv::Vec3f(NAN, NAN, NAN);
    }
  ASSERT_GT(background, 500);
  for (const char* mode : {"key", "sum"}) {
    ToonParams p;
    p.light = mode;
    p.specular = true;
    const cv::Mat out = toon_shade(in, Lighting::three_point(), glm::mat4(1.0f), p);
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const cv::Vec4b a = in.albedo.at<cv::Vec4b>(y, x);
        if (a[3] == 0) {
          ASSERT_EQ(out.at<cv::Vec4b>(y, x), a) << x << "," << y;
        } else {
          ASSERT_EQ(out.at<cv::Vec4b>(y, x)[3], a[3]);  // coverage kept
        }
      }
  }
}

TEST(Toon, PartialCoverageStaysPremultiplied) {
  ToonImages in = ramp(8, 1);
  in.albedo.at<cv::Vec4b>(0, 7) =
      cv::Vec4b(encode(decode(kAlbedo[0]) * 0.5f), encode(decode(kAlbedo[1]) * 0.5f),
                encode(decode(kAlbedo[2]) * 0.5f), 128);
  ToonParams p;
  const cv::Mat lin = toon_shade_linear(in, headlight(), glm::mat4(1.0f), p);
  const cv::Vec4f edge = lin.at<cv::Vec4f>(0, 7);
  EXPECT_NEAR(edge[3], 128.0f / 255.0f, 1e-6f);
  EXPECT_NEAR(edge[1], decode(in.albedo.at<cv::Vec4b>(0, 7)[1]) * toon_tones(p).back(), 1e-6f);
}

TEST(Toon, WorldSpaceLightsFollowTheView) {
  Lighting world = headlight();
  world.lights[0].camera_fixed = false;
  world.lights[0].vector = glm::vec3(1.0f, 0.0f, 0.0f);  // world +X
  // A view turning world +X onto view +Z.
  const glm::mat4 view = glm::rotate(glm::mat4(1.0f), -0.5f * kPi, glm::vec3(0, 1, 0));
  ASSERT_NEAR((glm::mat3(view) * glm::vec3(1, 0, 0)).z, 1.0f, 1e-6f);
  ToonParams p;
  const cv::Mat a = toon_shade(ramp(), headlight(), glm::mat4(1.0f), p);
  const cv::Mat b = toon_shade(ramp(), world, view, p);
  cv::Mat diff;
  cv::compare(a.reshape(1), b.reshape(1), diff, cv::CMP_NE);
  EXPECT_LE(cv::countNonZero(diff), 3 * 4 * 2);  // at most a boundary pixel per band per row
}

TEST(Toon, KeyLightIsTheBrightestDirectional) {
  Lighting l = Lighting::three_point();
  EXPECT_EQ(toon_key_light(l), 0);
  l.lights[2].color = glm::vec3(2.0f);
  EXPECT_EQ(toon_key_light(l), 2);
  Light point;
  point.type = Light::Type::Point;
  point.color = glm::vec3(5.0f);
  l.lights.push_back(point);
  EXPECT_EQ(toon_key_light(l), 2);  // directional lights come first
  l.lights = {point};
  EXPECT_EQ(toon_key_light(l), 0);
  ToonParams p;
  EXPECT_TRUE(toon_needs_position(l, p));
  l.lights.clear();
  EXPECT_EQ(toon_key_light(l), -1);
  EXPECT_FALSE(toon_needs_position(l, p));
  // No lights: a headlight along +Z drives the bands, so the ramp still has them all.
  EXPECT_EQ(runs(toon_shade(ramp(), l, glm::mat4(1.0f), p)).size(), 4u);
}

TEST(Toon, SumLightsTheKeysShadowSide) {
  Lighting two = headlight();
  Light back;  // from behind the ramp's dark end, half as bright
  back.vector = glm::vec3(0.0f, 0.0f, -1.0f);
  back.color = glm::vec3(0.5f);
  two.lights.push_back(back);
  ToonParams p;
  const cv::Mat key = toon_shade(ramp(), two, glm::mat4(1.0f), p);
  p.light = "sum";
  const cv::Mat sum = toon_shade(ramp(), two, glm::mat4(1.0f), p);
  // Key: the facing-away end is the shadow tone; sum: the back light lights it with a band.
  const cv::Vec4b shadow = key.at<cv::Vec4b>(0, 0);
  EXPECT_LT(shadow[1], sum.at<cv::Vec4b>(0, 0)[1]);
  EXPECT_EQ(key.at<cv::Vec4b>(0, 399), sum.at<cv::Vec4b>(0, 399));
  // With one light, sum and key agree exactly.
  EXPECT_EQ(cv::norm(toon_shade(ramp(), headlight(), glm::mat4(1.0f), p),
                     toon_shade(ramp(), headlight(), glm::mat4(1.0f), ToonParams{}), cv::NORM_INF),
            0.0);
}

TEST(Toon, SpecularBandIsAFlatHighlight) {
  const ToonImages in = sphere(128);
  ToonParams p;
  const cv::Mat plain = toon_shade(in, headlight(), glm::mat4(1.0f), p);
  p.specular = true;
  p.specular_threshold = 0.98f;
  const cv::Mat lit = toon_shade(in, headlight(), glm::mat4(1.0f), p);
  // The head-on centre is the highlight, mixed toward white.
  const cv::Vec4b centre = lit.at<cv::Vec4b>(64, 64);
  EXPECT_GT(centre[0], plain.at<cv::Vec4b>(64, 64)[0]);
  cv::Mat diff;
  cv::compare(plain.reshape(1), lit.reshape(1), diff, cv::CMP_NE);
  const int changed = cv::countNonZero(diff) / 3;
  // N·H >= 0.98 with H = N·(0,0,1): the cap n.z >= 0.98, about 4% of the disc area.
  EXPECT_GT(changed, 100);
  EXPECT_LT(changed, 800);
}

TEST(Toon, CastShadowsFromAShadowMap) {
  Lighting l = headlight();
  l.lights[0].camera_fixed = false;  // world = view here
  ToonImages in = plane();
  in.shadow = square_shadow_map();
  ToonParams p;
  const cv::Mat off = toon_shade(in, l, glm::mat4(1.0f), p);
  EXPECT_EQ(runs(off).size(), 1u);  // toon.cast_shadows off: the map is ignored
  p.cast_shadows = true;
  const cv::Mat on = toon_shade(in, l, glm::mat4(1.0f), p);
  const cv::Vec4b lit = off.at<cv::Vec4b>(0, 0);
  const cv::Vec4b shadow = on.at<cv::Vec4b>(32, 32);
  for (int ch = 0; ch < 3; ++ch)
    EXPECT_NEAR(shadow[ch], encode(decode(kAlbedo[ch]) * toon_tones(p)[0] * p.shadow), 1);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool under = x >= 16 && x < 48 && y >= 16 && y < 48;  // texels 8..23, 2 px each
      ASSERT_EQ(on.at<cv::Vec4b>(y, x), under ? shadow : lit) << x << "," << y;
    }
  // Moving the light camera moves the shadow: nothing blocks outside the map.
  in.shadow.light_view = glm::translate(in.shadow.light_view, glm::vec3(5.0f, 0.0f, 0.0f));
  EXPECT_EQ(runs(toon_shade(in, l, glm::mat4(1.0f), p)).size(), 1u);
}

TEST(Toon, SlopeScaledBiasPreventsSelfShadowing) {
  // A plane tilted 27 degrees from the light, its own shadow map sampled at texel centres.
  const float slope = 0.5f;
  ToonImages in = plane(slope);
  in.shadow = square_shadow_map(false);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const float px = (float(x) + 0.5f) / 32.0f * 2.0f - 1.0f;
      in.shadow.depth.at<float>(y, x) = 10.0f + slope * px;
    }
  ToonParams p;
  p.cast_shadows = true;
  const cv::Mat clean = toon_shade(in, headlight(), glm::mat4(1.0f), p);
  EXPECT_EQ(runs(clean).size(), 1u);
  for (int y = 1; y < 64; ++y)
    EXPECT_EQ(runs(clean, y).size(), 1u);
  p.shadow_bias = 0.0f;  // without bias, half of every texel shadows itself
  const cv::Mat acne = toon_shade(in, headlight(), glm::mat4(1.0f), p);
  EXPECT_GT(runs(acne).size(), 10u);
}

// The graph stand-in for the raster pass records which targets it was asked for.
struct GraphFixture {
  RenderGraph g;
  int normal, albedo, ka, position, id, depth;
  std::string made;
  GraphFixture() {
    normal = g.resource("normal");
    albedo = g.resource("albedo");
    ka = g.resource("ka");
    position = g.resource("position");
    id = g.resource("id");
    depth = g.resource("depth");
    const ToonImages in = sphere(32);
    g.add_pass("raster", {}, {normal, albedo, ka, position, id, depth}, [this, in](PassContext& c) {
      auto put = [&](int r, const cv::Mat& m) {
        if (!c.wanted(r)) return;
        made += g.resource_name(r) + ",";
        c.write(r, m);
      };
      put(normal, in.normal);
      put(albedo, in.albedo);
      put(ka, in.ka);
      put(position, in.position);
      put(id, cv::Mat(32, 32, CV_32SC1, cv::Scalar(1)));
      put(depth, cv::Mat(32, 32, CV_32FC1, cv::Scalar(5)));
    });
    // An edge-like pass that does read the ids, which toon must not make live.
    const int edges = g.resource("edges");
    g.add_pass("edges", {id, normal}, {edges},
               [edges](PassContext& c) { c.write(edges, cv::Mat()); });
  }
  ToonResources resources() const { return {normal, albedo, ka, position}; }
};

TEST(Toon, GraphNeverRasterisesIds) {
  GraphFixture f;
  ToonParams p;
  const int out = add_toon_pass(f.g, f.resources(), Lighting::three_point(), glm::mat4(1.0f), p);
  EXPECT_EQ(f.g.resource_name(out), "toon");
  f.g.present(out);
  f.g.compile();
  EXPECT_FALSE(f.g.is_live(f.id));
  EXPECT_FALSE(f.g.pass_live("edges"));
  EXPECT_TRUE(f.g.is_live(f.ka));         // ka_weight 0.5 reads it
  EXPECT_FALSE(f.g.is_live(f.position));  // directional lights, no cast shadows
  f.g.execute();
  EXPECT_EQ(f.made, "normal,albedo,ka,");
  const cv::Mat& img = f.g.get<cv::Mat>(out);
  EXPECT_EQ(img.type(), CV_8UC4);
  EXPECT_EQ(img.size(), cv::Size(32, 32));
}

TEST(Toon, GraphSkipsKaAtWeightZeroAndReadsWhatShadowsNeed) {
  {
    GraphFixture f;
    ToonParams p;
    p.ka_weight = 0.0f;
    f.g.present(add_toon_pass(f.g, f.resources(), headlight(), glm::mat4(1.0f), p));
    f.g.execute();
    EXPECT_EQ(f.made, "normal,albedo,");
  }
  {
    GraphFixture f;
    const int map = f.g.resource("shadow_map");
    f.g.add_pass("shadow", {f.depth}, {map}, [map, depth = f.depth](PassContext& c) {
      ToonShadowMap m = square_shadow_map();
      m.depth = c.read<cv::Mat>(depth);
      c.write(map, m);
    });
    ToonParams p;
    p.cast_shadows = true;
    ToonResources res = f.resources();
    res.shadow = map;
    f.g.present(add_toon_pass(f.g, res, headlight(), glm::mat4(1.0f), p));
    f.g.execute();
    EXPECT_EQ(f.made, "normal,albedo,ka,position,depth,");
  }
}

// Not a check: with SYLVA_TOON_LOOK_DIR set, writes ramp.png and sphere.png there (over a
// light grey ground) for looking at.
TEST(Toon, WritesLookImagesWhenAsked) {
  const char* dir = std::getenv("SYLVA_TOON_LOOK_DIR");
  if (!dir) GTEST_SKIP() << "set SYLVA_TOON_LOOK_DIR to write the look images";
  auto over_grey = [](const cv::Mat& bgra) {
    cv::Mat out(bgra.size(), CV_8UC3);
    for (int y = 0; y < bgra.rows; ++y)
      for (int x = 0; x < bgra.cols; ++x) {
        const cv::Vec4b c = bgra.at<cv::Vec4b>(y, x);
        const float a = float(c[3]) / 255.0f;
        for (int ch = 0; ch < 3; ++ch)
          out.at<cv::Vec3b>(y, x)[ch] = encode(decode(c[ch]) + (1.0f - a) * decode(225));
      }
    return out;
  };
  auto tile = [](const cv::Mat& m, int rows) {
    cv::Mat t;
    cv::repeat(m, rows, 1, t);
    return t;
  };
  std::vector<cv::Mat> rows;
  for (const char* setting : {"bands=3", "bands=5", "thresholds=0.2,0.6", "specular"}) {
    ToonParams p;
    ParamSet set;
    bind_toon_params(set, p);
    const std::string s = setting;
    if (s == "specular") {
      p.specular = true;
      p.specular_threshold = 0.9f;
    } else {
      const size_t eq = s.find('=');
      set.set_from_string("toon." + s.substr(0, eq), s.substr(eq + 1), "look");
    }
    rows.push_back(tile(toon_shade(ramp(512, 1), headlight(), glm::mat4(1.0f), p), 40));
  }
  cv::Mat ramp_img;
  cv::vconcat(rows, ramp_img);
  ASSERT_TRUE(cv::imwrite(std::string(dir) + "/ramp.png", over_grey(ramp_img)));

  std::vector<cv::Mat> spheres;
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0));
  for (int variant = 0; variant < 4; ++variant) {
    ToonParams p;
    if (variant == 1) {
      p.bands = 4;
      p.specular = true;
    }
    if (variant == 2) {
      p.light = "sum";
      p.ka_weight = 1.0f;
    }
    if (variant == 3) {
      p.shadow = 0.7f;
      p.shadow_tint = glm::vec3(0.35f, 0.45f, 0.9f);
      p.thresholds = "0.15,0.7";
      p.tones = "0.6,0.85,1.05";
    }
    spheres.push_back(toon_shade(sphere(256), Lighting::three_point(), view, p));
  }
  cv::Mat sphere_img;
  cv::hconcat(spheres, sphere_img);
  ASSERT_TRUE(cv::imwrite(std::string(dir) + "/sphere.png", over_grey(sphere_img)));
}

}  // namespace
}  // namespace sylva::test

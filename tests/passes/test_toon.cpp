// Toon shading (Decaudin 1996): band count, order and boundaries on an N·L ramp, explicit
// thresholds, the ka weight, parameter validation, determinism, background and partial
// coverage (every toon.* key at both ends of its range: tests/styles/test_every_parameter.cpp).
// Lights, shadows and the graph: test_toon_lights.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "passes/toon.h"
#include "tests/passes/toon_scenes.h"

namespace sylva::test {
namespace {

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

TEST(Toon, Deterministic) {
  ToonImages in = sphere(96);
  in.shadow = square_shadow_map();
  ToonParams p;
  p.specular = true;
  p.light = ToonLight::Sum;
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
  for (ToonLight mode : {ToonLight::Key, ToonLight::Sum}) {
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

}  // namespace
}  // namespace sylva::test

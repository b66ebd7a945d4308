// Toon shading's lights and graph (Decaudin 1996): world-space lights follow the view, the key
// and summed lights, the specular band, cast shadows from a synthetic shadow map with a
// slope-scaled bias, and graph culling (no ID buffer; ka and shadows read only when needed).
// scripts/look.sh writes a ramp and spheres as PNGs for a visual check.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "passes/toon.h"
#include "tests/passes/toon_scenes.h"

namespace sylva::test {
namespace {

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
  p.light = ToonLight::Sum;
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
  ImageHandle normal, albedo, ka, position, id, depth;
  std::string made;
  GraphFixture() {
    normal = g.resource<cv::Mat>("normal");
    albedo = g.resource<cv::Mat>("albedo");
    ka = g.resource<cv::Mat>("ka");
    position = g.resource<cv::Mat>("position");
    id = g.resource<cv::Mat>("id");
    depth = g.resource<cv::Mat>("depth");
    const ToonImages in = sphere(32);
    g.add_pass("raster", {}, {normal, albedo, ka, position, id, depth}, [this, in](PassContext& c) {
      auto put = [&](ImageHandle r, const cv::Mat& m) {
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
    const auto edges = g.resource<cv::Mat>("edges");
    g.add_pass("edges", {id, normal}, {edges},
               [edges](PassContext& c) { c.write(edges, cv::Mat()); });
  }
  ToonResources resources() const { return {normal, albedo, ka, position}; }
};

TEST(Toon, GraphNeverRasterisesIds) {
  GraphFixture f;
  ToonParams p;
  const auto out = add_toon_pass(f.g, f.resources(), Lighting::three_point(), glm::mat4(1.0f), p);
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
    const auto map = f.g.resource<ToonShadowMap>("shadow_map");
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

}  // namespace
}  // namespace sylva::test

// The raster pass's colour targets against analytic scenes: the unlit albedo, textures
// minified in linear light, image orientation and channel order, the sRGB-encoded background,
// and SSAA that averages colour but keeps ids exact (the other targets: test_raster.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/gl/rasterizer.h"
#include "tests/core/gl/raster_scenes.h"

namespace sylva {
namespace {

using namespace sylva::test;

TEST(Raster, AlbedoIsTheUnlitBaseColour) {
  // With no light at all the colour target is black, the albedo is the material's colour
  // (sRGB-encoded) with alpha = coverage; the background is transparent black.
  Material m;
  m.base_color = glm::vec4(0.2140f, 0.5f, 0.0331f, 1.0f);  // sRGB (128, 188, 51)
  Scene s = scene_of({make_quad(1.0f, 0.0f)}, m);
  set_ids(s.meshes[0], 1, 1);
  Rasterizer r(gl());
  r.upload(s);
  for (int ssaa : {1, 2}) {
    const GBuffer g = r.render(front_camera(s, 64), ambient_only(0),
                               request_of(Target::Color | Target::Albedo, IdKind::Primitive, ssaa));
    ASSERT_EQ(g.albedo.type(), CV_8UC4);
    const cv::Vec4b centre = g.albedo.at<cv::Vec4b>(32, 32);
    EXPECT_NEAR(centre[2], 128, 1) << ssaa;  // BGRA
    EXPECT_NEAR(centre[1], 188, 1) << ssaa;
    EXPECT_NEAR(centre[0], 51, 1) << ssaa;
    EXPECT_EQ(centre[3], 255) << ssaa;
    EXPECT_EQ(g.color.at<cv::Vec4b>(32, 32)[1], 0) << ssaa;
    EXPECT_EQ(g.albedo.at<cv::Vec4b>(0, 0), cv::Vec4b(0, 0, 0, 0)) << ssaa;
  }
}

TEST(Raster, MinifiedTexturesAverageInLinearLight) {
  // A one-texel black and white checker seen from afar: the mip levels average it in linear
  // light (sRGB 188, as glGenerateMipmap does for sRGB textures), not in sRGB (128), and do
  // not alias to black or white. Sizes that are not powers of two halve with rounding down.
  for (const cv::Size size : {cv::Size(256, 256), cv::Size(255, 129)}) {
    Scene s = scene_of({make_quad(1.0f, 0.0f)});
    Texture t;
    t.name = "checker";
    t.width = size.width;
    t.height = size.height;
    t.rgba.resize(size_t(size.area()) * 4);
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x) {
        uint8_t* px = &t.rgba[size_t(y * size.width + x) * 4];
        px[0] = px[1] = px[2] = (x + y) % 2 ? 255 : 0;
        px[3] = 255;
      }
    s.textures.push_back(t);
    s.materials[0].base_color_texture = 0;
    set_ids(s.meshes[0], 1, 1);
    Rasterizer r(gl());
    r.upload(s);
    const GBuffer g = r.render(front_camera(s, 32), ambient_only(0), request_of(Target::Albedo));
    for (const cv::Point p : {cv::Point(16, 16), cv::Point(13, 18)}) {
      const cv::Vec4b albedo = g.albedo.at<cv::Vec4b>(p);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(albedo[c], 188, 3) << size << " at " << p;
    }
  }
}

TEST(Raster, ImageOrientationAndChannelOrder) {
  // Texture: top half red, bottom half blue; a quad raised above the centre of the view.
  Scene s = scene_of({make_quad(1.0f, 0.0f)});
  Texture t{"halves", 64, 64, {}};
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const bool top = y < 32;
      t.rgba.insert(t.rgba.end(), {uint8_t(top ? 255 : 0), 0, uint8_t(top ? 0 : 255), 255});
    }
  }
  s.textures.push_back(t);
  s.materials[0].base_color_texture = 0;
  s.materials[0].double_sided = true;
  Rasterizer r(gl());
  r.upload(s);
  const GBuffer g = r.render(front_camera(s, 64, true), ambient_only(1), request_of(Target::Color));
  const cv::Vec4b top = g.color.at<cv::Vec4b>(16, 32), bottom = g.color.at<cv::Vec4b>(48, 32);
  EXPECT_GT(top[2], 200);  // BGRA: red in channel 2
  EXPECT_LT(top[0], 30);
  EXPECT_GT(bottom[0], 200);
  EXPECT_LT(bottom[2], 30);
}

TEST(Raster, BackgroundIsSrgbEncoded) {
  const Scene s = sphere_scene(16, 8);
  Rasterizer r(gl());
  r.upload(s);
  RasterRequest req = request_of(Target::Color);
  req.background = glm::vec4(0.21586f, 1.0f, 0.0f, 0.0f);  // linear 0.21586 = sRGB 128
  const GBuffer g = r.render(front_camera(s, 32), ambient_only(1), req);
  EXPECT_EQ(g.color.at<cv::Vec4b>(0, 0), cv::Vec4b(0, 255, 128, 0));
}

// Several separate spheres, each its own primitive id.
TEST(Raster, SsaaKeepsColourAndExactIds) {
  const Scene s = spheres_scene();
  Rasterizer r(gl());
  r.upload(s);
  OrbitParams p;
  const Camera cam = make_orbit_camera(s.bounds(), p, 160, 120);
  const TargetMask all = kAllTargetsMask;
  const GBuffer one = r.render(cam, Lighting::three_point(), request_of(all, IdKind::Primitive, 1));
  const GBuffer two = r.render(cam, Lighting::three_point(), request_of(all, IdKind::Primitive, 2));
  EXPECT_EQ(two.color.size(), cv::Size(160, 120));
  EXPECT_EQ(id_set(one.id), (std::set<int32_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(id_set(two.id), id_set(one.id));
  EXPECT_LT(cv::norm(one.color, two.color, cv::NORM_L1) / (160.0 * 120 * 4), 2.0);
  // Geometry pixels agree between the buffers: covered normal <=> non-zero id.
  cv::Mat normal_len;
  cv::Mat ch[3];
  cv::split(two.normal, ch);
  cv::magnitude(ch[0], ch[1], normal_len);
  cv::magnitude(normal_len, ch[2], normal_len);
  EXPECT_EQ(cv::countNonZero(normal_len), cv::countNonZero(two.id));
  double lo = 0, hi = 0;
  cv::minMaxLoc(normal_len, &lo, &hi, nullptr, nullptr, two.id != 0);
  EXPECT_NEAR(lo, 1.0, 1e-3);
  EXPECT_NEAR(hi, 1.0, 1e-3);
  // Mostly the same ids pixel by pixel (differences only along silhouettes).
  EXPECT_LT(cv::countNonZero(one.id != two.id), 0.05 * 160 * 120);
}

}  // namespace
}  // namespace sylva

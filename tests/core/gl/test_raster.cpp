// The G-buffer raster pass against analytic scenes: sphere normals, plane depth, ids, ka
// decoding, alpha-mask cut-outs, double-sided leaves, determinism and the light conventions (the
// colour targets: test_raster_colour.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "core/error.h"
#include "core/gl/rasterizer.h"
#include "tests/core/gl/raster_scenes.h"

namespace sylva {
namespace {

using namespace sylva::test;

TEST(Raster, SphereNormalsMatchAnalytic) {
  const Scene s = sphere_scene();
  OrbitParams p;  // default az 30, el 15
  const Camera cam = make_orbit_camera(s.bounds(), p, 256, 256);
  Rasterizer r(gl());
  r.upload(s);
  const GBuffer g = r.render(cam, Lighting::three_point(),
                             request_of(Target::Normal | Target::Position | Target::Depth));
  const glm::vec3 centre = glm::vec3(cam.view * glm::vec4(0.5f, -0.25f, 1.0f, 1.0f));
  double sum_deg = 0.0;
  int covered = 0;
  for (int y = 0; y < 256; ++y) {
    for (int x = 0; x < 256; ++x) {
      const cv::Vec3f n = g.normal.at<cv::Vec3f>(y, x);
      if (n == cv::Vec3f(0, 0, 0)) continue;
      ++covered;
      const cv::Vec3f pos = g.position.at<cv::Vec3f>(y, x);
      const glm::vec3 exact = glm::normalize(glm::vec3(pos[0], pos[1], pos[2]) - centre);
      const float c = std::clamp(glm::dot(exact, glm::vec3(n[0], n[1], n[2])), -1.0f, 1.0f);
      sum_deg += glm::degrees(std::acos(c));
      EXPECT_NEAR(cv::norm(n), 1.0, 2e-3);
      ASSERT_NEAR(g.depth.at<float>(y, x), -pos[2], 1e-4f * -pos[2]);
    }
  }
  // Analytic coverage of a centred sphere: angular radius asin(r / d), NDC radius
  // tan(asin(r / d)) / tan(fov / 2), area pi ndc^2 / 4 of the image.
  const float d = glm::length(cam.eye - glm::vec3(0.5f, -0.25f, 1.0f));
  const double ndc = std::tan(std::asin(1.0 / d)) / std::tan(glm::radians(p.fov_deg) / 2);
  EXPECT_NEAR(covered, std::numbers::pi * ndc * ndc / 4 * 256 * 256, 0.01 * covered);
  EXPECT_LT(sum_deg / covered, 1.0);
}

TEST(Raster, PlaneDepthIsLinearViewDistance) {
  Scene s = scene_of({make_quad(1.0f, 0.25f)});
  set_ids(s.meshes[0], 1, 1);
  for (bool ortho : {false, true}) {
    const Camera cam = front_camera(s, 128, ortho, 0.0f, 4.0f);
    Rasterizer r(gl());
    r.upload(s);
    const GBuffer g = r.render(cam, Lighting::three_point(),
                               request_of(Target::Depth | Target::Position | Target::Id));
    int covered = 0;
    for (int y = 0; y < 128; ++y) {
      for (int x = 0; x < 128; ++x) {
        if (g.id.at<int32_t>(y, x) == 0) {
          ASSERT_EQ(g.depth.at<float>(y, x), 0.0f);
          continue;
        }
        ++covered;
        // Eye at z = 0.25 + 4 (bounds centre z = 0.25), plane at z = 0.25: depth 4.
        ASSERT_NEAR(g.depth.at<float>(y, x), 4.0f, 4e-4f) << "ortho " << ortho;
        ASSERT_NEAR(g.position.at<cv::Vec3f>(y, x)[2], -4.0f, 4e-4f);
      }
    }
    EXPECT_GT(covered, 100);
  }
}

TEST(Raster, OneQuadIsOneId) {
  Mesh quad = make_quad(0.5f, 0.0f);
  set_ids(quad, 7, 3);
  Mesh far_sphere;  // a second object, so the object id of each mesh is checked
  add_sphere(far_sphere, glm::vec3(3, 0, -1), 0.5f, 32, 16);
  set_ids(far_sphere, 9, 4, Role::Wood);
  const Scene s = scene_of({quad, far_sphere});
  const Camera cam = front_camera(s, 200);
  Rasterizer r(gl());
  r.upload(s);
  const struct {
    IdKind kind;
    std::set<int32_t> expected;
  } cases[] = {
      {IdKind::Primitive, {0, 7, 9}}, {IdKind::Cluster, {0, 3, 4}}, {IdKind::Object, {0, 1, 2}}};
  for (const auto& c : cases) {
    const GBuffer g = r.render(cam, Lighting::three_point(), request_of(Target::Id, c.kind));
    EXPECT_EQ(id_set(g.id), c.expected);
  }
  // Only the quad: exactly one non-zero value, on a convex square region.
  const Scene only = scene_of({quad});
  r.upload(only);
  const GBuffer g =
      r.render(front_camera(only, 200), Lighting::three_point(), request_of(Target::Id));
  EXPECT_EQ(id_set(g.id), (std::set<int32_t>{0, 7}));
  const cv::Rect box = cv::boundingRect(g.id != 0);
  EXPECT_EQ(cv::countNonZero(g.id), box.area());
  EXPECT_NEAR(box.width, box.height, 1);
}

TEST(Raster, OnlyRequestedTargetsAreAllocated) {
  const Scene s = sphere_scene(32, 16);
  Rasterizer r(gl());
  r.upload(s);
  const Camera cam = front_camera(s, 64);
  GBuffer g = r.render(cam, Lighting::three_point(), request_of(Target::Color));
  EXPECT_EQ(r.last_allocated_targets(), static_cast<TargetMask>(Target::Color));
  EXPECT_EQ(g.color.type(), CV_8UC4);
  EXPECT_TRUE(g.normal.empty() && g.depth.empty() && g.id.empty() && g.ka.empty());
  g = r.render(cam, Lighting::three_point(), request_of(Target::Normal | Target::Id));
  EXPECT_EQ(r.last_allocated_targets(), Target::Normal | Target::Id);
  EXPECT_TRUE(g.color.empty());
  EXPECT_EQ(g.normal.type(), CV_32FC3);
  EXPECT_EQ(g.id.type(), CV_32SC1);
}

TEST(Raster, KaFromNormalLengthDarkensAmbient) {
  Material white;
  white.base_color = glm::vec4(1.0f);
  const float ambient = 0.8f;
  float linear[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const float ka = k == 0 ? 1.0f : 0.5f;
    const Scene s = scene_of({make_quad(1.0f, 0.0f, ka)}, white);
    Rasterizer r(gl());
    r.upload(s);
    const GBuffer g = r.render(front_camera(s, 64), ambient_only(ambient),
                               request_of(Target::Color | Target::Ka | Target::Normal));
    const cv::Vec4b c = g.color.at<cv::Vec4b>(32, 32);
    EXPECT_EQ(c[3], 255);
    EXPECT_NEAR(g.ka.at<float>(32, 32), ka, 1e-6f);
    EXPECT_NEAR(g.normal.at<cv::Vec3f>(32, 32)[2], 1.0f, 1e-3f);  // re-normalised
    linear[k] = srgb_to_linear(c[1]);
    EXPECT_NEAR(linear[k], ambient * ka, 0.01f);
  }
  EXPECT_NEAR(linear[1] / linear[0], 0.5f, 0.02f);
}

// A separate ka attribute wins over the normal length; the scaled normal target keeps
// |N| = ka (Luft Fig. 7c); set_vertex_shading replaces both after upload.
TEST(Raster, KaAttributeScaledNormalsAndReplacedShading) {
  Material white;
  white.base_color = glm::vec4(1.0f);
  Mesh quad = make_quad(1.0f, 0.0f, 0.5f);       // normal length 0.5 ...
  quad.ka.assign(quad.positions.size(), 0.25f);  // ... but the attribute says 0.25
  const Scene s = scene_of({quad}, white);
  Rasterizer r(gl());
  r.upload(s);
  RasterRequest req = request_of(Target::Color | Target::Ka | Target::Normal);
  GBuffer g = r.render(front_camera(s, 64), ambient_only(0.8f), req);
  EXPECT_NEAR(g.ka.at<float>(32, 32), 0.25f, 1e-6f);
  EXPECT_NEAR(cv::norm(g.normal.at<cv::Vec3f>(32, 32)), 1.0, 1e-3);
  req.scaled_normals = true;
  g = r.render(front_camera(s, 64), ambient_only(0.8f), req);
  EXPECT_NEAR(g.normal.at<cv::Vec3f>(32, 32)[2], 0.25f, 1e-3f);

  VertexShading shading;  // tilt the normals toward +x and drop the attribute
  const glm::vec3 tilted = glm::normalize(glm::vec3(1, 0, 1)) * 0.75f;
  shading.normals = {std::vector<glm::vec3>(quad.positions.size(), tilted)};
  r.set_vertex_shading(shading);
  g = r.render(front_camera(s, 64), ambient_only(0.8f), req);
  EXPECT_NEAR(g.ka.at<float>(32, 32), 0.75f, 1e-5f);
  const cv::Vec3f n = g.normal.at<cv::Vec3f>(32, 32);
  EXPECT_NEAR(n[0], tilted.x, 1e-3f);
  EXPECT_NEAR(n[2], tilted.z, 1e-3f);
  shading.normals[0].pop_back();
  EXPECT_THROW(r.set_vertex_shading(shading), InputError);
}

// Shading kept by pointer is not uploaded twice, but is applied again once the scene's own
// normals are back (restore_vertex_shading) or replaced by other shading.
TEST(Raster, KeptShadingIsAppliedAgainAfterAnythingReplacedIt) {
  Material white;
  white.base_color = glm::vec4(1.0f);
  const Mesh quad = make_quad(1.0f, 0.0f, 0.5f);
  const Scene s = scene_of({quad}, white);
  Rasterizer r(gl());
  r.upload(s);
  const RasterRequest req = request_of(Target::Ka);
  auto ka_now = [&] {
    return r.render(front_camera(s, 16), ambient_only(0.8f), req).ka.at<float>(8, 8);
  };
  auto shading_of = [&](float length) {
    auto v = std::make_shared<VertexShading>();
    v->normals = {std::vector<glm::vec3>(quad.positions.size(), glm::vec3(0, 0, length))};
    return std::shared_ptr<const VertexShading>(v);
  };
  const auto kept = shading_of(0.75f);
  r.set_vertex_shading(kept);
  EXPECT_NEAR(ka_now(), 0.75f, 1e-5f);
  r.set_vertex_shading(kept);
  EXPECT_NEAR(ka_now(), 0.75f, 1e-5f);
  r.restore_vertex_shading();
  EXPECT_NEAR(ka_now(), 0.5f, 1e-5f);
  r.set_vertex_shading(kept);
  EXPECT_NEAR(ka_now(), 0.75f, 1e-5f);
  r.set_vertex_shading(*shading_of(0.25f));  // not kept: the same object next is applied
  EXPECT_NEAR(ka_now(), 0.25f, 1e-5f);
  r.set_vertex_shading(kept);
  EXPECT_NEAR(ka_now(), 0.75f, 1e-5f);
  r.upload(s);
  EXPECT_NEAR(ka_now(), 0.5f, 1e-5f);
  r.set_vertex_shading(kept);
  EXPECT_NEAR(ka_now(), 0.75f, 1e-5f);
}

// A 256^2 texture whose alpha is a disc of radius 0.4 (uv units), opaque square otherwise.
Scene masked_quad_scene(AlphaMode mode) {
  Scene s = scene_of({make_quad(1.0f, 0.0f)});
  Texture t;
  t.name = "disc";
  t.width = t.height = 256;
  t.rgba.resize(256 * 256 * 4);
  for (int y = 0; y < 256; ++y) {
    for (int x = 0; x < 256; ++x) {
      const float u = (x + 0.5f) / 256 - 0.5f, v = (y + 0.5f) / 256 - 0.5f;
      uint8_t* px = &t.rgba[(y * 256 + x) * 4];
      px[0] = 40, px[1] = 160, px[2] = 40;
      px[3] = u * u + v * v < 0.16f ? 255 : 0;
    }
  }
  s.textures.push_back(t);
  s.materials[0].base_color_texture = 0;
  s.materials[0].alpha_mode = mode;
  s.materials[0].double_sided = true;
  set_ids(s.meshes[0], 1, 1);
  return s;
}

TEST(Raster, AlphaMaskCutsEveryTarget) {
  const TargetMask all = kAllTargetsMask;
  Rasterizer r(gl());
  Scene s = masked_quad_scene(AlphaMode::Opaque);
  const Camera cam = front_camera(s, 256, true);
  r.upload(s);
  const int square = cv::countNonZero(r.render(cam, ambient_only(1), request_of(all)).id);
  for (AlphaMode mode : {AlphaMode::Mask, AlphaMode::Blend}) {
    s = masked_quad_scene(mode);
    r.upload(s);
    const GBuffer g = r.render(cam, ambient_only(1), request_of(all));
    const int disc = cv::countNonZero(g.id);
    EXPECT_NEAR(disc, square * std::numbers::pi * 0.16, 0.02 * disc) << alpha_mode_name(mode);
    EXPECT_EQ(cv::countNonZero(g.depth), disc);
    EXPECT_EQ(cv::countNonZero(g.ka), disc);
    cv::Mat channels[4];
    cv::split(g.color, channels);
    EXPECT_EQ(cv::countNonZero(channels[3]), disc);
    // The corners of the square are background, the centre is leaf-green.
    const cv::Rect box = cv::boundingRect(g.id != 0);
    EXPECT_NEAR(box.width, std::sqrt(disc / std::numbers::pi) * 2, 3);
    const cv::Vec4b centre = g.color.at<cv::Vec4b>(128, 128);
    EXPECT_GT(centre[1], centre[0] + 50);
  }
}

TEST(Raster, DoubleSidedBackFaceNormalFacesCamera) {
  Material two_sided;
  two_sided.double_sided = true;
  Scene s = scene_of({make_quad(1.0f, 0.0f)}, two_sided);
  set_ids(s.meshes[0], 1, 1);
  const Camera back = front_camera(s, 64, false, 180.0f);  // on -Z, sees the back face
  Rasterizer r(gl());
  r.upload(s);
  GBuffer g = r.render(back, ambient_only(1), request_of(Target::Normal | Target::Id));
  ASSERT_GT(cv::countNonZero(g.id), 64 * 64 / 4);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      if (g.id.at<int32_t>(y, x) != 0) {
        ASSERT_GT(g.normal.at<cv::Vec3f>(y, x)[2], 0.99f);
      }
    }
  }
  // Without vertex normals the flat normal faces the viewer from either side, ka = 1.
  s.meshes[0].normals.clear();
  r.upload(s);
  for (float az : {0.0f, 180.0f}) {
    g = r.render(front_camera(s, 64, false, az), ambient_only(1),
                 request_of(Target::Normal | Target::Id | Target::Ka));
    ASSERT_GT(cv::countNonZero(g.id), 64 * 64 / 4);
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 64; ++x) {
        if (g.id.at<int32_t>(y, x) == 0) continue;
        ASSERT_GT(g.normal.at<cv::Vec3f>(y, x)[2], 0.99f) << "az " << az;
        ASSERT_EQ(g.ka.at<float>(y, x), 1.0f);
      }
    }
  }
  // Single-sided: the back face is culled.
  s.materials[0].double_sided = false;
  r.upload(s);
  g = r.render(back, ambient_only(1), request_of(Target::Normal | Target::Id));
  EXPECT_EQ(cv::countNonZero(g.id), 0);
}

TEST(Raster, OutwardFoliageNormalsAreNotFlippedOnBackFaces) {
  // A baked (realigned) leaf's normal points out of the crown whichever side is seen.
  Material two_sided;
  two_sided.double_sided = true;
  Scene s = scene_of({make_quad(1.0f, 0.0f)}, two_sided);
  set_ids(s.meshes[0], 1, 1, Role::Foliage);
  s.meshes[0].outward_normals = true;
  Rasterizer r(gl());
  r.upload(s);
  const GBuffer g = r.render(front_camera(s, 64, false, 180.0f), ambient_only(1),
                             request_of(Target::Normal | Target::Id));
  ASSERT_GT(cv::countNonZero(g.id), 64 * 64 / 4);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      if (g.id.at<int32_t>(y, x) != 0) {
        ASSERT_LT(g.normal.at<cv::Vec3f>(y, x)[2], -0.99f);
      }
    }
  }
}

TEST(Raster, FiniteAndDeterministic) {
  const Scene s = spheres_scene();
  Rasterizer r(gl());
  r.upload(s);
  const Camera cam = make_orbit_camera(s.bounds(), OrbitParams{}, 96, 80);
  for (int ssaa : {1, 3}) {
    const RasterRequest req = request_of(kAllTargetsMask, IdKind::Cluster, ssaa);
    const GBuffer a = r.render(cam, Lighting::three_point(), req);
    const GBuffer b = r.render(cam, Lighting::three_point(), req);
    double ka_lo = 0, ka_hi = 0;
    cv::minMaxLoc(a.ka, &ka_lo, &ka_hi);
    EXPECT_GE(ka_lo, 0.0);
    EXPECT_LE(ka_hi, 1.0);  // interpolation must not push ka past 1
    for (Target t : kAllTargets) {
      const cv::Mat &ma = target_image(a, t), &mb = target_image(b, t);
      ASSERT_EQ(ma.size(), cv::Size(96, 80)) << target_name(t);
      if (ma.depth() == CV_32F) {
        EXPECT_TRUE(cv::checkRange(ma)) << target_name(t);
      }
      ASSERT_EQ(ma.total() * ma.elemSize(), mb.total() * mb.elemSize());
      EXPECT_EQ(std::memcmp(ma.data, mb.data, ma.total() * ma.elemSize()), 0) << target_name(t);
    }
  }
}

TEST(Raster, ResizesBetweenRenders) {
  const Scene s = sphere_scene(32, 16);
  Rasterizer r(gl());
  r.upload(s);
  for (auto [w, h] : {std::pair{64, 48}, std::pair{33, 101}, std::pair{64, 48}}) {
    const Camera cam = make_orbit_camera(s.bounds(), OrbitParams{}, w, h);
    const GBuffer g =
        r.render(cam, Lighting::three_point(), request_of(Target::Color | Target::Id));
    EXPECT_EQ(g.color.size(), cv::Size(w, h));
    EXPECT_EQ(g.id.size(), cv::Size(w, h));
    EXPECT_GT(cv::countNonZero(g.id), w * h / 20);  // the sphere fits the narrow side
  }
}

// Light conventions on a white quad facing +Z with no ambient: world-fixed vectors are
// world space, camera-fixed ones view space, point lights do not attenuate, the specular
// term adds white on top.
TEST(Raster, LightConventions) {
  Material white;
  white.base_color = glm::vec4(1.0f);
  white.double_sided = true;
  Scene s = scene_of({make_quad(1.0f, 0.0f)}, white);
  Rasterizer r(gl());
  r.upload(s);
  auto lit = [&](Light light, float az, float distance) {
    Lighting l = ambient_only(0.0f);
    light.color = glm::vec3(0.5f);
    l.lights = {light};
    const Camera cam = front_camera(s, 32, false, az, distance);
    const GBuffer g = r.render(cam, l, request_of(Target::Color));
    return srgb_to_linear(g.color.at<cv::Vec4b>(16, 16)[1]);
  };
  Light world;
  world.camera_fixed = false;
  world.vector = glm::vec3(0, 0, 1);
  EXPECT_NEAR(lit(world, 0, 4), 0.5f, 0.01f);
  EXPECT_NEAR(lit(world, 180, 4), 0.0f, 0.002f);  // the back side faces away from the light
  world.vector = glm::vec3(0, 0, -1);
  EXPECT_NEAR(lit(world, 0, 4), 0.0f, 0.002f);
  Light head;  // camera-fixed, from the viewer: lights whichever side is seen
  head.vector = glm::vec3(0, 0, 1);
  EXPECT_NEAR(lit(head, 0, 4), 0.5f, 0.01f);
  EXPECT_NEAR(lit(head, 180, 4), 0.5f, 0.01f);
  Light point;  // at the eye, in view space
  point.type = Light::Type::Point;
  point.vector = glm::vec3(0.0f);
  EXPECT_NEAR(lit(point, 0, 4), 0.5f, 0.01f);
  EXPECT_NEAR(lit(point, 0, 8), 0.5f, 0.01f);  // no fall-off with distance
  head.specular = 1.0f;
  head.shininess = 8.0f;
  EXPECT_NEAR(lit(head, 0, 4), 1.0f, 0.01f);  // 0.5 diffuse + 0.5 highlight (N = H)
}

TEST(Raster, InvalidRequestsThrow) {
  const Scene s = sphere_scene(8, 4);
  Rasterizer r(gl());
  r.upload(s);
  const Camera cam = front_camera(s, 16);
  EXPECT_THROW(
      r.render(cam, ambient_only(1), request_of(Target::Id | Target::Color, IdKind::Object, 5)),
      InputError);
  EXPECT_THROW(
      r.render(cam, ambient_only(1), request_of(Target::Id | Target::Color, IdKind::Object, 0)),
      InputError);
  EXPECT_NO_THROW(r.render(cam, ambient_only(1), request_of(kAllTargetsMask, IdKind::Object, 4)));
  // 4096^2 at SSAA 4 with every target would need ~13 GiB: refused before allocating.
  const Camera huge = front_camera(s, 4096);
  EXPECT_THROW(r.render(huge, ambient_only(1), request_of(kAllTargetsMask, IdKind::Object, 4)),
               InputError);
  Lighting many = Lighting::three_point();
  many.lights.resize(kMaxLights + 1);
  EXPECT_THROW(r.render(cam, many, request_of(Target::Id | Target::Color)), InputError);
  Scene bad = s;
  bad.meshes[0].indices.back() = 1u << 30;
  EXPECT_THROW(r.upload(bad), InputError);
}

}  // namespace
}  // namespace sylva

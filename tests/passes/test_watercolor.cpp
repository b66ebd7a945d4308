// Watercolor pass (Bousseau et al. 2006; Luft & Deussen 2006) on synthetic G-buffers: the
// pigment formula, determinism, wash edges, edge darkening, glazing, world-space turbulence
// under a rotating view, the paper, bad input and the graph node.
// Scenes from tests/passes/watercolor_scenes.h; scripts/look.sh writes the look images.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/graph/render_graph.h"
#include "core/params.h"
#include "passes/watercolor.h"
#include "passes/watercolor_textures.h"
#include "tests/passes/watercolor_scenes.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

using Scene = WatercolorScene;

WatercolorParams plain_params() {
  WatercolorParams p;
  p.paper_strength = 0;
  p.turbulence_strength = 0;
  p.wobble = 0;
  p.edge_darkening = 0;
  p.detail = 0;
  p.gradation = 0;
  p.warm_cool = 0;
  p.paper_color = glm::vec3(1.0f);
  return p;
}

float grey(const cv::Mat& bgra, int y, int x) {
  const cv::Vec4b& v = bgra.at<cv::Vec4b>(y, x);
  return (float(v[0]) + float(v[1]) + float(v[2])) / 3.0f;
}

bool identical(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// Pixels along the row through the centre, from the centre outwards, that lie strictly
// between the wash and the paper: the width of the edge.
int edge_width(const cv::Mat& out, cv::Point c) {
  const float inside = grey(out, c.y, c.x), paper = grey(out, c.y, out.cols - 1);
  int n = 0;
  for (int x = c.x; x < out.cols; ++x) {
    const float g = grey(out, c.y, x);
    if (g > inside + 2.0f && g < paper - 2.0f) ++n;
  }
  return n;
}

const glm::mat4 kIdentity(1.0f);

TEST(Watercolor, PigmentFormulaFixesBlackAndWhiteAndHalfIsIdentity) {
  for (float d : {0.0f, 0.5f, 1.0f, 1.5f, 2.0f}) {
    EXPECT_FLOAT_EQ(pigment_density(0.0f, d), 0.0f);
    EXPECT_FLOAT_EQ(pigment_density(1.0f, d), 1.0f);
  }
  for (float beta : {0.0f, 0.3f, 1.0f})
    for (float c : {0.0f, 0.1f, 0.37f, 0.5f, 0.9f, 1.0f})
      EXPECT_FLOAT_EQ(pigment_density(c, texture_density(0.5f, beta)), c);
  // Denser than 1 darkens, thinner lightens (Bousseau: d > 1 more pigment).
  EXPECT_LT(pigment_density(0.5f, texture_density(1.0f, 1.0f)), 0.5f);
  EXPECT_GT(pigment_density(0.5f, texture_density(0.0f, 1.0f)), 0.5f);
  EXPECT_FLOAT_EQ(pigment_density(0.5f, 2.0f), 0.25f);  // d = 2: c^2, two layers
}

Scene three_clusters(cv::Size size) {
  Scene s = empty_scene(size);
  const float w = float(size.width);
  add_disc(s, {0.4f * w, 0.45f * w}, 0.22f * w, 7, {0.10f, 0.45f, 0.12f}, 5.0f);
  add_disc(s, {0.6f * w, 0.5f * w}, 0.2f * w, 3, {0.05f, 0.25f, 0.35f}, 4.0f);
  add_disc(s, {0.5f * w, 0.65f * w}, 0.15f * w, 12, {0.3f, 0.5f, 0.2f}, 3.0f);
  return s;
}

TEST(Watercolor, SameInputsGiveTheSameBytes) {
  const Scene s = three_clusters({160, 160});
  const WatercolorParams p;
  const cv::Mat a = watercolor(s.img, kIdentity, p);
  const cv::Mat b = watercolor(s.img, kIdentity, p);
  ASSERT_EQ(a.type(), CV_8UC4);
  ASSERT_EQ(a.size(), s.img.id.size());
  EXPECT_TRUE(identical(a, b));
  WatercolorParams other = p;
  other.seed = 2;
  EXPECT_FALSE(identical(a, watercolor(s.img, kIdentity, other)));
}

TEST(Watercolor, DiscEdgeWidensWithSoftness) {
  Scene s = empty_scene({200, 200});
  add_disc(s, {100, 100}, 50, 5, {0.1f, 0.4f, 0.2f}, 4.0f);
  std::vector<int> widths;
  for (float soft : {0.0f, 0.5f, 1.0f}) {
    WatercolorParams p = plain_params();
    p.blur = 40;  // px at 1024 px: 7.8 px here
    p.edge_softness = soft;
    const cv::Mat out = watercolor(s.img, kIdentity, p);
    // A blob: the centre is the pigment, the corners paper.
    EXPECT_LT(grey(out, 100, 100), 200.0f);
    EXPECT_EQ(grey(out, 0, 0), 255.0f);
    widths.push_back(edge_width(out, {100, 100}));
  }
  EXPECT_LE(widths[0], 3);
  EXPECT_LT(widths[0], widths[1]);
  EXPECT_LT(widths[1], widths[2]);
}

TEST(Watercolor, EdgeDarkeningDarkensTheRim) {
  Scene s = empty_scene({200, 200});
  add_disc(s, {100, 100}, 60, 5, {0.2f, 0.5f, 0.3f}, 4.0f);
  for (float dark : {0.0f, 1.0f}) {
    WatercolorParams p = plain_params();
    p.blur = 30;
    p.edge_darkening = dark;
    const cv::Mat out = watercolor(s.img, kIdentity, p);
    float rim = 255;
    for (int x = 140; x < 175; ++x)
      rim = std::min(rim, grey(out, 100, x));
    const float centre = grey(out, 100, 100);
    if (dark == 0.0f) {
      EXPECT_GE(rim, centre - 1.0f);
    } else {
      EXPECT_LT(rim, centre - 15.0f);
    }
  }
}

TEST(Watercolor, OverlapsAreGlazed) {
  // A back wash continues under the front one: near their shared border the front wash is
  // darker than far from it, because the back pigment shows through.
  Scene s = empty_scene({240, 200});
  add_disc(s, {80, 100}, 60, 1, {0.2f, 0.6f, 0.9f}, 6.0f);    // back, blue-ish
  add_disc(s, {160, 100}, 60, 2, {0.8f, 0.5f, 0.15f}, 3.0f);  // front
  WatercolorParams p = plain_params();
  p.blur = 40;
  const cv::Mat out = watercolor(s.img, kIdentity, p);
  const float near_border = grey(out, 100, 104), far = grey(out, 100, 175);
  EXPECT_LT(near_border, far - 5.0f);
}

// Two views of the same world points: positions in view 2 are R * positions in view 1, and
// view_to_world_2 = view_to_world_1 * R^-1.
TEST(Watercolor, TurbulenceStaysOnTheWorldWhenTheViewRotates) {
  Scene s = three_clusters({128, 128});
  const glm::mat4 v2w1 = glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, -1.0f, 8.0f));
  const glm::mat4 r = glm::rotate(glm::mat4(1.0f), glm::radians(37.0f), glm::vec3(0, 1, 0.2f));
  const glm::mat4 v2w2 = v2w1 * glm::inverse(r);
  cv::Mat pos2 = s.img.position.clone();
  for (int y = 0; y < pos2.rows; ++y)
    for (int x = 0; x < pos2.cols; ++x) {
      cv::Vec3f& v = pos2.at<cv::Vec3f>(y, x);
      if (s.img.depth.at<float>(y, x) <= 0.0f) continue;
      const glm::vec3 q = glm::vec3(r * glm::vec4(v[0], v[1], v[2], 1.0f));
      v = cv::Vec3f(q.x, q.y, q.z);
    }
  WatercolorParams p;
  p.turbulence_size = "0.1";
  const cv::Mat t1 = watercolor_turbulence(s.img.position, s.img.depth, v2w1, p);
  const cv::Mat t2 = watercolor_turbulence(pos2, s.img.depth, v2w2, p);
  const cv::Mat wrong = watercolor_turbulence(pos2, s.img.depth, v2w1, p);
  const cv::Mat fg = s.img.depth > 0.0f;
  double lo = 0, hi = 0;
  cv::minMaxLoc(t1, &lo, &hi, nullptr, nullptr, fg);
  EXPECT_GT(hi - lo, 0.2);  // the noise varies over the plant
  EXPECT_LT(cv::norm(t1, t2, cv::NORM_INF, fg), 1e-4);
  EXPECT_GT(cv::norm(t1, wrong, cv::NORM_INF, fg), 0.05);  // a view-space lookup would swim
  // The whole pass agrees too (the paper is screen-space, the rest view-independent).
  p.reference_length = 2.0f;
  p.turbulence_size = "auto";
  const cv::Mat a = watercolor(s.img, v2w1, p);
  WatercolorImages rotated = s.img;
  rotated.position = pos2;
  const cv::Mat b = watercolor(rotated, v2w2, p);
  EXPECT_LE(cv::norm(a, b, cv::NORM_INF), 1.0);
}

TEST(Watercolor, EmptyIdBufferIsPaperOnly) {
  const Scene s = empty_scene({64, 48});
  WatercolorParams p;
  p.paper_strength = 0;
  const cv::Mat out = watercolor(s.img, kIdentity, p);
  const cv::Vec4b first = out.at<cv::Vec4b>(0, 0);
  EXPECT_NEAR(first[2], std::lround(srgb_encode(p.paper_color.r) * 255.0f), 1);
  EXPECT_NEAR(first[1], std::lround(srgb_encode(p.paper_color.g) * 255.0f), 1);
  EXPECT_NEAR(first[0], std::lround(srgb_encode(p.paper_color.b) * 255.0f), 1);
  EXPECT_EQ(cv::norm(out, cv::Mat(out.size(), CV_8UC4, cv::Scalar(first)), cv::NORM_INF), 0);
  // With grain the paper has relief but stays close to its colour.
  p.paper_strength = 1;
  const cv::Mat grain = watercolor(s.img, kIdentity, p);
  EXPECT_GT(cv::norm(grain, out, cv::NORM_INF), 0);
  EXPECT_LE(cv::norm(grain, out, cv::NORM_INF), 20);
}

TEST(Watercolor, PaperIsGeneratedDeterministicallyOrLoaded) {
  WatercolorParams p;
  const cv::Mat a = watercolor_paper({300, 200}, p);
  ASSERT_EQ(a.type(), CV_32FC1);
  EXPECT_TRUE(identical(a, watercolor_paper({300, 200}, p)));
  cv::Scalar mean, sd;
  cv::meanStdDev(a, mean, sd);
  EXPECT_NEAR(mean[0], 0.5, 0.02);
  EXPECT_GT(sd[0], 0.1);
  p.seed = 9;
  EXPECT_FALSE(identical(a, watercolor_paper({300, 200}, p)));

  const std::string dir = (std::filesystem::temp_directory_path() / "sylva-water-paper").string();
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/paper.png";
  cv::Mat tile(40, 50, CV_8UC1);
  cv::randu(tile, 0, 255);
  ASSERT_TRUE(cv::imwrite(path, tile));
  p.paper = path;
  const cv::Mat loaded = watercolor_paper({1024, 1024}, p);
  ASSERT_EQ(loaded.size(), cv::Size(1024, 1024));
  // Tiled at 1 px per px at the reference resolution.
  EXPECT_TRUE(identical(loaded(cv::Rect(0, 0, 50, 40)), loaded(cv::Rect(50, 40, 50, 40))));

  ParamSet set;
  WatercolorParams q;
  bind_watercolor_params(set, q);
  set.set_text("watercolor.paper", path, "test");
  EXPECT_EQ(q.paper, path);
  EXPECT_THROW(set.set_text("watercolor.paper", dir + "/missing.png", "test"), InputError);
  q.paper = dir + "/missing.png";  // e.g. deleted after the preset was read
  EXPECT_THROW(watercolor(three_clusters({32, 32}).img, kIdentity, q), InputError);
  std::filesystem::remove_all(dir);
}

TEST(Watercolor, PaperFieldIsDefinedEverywhereAndLoadedPaperTiles) {
  WatercolorParams p;
  const watercolor_internal::PaperField paper(p, 1.0);
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int y = -300; y < 300; y += 3)
    for (int x = -300; x < 300; x += 3) {
      const float v = paper.relief(float(x) + 0.5f, float(y) + 0.5f);
      ASSERT_GE(v, 0.0f);
      ASSERT_LE(v, 1.0f);
      sum += v;
      sum2 += double(v) * v;
      ++n;
    }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.5, 0.05);
  EXPECT_NEAR(sd, 0.18, 0.04);
  const watercolor_internal::PaperField again(p, 1.0);
  EXPECT_EQ(paper.relief(-123.25f, 77.5f), again.relief(-123.25f, 77.5f));
  const cv::Vec2f g = paper.slope(10.0f, 20.0f);
  EXPECT_TRUE(std::isfinite(g[0]) && std::isfinite(g[1]));
  // A loaded image repeats with its size (at the 1024 px reference, 1 image px per px).
  const std::string dir = temp_dir("watercolor-paper-field");
  cv::Mat img(40, 30, CV_8UC1);
  cv::randu(img, 0, 256);
  ASSERT_TRUE(cv::imwrite(dir + "/paper.png", img));
  p.paper = dir + "/paper.png";
  const watercolor_internal::PaperField tiled(p, 1.0);
  EXPECT_NEAR(tiled.relief(5.5f, 7.5f), tiled.relief(35.5f, 47.5f), 1e-5f);
  EXPECT_NEAR(tiled.relief(5.5f, 7.5f), tiled.relief(-24.5f, -32.5f), 1e-5f);
}

TEST(Watercolor, AlbedoPigmentNeedsTheAlbedo) {
  Scene s = three_clusters({64, 64});
  WatercolorParams p;
  p.pigment = Pigment::Albedo;
  EXPECT_NO_THROW(watercolor(s.img, kIdentity, p));
  s.img.albedo.release();
  EXPECT_THROW(watercolor(s.img, kIdentity, p), InputError);
}

TEST(Watercolor, DetailFollowsTheBlurredDepthTest) {
  cv::RNG rng(4);
  Scene s = empty_scene({200, 200});
  add_clump(s, rng, {100, 100}, 60, 3, {0.1f, 0.4f, 0.15f}, 5.0f, 300, 12);
  const cv::Rect inner(80, 80, 40, 40);
  cv::Scalar m, none, some;
  WatercolorParams p = plain_params();
  p.blur = 20;
  p.detail = 0;
  cv::meanStdDev(watercolor(s.img, kIdentity, p)(inner), m, none);
  p.detail = 1;
  cv::meanStdDev(watercolor(s.img, kIdentity, p)(inner), m, some);
  EXPECT_LT(none[1], 1.0);
  EXPECT_GT(some[1], 3.0 * none[1] + 2.0);
}

TEST(Watercolor, RimsDarkenAtTheOuterEdgeAndAtDepthStepsOnly) {
  // Two overlapping discs: the front one's rim over the back one darkens only when their depth
  // step exceeds rim_step of the depth range; the outer edge darkens either way.
  Scene s = empty_scene({240, 200});
  add_disc(s, {80, 100}, 60, 1, {0.2f, 0.5f, 0.3f}, 6.0f);   // back
  add_disc(s, {160, 100}, 60, 2, {0.2f, 0.5f, 0.3f}, 3.0f);  // front
  WatercolorParams p = plain_params();
  p.blur = 12;
  p.edge_darkening = 1;
  p.rim_step = 0;
  const cv::Mat every = watercolor(s.img, kIdentity, p);
  p.rim_step = 1;
  const cv::Mat outer = watercolor(s.img, kIdentity, p);
  auto darkest = [](const cv::Mat& out, int x0, int x1) {
    float g = 255;
    for (int x = x0; x < x1; ++x)
      g = std::min(g, grey(out, 100, x));
    return g;
  };
  // The front disc's edge over the back disc (x = 100) and its outer edge (x = 220).
  EXPECT_LT(darkest(every, 94, 108), darkest(outer, 94, 108) - 8.0f);
  EXPECT_NEAR(darkest(every, 205, 232), darkest(outer, 205, 232), 1.0f);
  EXPECT_LT(darkest(outer, 205, 232), grey(outer, 100, 160) - 8.0f);
}

TEST(Watercolor, GradationFollowsTheLightInsideAWash) {
  // One disc lit from the right: its shaded colour brightens with x. Flat at gradation 0,
  // darker on the left than on the right at 1.
  Scene s = empty_scene({200, 200});
  add_disc(s, {100, 100}, 70, 1, {0.2f, 0.5f, 0.3f}, 4.0f);
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x)
      if (s.img.id.at<int32_t>(y, x) == 1) {
        const float lit = 0.3f + 0.7f * float(x - 30) / 140.0f;
        const cv::Vec3f c(0.2f * lit, 0.5f * lit, 0.3f * lit);
        set_pixel(s, x, y, 1, c, s.img.depth.at<float>(y, x));
      }
  WatercolorParams p = plain_params();
  p.blur = 10;
  const cv::Mat flat = watercolor(s.img, kIdentity, p);
  p.gradation = 1;
  const cv::Mat graded = watercolor(s.img, kIdentity, p);
  EXPECT_NEAR(grey(flat, 100, 60), grey(flat, 100, 140), 1.0f);
  EXPECT_LT(grey(graded, 100, 60), grey(graded, 100, 140) - 20.0f);
}

TEST(Watercolor, WarmLightCoolShade) {
  // The same disc: with warm_cool its lit (right) side turns redder and its shaded (left) side
  // bluer than without, the wash's value staying about the same.
  Scene s = empty_scene({200, 200});
  add_disc(s, {100, 100}, 70, 1, {0.3f, 0.5f, 0.3f}, 4.0f);
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x)
      if (s.img.id.at<int32_t>(y, x) == 1) {
        const float lit = 0.3f + 0.7f * float(x - 30) / 140.0f;
        set_pixel(s, x, y, 1, cv::Vec3f(0.3f, 0.5f, 0.3f) * lit, s.img.depth.at<float>(y, x));
      }
  WatercolorParams p = plain_params();
  p.blur = 10;
  p.gradation = 1;
  const cv::Mat plain = watercolor(s.img, kIdentity, p);
  p.warm_cool = 1;
  const cv::Mat tinted = watercolor(s.img, kIdentity, p);
  auto red_over_blue = [](const cv::Mat& m, int x) {
    const cv::Vec4b v = m.at<cv::Vec4b>(100, x);
    return float(v[2]) - float(v[0]);
  };
  EXPECT_GT(red_over_blue(tinted, 150), red_over_blue(plain, 150) + 3.0f) << "warm light";
  EXPECT_LT(red_over_blue(tinted, 50), red_over_blue(plain, 50) - 3.0f) << "cool shade";
  EXPECT_NEAR(grey(tinted, 100, 150), grey(plain, 100, 150), 6.0f);
}

TEST(Watercolor, TheWoodIsPaintedWhereverItIsSeen) {
  // A trunk (id 99) behind a sparse crown of three leaves: the blurred leaf washes would close
  // the gaps between the leaves; the trunk is painted bare of them wherever it is seen.
  Scene s = empty_scene({200, 240});
  const cv::Vec3f bark(0.05f, 0.12f, 0.25f), leaf(0.08f, 0.35f, 0.1f);  // BGR linear
  add_rect(s, cv::Rect(85, 0, 30, 240), 99, bark, 10.0f);
  for (int i = 0; i < 3; ++i)  // one cluster of three leaves, 6 px apart
    add_disc(s, {100.0f, 40.0f + 80.0f * float(i)}, 37, 1, leaf, 6.0f);
  WatercolorParams p = plain_params();
  p.blur = 30;
  const cv::Point gap(100, 80);  // on the trunk, between the first two leaves
  ASSERT_EQ(s.img.id.at<int32_t>(gap), 99);
  auto reddish = [&](const cv::Mat& out) {
    const cv::Vec4b v = out.at<cv::Vec4b>(gap);
    return float(v[2]) - float(v[1]);  // R - G: bark > 0, leaves < 0
  };
  s.img.wood_cluster = 0;  // the trunk a wash like any other: glazed over by the leaves
  const float plain = reddish(watercolor(s.img, kIdentity, p));
  s.img.wood_cluster = 99;
  const float wood = reddish(watercolor(s.img, kIdentity, p));
  EXPECT_GT(wood, 10.0f);
  EXPECT_GT(wood, plain + 20.0f) << "plain " << plain;
}

TEST(Watercolor, LeafDetailFadesContinuouslyWithDepth) {
  // Luft & Deussen's blurred depth test: a leaf moving out of its clump (in front of the clump's
  // surface at every depth here) shows its own shade gradually, with no jump between two
  // nearby depths.
  std::vector<float> g;
  for (int i = 0; i <= 30; ++i) {
    Scene s = empty_scene({160, 160});
    add_disc(s, {80, 80}, 50, 1, {0.2f, 0.5f, 0.3f}, 5.0f);
    // Near the disc's rim, where its surface lies behind its blurred depth.
    add_rect(s, cv::Rect(116, 74, 12, 12), 1, {0.02f, 0.06f, 0.03f}, 4.72f - 0.01f * float(i));
    WatercolorParams p = plain_params();
    p.blur = 15;
    p.detail = 1;
    g.push_back(grey(watercolor(s.img, kIdentity, p), 80, 122));
  }
  const float total = std::abs(g.front() - g.back());
  std::string values;
  for (float v : g)
    values += std::to_string(int(v)) + " ";
  SCOPED_TRACE(values);
  EXPECT_GT(total, 10.0f);
  for (size_t i = 1; i < g.size(); ++i)
    EXPECT_LT(std::abs(g[i] - g[i - 1]), 0.35f * total) << i;
}

TEST(Watercolor, GraphPassReadsOnlyWhatItUses) {
  const Scene s = three_clusters({64, 64});
  for (bool turbulence : {false, true}) {
    RenderGraph g;
    WatercolorResources res;
    res.color = g.resource<cv::Mat>("color");
    res.albedo = g.resource<cv::Mat>("albedo");
    res.id = g.resource<cv::Mat>("id");
    res.depth = g.resource<cv::Mat>("depth");
    res.position = g.resource<cv::Mat>("position");
    auto source = [&](const char* name, ImageHandle r, cv::Mat m) {
      g.add_pass(std::string("make ") + name, {}, {r},
                 [r, m](PassContext& ctx) { ctx.write(r, m); });
    };
    source("color", res.color, s.img.color);
    source("albedo", res.albedo, s.img.albedo);
    source("id", res.id, s.img.id);
    source("depth", res.depth, s.img.depth);
    source("position", res.position, s.img.position);
    WatercolorParams p;
    p.turbulence_strength = turbulence ? 0.5f : 0.0f;
    const auto out = add_watercolor_pass(g, res, kIdentity, p);
    EXPECT_EQ(g.resource_name(out), "watercolor");
    g.present(out);
    g.compile();
    EXPECT_FALSE(g.pass_live("make albedo"));
    EXPECT_EQ(g.pass_live("make position"), turbulence);
    g.execute();
    EXPECT_TRUE(identical(g.get<cv::Mat>(out), watercolor(s.img, kIdentity, p)));
  }
}

}  // namespace
}  // namespace sylva::test

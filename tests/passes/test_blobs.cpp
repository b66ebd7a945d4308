// Blob painting (Dudley 2005 ch. 4) on synthetic buffers: painter's order by nearest leaf,
// the wash/detail blend, outlines wider on the left, translucency, the branch base layer,
// silhouettes, determinism, parameter extremes and the graph node.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "core/color.h"
#include "core/error.h"
#include "core/graph/render_graph.h"
#include "npr/blob_keyframes.h"
#include "passes/blobs.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

struct Buffers {
  BlobImages img;
  cv::Mat depth;
};

Buffers empty_buffers(int size) {
  Buffers b;
  b.img.color = cv::Mat(size, size, CV_8UC4, cv::Scalar(0, 0, 0, 0));
  b.img.albedo = cv::Mat(size, size, CV_8UC4, cv::Scalar(0, 0, 0, 0));
  b.img.id = cv::Mat(size, size, CV_32SC1, cv::Scalar(0));
  b.depth = cv::Mat(size, size, CV_32FC1, cv::Scalar(0));
  return b;
}

// A disc of leaves of one cluster: colour and albedo `bgr` (sRGB bytes), at `depth`.
void add_disc(Buffers& b, cv::Point c, int r, int cluster, cv::Scalar bgr, float depth) {
  cv::circle(b.img.id, c, r, cv::Scalar(cluster), cv::FILLED);
  cv::circle(b.img.color, c, r, bgr + cv::Scalar(0, 0, 0, 255), cv::FILLED);
  cv::circle(b.img.albedo, c, r, bgr + cv::Scalar(0, 0, 0, 255), cv::FILLED);
  cv::circle(b.depth, c, r, cv::Scalar(depth), cv::FILLED);
}

// Flat, unlit wash only: ambient 1, no lights, no peaks, alpha 1 (no detail), no outline.
BlobParams wash_only() {
  BlobParams p;
  p.peak_height = 0;
  p.blend_ambient = 1;
  p.blend_diffuse = 0;
  p.edge_width = 0;
  p.variation = 0;
  return p;
}

BlobFrame flat_frame() {
  BlobFrame f;
  f.lighting.ambient = 1.0f;
  f.background = {1, 1, 1, 1};
  return f;
}

cv::Mat paint(const Buffers& b, const BlobParams& p, const BlobFrame& f = flat_frame()) {
  ShrinkWrapParams sw;
  sw.control_points = p.control_points;
  sw.step = p.step;
  return paint_blobs(
      b.img, still_blob_set(find_blob_outlines(b.img.id, b.depth, f.branch_cluster, sw)), f, p);
}

TEST(Blobs, PainterOrderByNearestLeaf) {
  // Two clusters whose leaves interleave over one disc (4-px stripes): both outlines cover
  // the disc, and whichever is painted last covers it all.
  Buffers b = empty_buffers(128);
  add_disc(b, {64, 64}, 40, 1, cv::Scalar(0, 0, 200), 1.0f);  // red
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x)
      if (b.img.id.at<int32_t>(y, x) && (x / 4) % 2) {
        b.img.id.at<int32_t>(y, x) = 2;  // blue
        b.img.color.at<cv::Vec4b>(y, x) = b.img.albedo.at<cv::Vec4b>(y, x) =
            cv::Vec4b(200, 0, 0, 255);
        b.depth.at<float>(y, x) = 2.0f;
      }
  cv::Mat out = paint(b, wash_only());
  // Red's nearest leaf (1.0) is nearer than blue's (2.0): red is painted last, over blue.
  for (cv::Point q : {cv::Point(64, 64), cv::Point(66, 64), cv::Point(50, 80)}) {
    EXPECT_GT(out.at<cv::Vec4b>(q)[2], 150) << q;
    EXPECT_LT(out.at<cv::Vec4b>(q)[0], 30) << q;
  }
  // One blue leaf pixel nearer than any red one: blue's nearest leaf decides, blue goes last.
  b.depth.at<float>(64, 68) = 0.5f;
  out = paint(b, wash_only());
  for (cv::Point q : {cv::Point(64, 64), cv::Point(66, 64), cv::Point(50, 80)}) {
    EXPECT_GT(out.at<cv::Vec4b>(q)[0], 150) << q;
    EXPECT_LT(out.at<cv::Vec4b>(q)[2], 30) << q;
  }
  // Background stays the background.
  EXPECT_EQ(out.at<cv::Vec4b>(2, 2), cv::Vec4b(255, 255, 255, 255));
}

// Dudley §5.1: when the depth order of two overlapping blobs swaps between keyframes, the
// frames between cross-fade instead of popping in one frame.
TEST(Blobs, DepthSwapCrossFadesWithoutAPop) {
  Buffers b = empty_buffers(64);
  add_disc(b, {32, 32}, 20, 1, cv::Scalar(0, 0, 200), 1.0f);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (b.img.id.at<int32_t>(y, x) && (x / 4) % 2) {
        b.img.id.at<int32_t>(y, x) = 2;
        b.img.color.at<cv::Vec4b>(y, x) = b.img.albedo.at<cv::Vec4b>(y, x) =
            cv::Vec4b(200, 0, 0, 255);
      }
  const auto outlines = find_blob_outlines(b.img.id, b.depth, 0, {});
  ASSERT_EQ(outlines.size(), 2u);
  const int every = 8;
  BlobKeyframes keys(every + 1, every, [&](int f) {
    std::vector<BlobOutline> o = outlines;
    o[0].min_depth = f == 0 ? 1.0f : 3.0f;  // red in front at key 0, behind at key 1
    o[1].min_depth = 2.0f;
    return o;
  });
  std::vector<cv::Vec4b> px;
  for (int f = 0; f <= every; ++f)
    px.push_back(
        paint_blobs(b.img, keys.frame(f), flat_frame(), wash_only()).at<cv::Vec4b>(32, 33));
  EXPECT_GT(px.front()[2], 150);  // red on top
  EXPECT_GT(px.back()[0], 150);   // blue on top
  // The fade is linear in linear light: equal steps of 1/8 of the change, not one jump.
  auto lin = [](uint8_t v) { return srgb_to_linear(v / 255.0f); };
  const float total = lin(px.back()[0]) - lin(px.front()[0]);
  for (int f = 1; f <= every; ++f)
    EXPECT_NEAR(lin(px[f][0]) - lin(px[f - 1][0]), total / every, 0.02f) << "frame " << f;
}

TEST(Blobs, BlendMaskMixesWashAndDetail) {
  Buffers b = empty_buffers(96);
  add_disc(b, {48, 48}, 30, 1, cv::Scalar(40, 160, 60), 1.0f);
  // Detail differs from the albedo: a checkered pattern of dark and light leaves.
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x)
      if (b.img.id.at<int32_t>(y, x) && ((x / 4 + y / 4) % 2))
        b.img.color.at<cv::Vec4b>(y, x) = cv::Vec4b(10, 30, 10, 255);
  BlobParams p = wash_only();
  p.blend_ambient = 0;  // alpha 0: all detail
  const cv::Mat detail = paint(b, p);
  for (cv::Point q : {cv::Point(44, 44), cv::Point(48, 48), cv::Point(52, 40)}) {
    const cv::Vec4b want = b.img.color.at<cv::Vec4b>(q);
    const cv::Vec4b got = detail.at<cv::Vec4b>(q);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(got[k], want[k], 1) << q;
  }
  // Alpha 1: the flat wash (the cluster's mean albedo) everywhere inside.
  const cv::Mat wash = paint(b, wash_only());
  EXPECT_EQ(wash.at<cv::Vec4b>(44, 44), wash.at<cv::Vec4b>(48, 48));
  // A directional blend light from the right, diffuse only, on a domed blob: the right side
  // gets the wash (bright under the blend light), the left side the leaves' detail.
  BlobParams lit = wash_only();
  lit.peak_height = 1.0f;
  lit.blend_ambient = 0;
  lit.blend_diffuse = 1.0f;
  lit.blend_right = 10.0f;
  lit.blend_up = 0.0f;
  const cv::Mat mixed = paint(b, lit);
  double left = 0, right = 0;
  for (int y = 40; y < 56; ++y) {
    for (int x = 24; x < 36; ++x)
      left += cv::norm(mixed.at<cv::Vec4b>(y, x), wash.at<cv::Vec4b>(y, x));
    for (int x = 60; x < 72; ++x)
      right += cv::norm(mixed.at<cv::Vec4b>(y, x), wash.at<cv::Vec4b>(y, x));
  }
  EXPECT_GT(left, 3 * right);
}

TEST(Blobs, OutlineWiderOnTheLeft) {
  Buffers b = empty_buffers(256);
  add_disc(b, {128, 128}, 80, 1, cv::Scalar(200, 200, 200), 1.0f);
  BlobParams p = wash_only();
  p.control_points = 60;
  p.step = 0.05f;
  p.edge_width = 16;  // 4 px at 256 px
  p.edge_tone = 0;    // black
  p.edge_left = 1;    // 8 px where the edge is on the left
  const cv::Mat out = paint(b, p);
  // Ink along a line of pixels from outside the blob inward: sum of the darkening below the
  // wash (200), over the first `n` pixels that are not background.
  auto ink = [&](cv::Point from, cv::Point step) {
    double sum = 0;
    int inside = 0;
    for (cv::Point q = from; inside < 24; q += step) {
      const int v = out.at<cv::Vec4b>(q)[1];
      if (v == 255) continue;
      ++inside;
      sum += std::clamp(1.0 - v / 200.0, 0.0, 1.0);
    }
    return sum;
  };
  EXPECT_NEAR(ink({0, 128}, {1, 0}), 8.0, 1.0);     // left rim: (1 + edge_left) x 4 px
  EXPECT_NEAR(ink({255, 128}, {-1, 0}), 4.0, 1.0);  // right rim: 4 px
  // Top: 4 px, plus the round ends of the wider strokes just left of it.
  EXPECT_NEAR(ink({128, 0}, {0, 1}), 5.0, 1.0);
  EXPECT_NEAR(ink({128, 255}, {0, -1}), 4.0, 1.0);  // bottom: 4 px
}

TEST(Blobs, TranslucencyBranchesAndSilhouettes) {
  Buffers b = empty_buffers(96);
  cv::rectangle(b.img.id, cv::Rect(44, 40, 8, 56), cv::Scalar(7), cv::FILLED);  // trunk
  cv::rectangle(b.img.color, cv::Rect(44, 40, 8, 56), cv::Scalar(20, 60, 100, 255), cv::FILLED);
  cv::rectangle(b.img.albedo, cv::Rect(44, 40, 8, 56), cv::Scalar(20, 60, 100, 255), cv::FILLED);
  add_disc(b, {48, 30}, 20, 1, cv::Scalar(40, 160, 60), 1.0f);
  BlobFrame f = flat_frame();
  f.branch_cluster = 7;
  // The trunk is not a blob: it comes straight from the colour buffer.
  const cv::Mat out = paint(b, wash_only(), f);
  EXPECT_EQ(out.at<cv::Vec4b>(80, 48), cv::Vec4b(20, 60, 100, 255));
  EXPECT_NE(out.at<cv::Vec4b>(30, 48), cv::Vec4b(255, 255, 255, 255));
  // Fully translucent blobs leave the trunk and the background.
  BlobParams clear = wash_only();
  clear.translucency = 1.0f;
  const cv::Mat bare = paint(b, clear, f);
  EXPECT_EQ(bare.at<cv::Vec4b>(30, 30), cv::Vec4b(255, 255, 255, 255));
  EXPECT_EQ(bare.at<cv::Vec4b>(60, 48), cv::Vec4b(20, 60, 100, 255));
  // Silhouette lines in the detail take silhouette_tone x the unlit blob colour.
  BlobParams sil = wash_only();
  sil.blend_ambient = 0;
  sil.silhouette_tone = 0;
  b.img.lines = cv::Mat::zeros(96, 96, CV_32FC1);
  cv::line(b.img.lines, {40, 30}, {56, 30}, cv::Scalar(1.0f), 1);
  const cv::Mat lined = paint(b, sil, f);
  EXPECT_EQ(lined.at<cv::Vec4b>(30, 48), cv::Vec4b(0, 0, 0, 255));
  EXPECT_EQ(lined.at<cv::Vec4b>(34, 48), b.img.color.at<cv::Vec4b>(34, 48));
}

TEST(Blobs, DeterministicAndVariationSeeded) {
  Buffers b = empty_buffers(96);
  const cv::Point centres[] = {{20, 20}, {60, 20}, {20, 60}, {60, 60}};
  for (int i = 0; i < 4; ++i)
    add_disc(b, centres[i], 12, i + 1, cv::Scalar(40, 160, 60), 1.0f + float(i));
  BlobParams p;
  p.variation = 0.5f;
  BlobFrame f = flat_frame();
  f.lighting = Lighting::three_point();
  const cv::Mat a = paint(b, p, f), a2 = paint(b, p, f);
  EXPECT_EQ(cv::norm(a, a2, cv::NORM_INF), 0.0);
  // The same albedo gives differently toned blobs; another seed other tones.
  BlobParams q = wash_only();
  q.variation = 0.5f;
  const cv::Mat v = paint(b, q);
  int spread = 0;  // the tones of four blobs span more than a few levels
  for (const cv::Point& c : centres)
    spread = std::max(spread,
                      std::abs(int(v.at<cv::Vec4b>(c)[1]) - int(v.at<cv::Vec4b>(centres[0])[1])));
  EXPECT_GT(spread, 10);
  q.seed = 2;
  EXPECT_GT(cv::norm(paint(b, q), v, cv::NORM_INF), 0.0);
}

TEST(Blobs, ExtremesAndBadValues) {
  Buffers b = empty_buffers(64);
  add_disc(b, {32, 32}, 12, 1, cv::Scalar(40, 160, 60), 1.0f);
  b.img.id.at<int32_t>(0, 0) = 2;  // a one-pixel cluster in the corner
  b.img.color.at<cv::Vec4b>(0, 0) = cv::Vec4b(0, 0, 255, 255);
  b.img.albedo.at<cv::Vec4b>(0, 0) = cv::Vec4b(0, 0, 255, 255);
  b.img.position = cv::Mat(64, 64, CV_32FC3, cv::Scalar(0, 0, -3));
  BlobFrame f = flat_frame();
  f.lighting = Lighting::three_point();
  for (int end = 0; end < 2; ++end) {
    BlobParams p;
    const bool hi = end == 1;
    p.control_points = hi ? 512 : 3;
    p.step = hi ? 1.0f : 0.001f;
    p.peaks = hi ? 16 : 1;
    p.peak_height = hi ? 2.0f : 0.0f;
    p.blend_light = hi ? BlendLight::Point : BlendLight::Directional;
    p.blend_right = p.blend_up = hi ? 10.0f : -10.0f;
    p.blend_ambient = hi ? 1.0f : 0.0f;
    p.blend_diffuse = hi ? 2.0f : 0.0f;
    p.silhouette_tone = hi ? 10.0f : 0.0f;
    p.edge_width = hi ? 32.0f : 0.0f;
    p.edge_left = hi ? 4.0f : 0.0f;
    p.edge_tone = hi ? 10.0f : 0.0f;
    p.translucency = hi ? 1.0f : 0.0f;
    p.variation = hi ? 0.5f : 0.0f;
    p.seed = hi ? 2147483647 : 0;
    const cv::Mat out = paint(b, p, f);
    EXPECT_EQ(out.size(), cv::Size(64, 64)) << end;
  }
  // No clusters at all: the background.
  const cv::Mat none = paint(empty_buffers(16), BlobParams{});
  EXPECT_EQ(cv::countNonZero(none.reshape(1) != 255), 0);
  auto where = [&](auto set) {
    BlobParams p;
    set(p);
    return where_of([&] { validate_blob_params(p); });
  };
  EXPECT_EQ(where([](BlobParams& p) { p.peaks = 0; }), "blobs.peaks");
  EXPECT_EQ(where([](BlobParams& p) { p.peaks = 17; }), "blobs.peaks");
  EXPECT_EQ(where([](BlobParams& p) { p.step = 0; }), "blobs.step");
  EXPECT_EQ(where([](BlobParams& p) { p.control_points = 2; }), "blobs.control_points");
  EXPECT_EQ(where([](BlobParams& p) { p.peak_height = 2.01f; }), "blobs.peak_height");
  EXPECT_EQ(where([](BlobParams& p) { p.translucency = -0.01f; }), "blobs.translucency");
  EXPECT_EQ(where([](BlobParams& p) { p.edge_width = 32.5f; }), "blobs.edge_width");
  EXPECT_EQ(where([](BlobParams& p) { p.blend_right = 10.5f; }), "blobs.blend_right");
  EXPECT_EQ(where([](BlobParams& p) { p.blend_light = static_cast<BlendLight>(7); }),
            "blobs.blend_light");
  EXPECT_EQ(where([](BlobParams& p) { p.variation = 0.6f; }), "blobs.variation");
}

TEST(Blobs, GraphNodesReadOnlyWhatTheyNeed) {
  RenderGraph g;
  const ImageHandle color = g.resource<cv::Mat>("color"), albedo = g.resource<cv::Mat>("albedo"),
                    id = g.resource<cv::Mat>("id"), depth = g.resource<cv::Mat>("depth"),
                    position = g.resource<cv::Mat>("position");
  Buffers b = empty_buffers(32);
  add_disc(b, {16, 16}, 8, 1, cv::Scalar(40, 160, 60), 1.0f);
  g.add_pass("raster", {}, {color, albedo, id, depth, position}, [&](PassContext& ctx) {
    ctx.write(color, b.img.color);
    ctx.write(albedo, b.img.albedo);
    ctx.write(id, b.img.id);
    ctx.write(depth, b.depth);
    ctx.write(position, cv::Mat());
  });
  const BlobParams p = wash_only();
  const auto outlines = add_blob_outlines_pass(g, id, depth, 0, p);
  BlobResources r;
  r.color = color;
  r.albedo = albedo;
  r.id = id;
  r.position = position;
  const auto out = add_blobs_pass(g, outlines, r, flat_frame(), p);
  g.present(out);
  g.compile();
  g.execute();
  const cv::Mat img = g.get<cv::Mat>(out);
  EXPECT_EQ(img.type(), CV_8UC4);
  EXPECT_EQ(cv::norm(img, paint(b, p), cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace sylva::test

// The foliage's drawing primitives (passes/leaf_primitives.h) on synthetic scenes of known
// geometry: a disc in front of another is outlined where it overlaps it only when the depth
// step between them passes leaves.depth_step (and against the paper always); a card cut by its
// texture's alpha gives a primitive of the cut shape, not of the card; on a sphere of leaves lit
// from one side the tone rank follows the shading and the black fill lies on the dark side; the
// output is finite and deterministic. Every parameter at both ends of its range:
// tests/styles/test_every_parameter.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numeric>
#include <opencv2/imgproc.hpp>

#include "core/stroke_render.h"
#include "npr/leaf_pieces.h"
#include "npr/surface_samples.h"
#include "passes/leaf_primitives.h"
#include "tests/passes/front_view.h"

namespace sylva::test {
namespace {

constexpr int kSize = kFrontSize;

// A flat round leaf of radius r facing the camera: the covariance of a uniform disc.
LeafPiece disc_piece(glm::vec3 centre, float r, uint32_t cluster) {
  LeafPiece p;
  p.centre = centre;
  p.cov[0] = p.cov[3] = r * r / 4.0f;
  p.area = float(M_PI) * r * r;
  p.cluster = cluster;
  return p;
}

LeafImages images_of(std::vector<LeafPiece> pieces, cv::Mat color = {}) {
  auto lp = std::make_shared<LeafPieces>();
  lp->pieces = std::move(pieces);
  lp->cell = 0.05f;
  LeafImages in;
  in.pieces = lp;
  in.camera = front_camera();
  in.color = color.empty() ? cv::Mat(kSize, kSize, CV_8UC4, cv::Scalar(128, 128, 128, 255)) : color;
  in.depth = cv::Mat(kSize, kSize, CV_32FC1, cv::Scalar(0));
  in.wood.depth = in.depth;
  return in;
}

// Primitives of their own shape and size, no zones, no fade: outlines on or off by the step.
LeafParams plain() {
  LeafParams p;
  p.shape = LeafShape::Disc;
  p.size = 0.1f;
  p.fade = 0.0f;
  p.lit = 0.0f;
  p.black = 0.0f;
  p.shadow = 0.0f;
  return p;
}

InkLineParams ink_lines() {
  InkLineParams l;
  l.detail = 10.0f;
  return l;
}

std::vector<glm::vec2> points_of(const StrokeDrawing& d, LineClass cls) {
  std::vector<glm::vec2> out;
  for (const Stroke& s : d.strokes)
    if (s.cls == cls) out.insert(out.end(), s.points.begin(), s.points.end());
  return out;
}

bool finite(const StrokeDrawing& d) {
  for (const Stroke& s : d.strokes) {
    for (const glm::vec2& q : s.points)
      if (!std::isfinite(q.x) || !std::isfinite(q.y)) return false;
    for (float w : s.widths)
      if (!std::isfinite(w) || w < 0.0f) return false;
  }
  return true;
}

// Two overlapping discs 0.3 apart in depth, and a third far behind, beside the back one and
// touching it (one plant in the picture), that makes the plant's depth extent 1.
const glm::vec3 kThird{0.72f, 0, -0.5f};
std::vector<LeafPiece> two_discs() {
  return {disc_piece({-0.3f, 0, 0.5f}, 0.6f, 1), disc_piece({0.3f, 0, 0.2f}, 0.6f, 2),
          disc_piece(kThird, 0.3f, 3)};
}

// Not on the third disc's outline (the back disc stands well in front of it).
bool off_the_third(const glm::vec2& q) {
  const cv::Point2f c = to_px({kThird.x, kThird.y, 0});
  return std::hypot(q.x - c.x, q.y - c.y) > 0.3f / 4.0f * kSize + 3.0f;
}

TEST(LeafPrimitives, TheFrontDiscIsOutlinedOverTheBackOneOnlyAboveTheDepthStep) {
  const LeafImages in = images_of(two_discs());
  const cv::Point2f front = to_px({-0.3f, 0, 0}), back = to_px({0.3f, 0, 0});
  const float r = 0.6f / 4.0f * kSize;
  for (float step : {0.2f, 0.4f}) {
    LeafParams p = plain();
    p.depth_step = step;
    const LeafLayer layer = leaf_layer(in, p, ink_lines(), EdgeParams{});
    ASSERT_TRUE(finite(layer.drawing));
    std::vector<glm::vec2> inner = points_of(layer.drawing, LineClass::Foliage);
    std::erase_if(inner, [](const glm::vec2& q) { return !off_the_third(q); });
    // The gap is 0.3 of the extent: outlined at a step of 0.2, not at 0.4.
    if (step < 0.3f) {
      ASSERT_GT(inner.size(), 10u);
      for (const glm::vec2& q : inner) {
        // On the front disc's edge (the line lies just inside it), over the back disc.
        EXPECT_NEAR(std::hypot(q.x - front.x, q.y - front.y), r, 2.5f);
        EXPECT_LT(std::hypot(q.x - back.x, q.y - back.y), r + 1.0f);
      }
    } else {
      EXPECT_TRUE(inner.empty()) << inner.size() << " interior points at a step of " << step;
    }
    // Against the paper every disc is outlined.
    EXPECT_GT(points_of(layer.drawing, LineClass::Silhouette).size(), 50u);
  }
}

TEST(LeafPrimitives, TheOutlinesFadeInOverTheBandAroundTheStep) {
  const LeafImages in = images_of(two_discs());
  LeafParams p = plain();
  p.fade = 0.5f;
  auto widest = [&](float step) {
    p.depth_step = step;
    float w = 0.0f;
    for (const Stroke& s : leaf_layer(in, p, ink_lines(), EdgeParams{}).drawing.strokes)
      if (s.cls == LineClass::Foliage &&
          std::all_of(s.points.begin(), s.points.end(), off_the_third))
        w = std::max(
            w, s.widths.empty() ? s.width : *std::max_element(s.widths.begin(), s.widths.end()));
    return w;
  };
  // A gap of 0.3: full width well under it, thinner near it, none well above it.
  const float full = widest(0.1f), near = widest(0.3f), none = widest(0.7f);
  EXPECT_GT(full, 0.0f);
  EXPECT_GT(near, 0.0f);
  EXPECT_LT(near, full);
  EXPECT_EQ(none, 0.0f);
}

TEST(LeafPrimitives, OutlinesFollowTheAlphaCutShapeNotTheCard) {
  // A 1 x 1 card whose texture keeps a disc of radius 0.3 around its centre, inside one cell of
  // the pieces' grid (so it is one piece).
  Scene scene;
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.roles = {Role::Foliage, Role::Foliage};
  m.cluster_ids = {2, 2};
  m.primitive_ids = {1, 1};
  m.material = 0;
  scene.meshes.push_back(m);
  Texture t;
  t.width = t.height = 64;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool in = std::hypot((x + 0.5) / 64.0 - 0.5, (y + 0.5) / 64.0 - 0.5) < 0.3;
      t.rgba.insert(t.rgba.end(), {255, 255, 255, uint8_t(in ? 255 : 0)});
    }
  scene.textures.push_back(t);
  Material mat;
  mat.alpha_mode = AlphaMode::Mask;
  mat.base_color_texture = 0;
  scene.materials.push_back(mat);
  auto radius_of = [&](AlphaMode mode) {
    scene.materials[0].alpha_mode = mode;
    const SurfaceSamples s = sample_surfaces(scene, 0.01f);
    LeafImages in = images_of(make_leaf_pieces(s, 0, 10.0f).pieces);
    LeafParams p = plain();
    p.shape = LeafShape::Auto;
    const std::vector<glm::vec2> pts =
        points_of(leaf_layer(in, p, ink_lines(), EdgeParams{}).drawing, LineClass::Silhouette);
    double sum = 0.0;
    const cv::Point2f c = to_px({0.5f, 0.5f, 0.0f});
    for (const glm::vec2& q : pts)
      sum += std::hypot(q.x - c.x, q.y - c.y);
    return pts.empty() ? 0.0 : sum / double(pts.size()) / (kSize / 4.0);  // scene units
  };
  // The cut card is outlined as the disc it shows; the opaque card as the square's (a uniform
  // square of side 1 has the variance of a disc of radius 1/sqrt(3) = 0.577).
  EXPECT_NEAR(radius_of(AlphaMode::Mask), 0.3, 0.03);
  EXPECT_NEAR(radius_of(AlphaMode::Opaque), 0.577, 0.04);
}

// Spearman's rank correlation of two samples.
double spearman(const std::vector<double>& a, const std::vector<double>& b) {
  auto ranks = [](const std::vector<double>& v) {
    std::vector<size_t> order(v.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](size_t i, size_t j) { return v[i] < v[j]; });
    std::vector<double> r(v.size());
    for (size_t k = 0; k < order.size(); ++k)
      r[order[k]] = double(k);
    return r;
  };
  const std::vector<double> ra = ranks(a), rb = ranks(b);
  const double n = double(a.size()), mean = (n - 1.0) / 2.0;
  double num = 0, da = 0, db = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    num += (ra[i] - mean) * (rb[i] - mean);
    da += (ra[i] - mean) * (ra[i] - mean);
    db += (rb[i] - mean) * (rb[i] - mean);
  }
  return num / std::sqrt(da * db);
}

TEST(LeafPrimitives, TheToneZonesFollowTheLightOnASphereOfLeaves) {
  // Small leaves on the front of a unit sphere, and its shading by a light from +x: the colour
  // the ink style's raster pass would give (N.L with an ambient floor).
  std::vector<LeafPiece> pieces;
  const glm::vec3 light = glm::normalize(glm::vec3(1, 0.3f, 0.5f));
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const glm::vec3 p((i + 0.5f) / 20.0f - 1.0f, (j + 0.5f) / 20.0f - 1.0f, 0.0f);
      const float z2 = 1.0f - p.x * p.x - p.y * p.y;
      if (z2 <= 0.0f) continue;
      pieces.push_back(disc_piece({p.x, p.y, std::sqrt(z2)}, 0.03f, uint32_t(1 + i / 10)));
    }
  cv::Mat color(kSize, kSize, CV_8UC4, cv::Scalar(255, 255, 255, 0));
  cv::Mat lit(kSize, kSize, CV_32FC1, cv::Scalar(-1));
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float px = (x + 0.5f) / kSize * 4.0f - 2.0f, py = 2.0f - (y + 0.5f) / kSize * 4.0f;
      const float z2 = 1.0f - px * px - py * py;
      if (z2 <= 0.0f) continue;
      const float nl = std::max(0.0f, glm::dot(glm::vec3(px, py, std::sqrt(z2)), light));
      const uint8_t v = uint8_t(40 + 200 * nl);
      color.at<cv::Vec4b>(y, x) = {v, v, v, 255};
      lit.at<float>(y, x) = nl;
    }
  LeafParams p;
  p.shadow = 0.0f;  // no samples for the shadow map: the shading alone
  const LeafLayer layer = leaf_layer(images_of(pieces, color), p, ink_lines(), EdgeParams{});
  ASSERT_TRUE(finite(layer.drawing));
  // The rank (darkness among the plant's) falls as the light grows, monotone.
  std::vector<double> rank, light_here;
  for (int y = 0; y < layer.rank.rows; ++y)
    for (int x = 0; x < layer.rank.cols; ++x) {
      const int ox = int((x + 0.5) * layer.factor), oy = int((y + 0.5) * layer.factor);
      if (layer.front.at<int>(y, x) <= 0 || lit.at<float>(oy, ox) < 0.0f) continue;
      rank.push_back(layer.rank.at<float>(y, x));
      light_here.push_back(-lit.at<float>(oy, ox));
    }
  ASSERT_GT(rank.size(), 1000u);
  EXPECT_GT(spearman(rank, light_here), 0.95);
  // The black fills lie where the light is weakest; the lit side has none.
  cv::Mat fills = rasterize_strokes([&] {
    StrokeDrawing d = layer.drawing;
    std::erase_if(d.strokes, [](const Stroke& s) { return s.cls != LineClass::Shadow; });
    return d;
  }());
  double dark = 0, bright = 0, total = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float f = fills.at<float>(y, x), l = lit.at<float>(y, x);
      if (f < 0.5f || l < 0.0f) continue;
      total += 1;
      dark += l < 0.25f;
      bright += l > 0.6f;
    }
  ASSERT_GT(total, 200.0);
  EXPECT_GT(dark / total, 0.8);
  EXPECT_EQ(bright, 0.0);
}

TEST(LeafPrimitives, SameInputSameStrokes) {
  const LeafImages in = images_of(two_discs());
  LeafParams p = plain();
  p.depth_step = 0.2f;
  const StrokeDrawing a = leaf_layer(in, p, ink_lines(), EdgeParams{}).drawing;
  const StrokeDrawing b = leaf_layer(in, p, ink_lines(), EdgeParams{}).drawing;
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (size_t i = 0; i < a.strokes.size(); ++i) {
    ASSERT_EQ(a.strokes[i].points.size(), b.strokes[i].points.size());
    for (size_t k = 0; k < a.strokes[i].points.size(); ++k)
      EXPECT_EQ(a.strokes[i].points[k], b.strokes[i].points[k]);
  }
}

}  // namespace
}  // namespace sylva::test

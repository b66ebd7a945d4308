// The foliage's pieces (npr/leaf_pieces.h): one per element (a leaf) when it fits in a cell, an
// element larger than a cell cut into one piece per cell it crosses (each marked cut), the
// areas kept, the wood and cluster 0 left out, the centre and covariance those of the element's
// samples, and the leaves' size the area-weighted median of the elements' extents; the key light
// reaching a point through the samples (npr/sample_shadow.h) falls with depth behind the first
// surface and is 1 in front of it.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "npr/leaf_pieces.h"
#include "npr/sample_shadow.h"

namespace sylva::test {
namespace {

// `n` samples spread evenly along x over [x0, x0 + length) at y = z = 0, of element `primitive`.
void add_line(SurfaceSamples& s, float x0, float length, int n, uint32_t primitive,
              uint32_t cluster) {
  for (int i = 0; i < n; ++i) {
    s.positions.push_back({x0 + length * (float(i) + 0.5f) / float(n), 0.0f, 0.0f});
    s.normals.push_back({0, 0, 1});
    s.areas.push_back(0.01f);
    s.clusters.push_back(cluster);
    s.primitives.push_back(primitive);
  }
  s.spacing = 0.01f;
}

double total_area(const LeafPieces& p) {
  return std::accumulate(p.pieces.begin(), p.pieces.end(), 0.0,
                         [](double a, const LeafPiece& q) { return a + q.area; });
}

TEST(LeafPieces, SmallElementsAreOnePieceAndLargeOnesAreCutByCell) {
  SurfaceSamples s;
  add_line(s, 0.1f, 0.2f, 20, 1, 4);   // a small leaf inside one cell
  add_line(s, 2.0f, 3.0f, 300, 2, 4);  // a frond crossing three cells
  add_line(s, 0.1f, 0.2f, 20, 3, 9);   // wood
  add_line(s, 0.1f, 0.2f, 20, 4, 0);   // not a plant part
  const LeafPieces p = make_leaf_pieces(s, 9, 1.0f);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_FALSE(p.pieces[0].cut);
  EXPECT_NEAR(p.pieces[0].centre.x, 0.2f, 1e-5f);
  // A uniform segment of length L has variance L^2 / 12 along it, none across.
  EXPECT_NEAR(p.pieces[0].cov[0], 0.04f / 12.0f, 1e-4f);
  EXPECT_NEAR(p.pieces[0].cov[3], 0.0f, 1e-7f);
  for (size_t i = 1; i < 4; ++i) {
    EXPECT_TRUE(p.pieces[i].cut);
    EXPECT_EQ(p.pieces[i].cluster, 4u);
    EXPECT_NEAR(p.pieces[i].centre.x, float(i) + 1.5f, 0.01f);
  }
  EXPECT_NEAR(total_area(p), 3.2, 1e-4);  // 320 samples of 0.01 (no wood, no cluster 0)
}

TEST(LeafPieces, TheSameSamplesGiveTheSamePieces) {
  SurfaceSamples s;
  add_line(s, -1.3f, 4.0f, 500, 7, 2);
  add_line(s, 0.0f, 0.5f, 50, 8, 3);
  const LeafPieces a = make_leaf_pieces(s, 0, 0.7f), b = make_leaf_pieces(s, 0, 0.7f);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.pieces[i].centre, b.pieces[i].centre);
    EXPECT_EQ(a.pieces[i].area, b.pieces[i].area);
  }
}

TEST(LeafPieces, TheLeavesSizeIsTheAreaWeightedMedianOfTheElementsExtents) {
  SurfaceSamples s;
  add_line(s, 0.0f, 1.0f, 100, 1, 4);   // extent 0.99, area 1
  add_line(s, 3.0f, 2.0f, 100, 2, 4);   // extent 1.98, area 1
  add_line(s, 6.0f, 0.5f, 250, 3, 4);   // extent 0.498, area 2.5: the median by area
  add_line(s, 9.0f, 40.0f, 400, 4, 9);  // wood: not a leaf
  add_line(s, 0.0f, 40.0f, 400, 5, 0);  // not a plant part
  const LeafPieces p = make_leaf_pieces(s, 9, 1.0f);
  EXPECT_NEAR(p.leaf_extent, 0.5f * 249.0f / 250.0f, 1e-4f);
  EXPECT_NEAR(leaf_share(p), p.leaf_extent * kPieceCells, 1e-6f);
  // Samples that name no elements: the size is unknown.
  s.primitives.clear();
  EXPECT_EQ(make_leaf_pieces(s, 9, 1.0f).leaf_extent, 0.0f);
  EXPECT_EQ(leaf_share(LeafPieces{}), 0.0f);
}

TEST(SampleShadow, TheLightFallsWithDepthBehindTheFirstSurface) {
  // A sheet of samples in the plane z = 0, the light straight above (+z).
  SurfaceSamples s;
  for (int i = 0; i < 200; ++i)
    for (int j = 0; j < 200; ++j) {
      s.positions.push_back({(i + 0.5f) / 100.0f - 1.0f, (j + 0.5f) / 100.0f - 1.0f, 0.0f});
      s.normals.push_back({0, 0, 1});
      s.areas.push_back(1e-4f);
      s.clusters.push_back(1);
    }
  Sphere sphere;
  sphere.radius = 1.5f;
  const SampleShadow map = sample_shadow_map(s, sphere, {0, 0, 1}, false, 128, 0.2f);
  ASSERT_FALSE(map.empty());
  EXPECT_FLOAT_EQ(light_reaching(map, {0, 0, 0.5f}), 1.0f);  // in front of the sheet
  EXPECT_GT(light_reaching(map, {0, 0, 0.0f}), 0.99f);       // on it
  float last = 1.0f;
  for (float z : {-0.1f, -0.2f, -0.4f, -0.8f}) {
    const float here = light_reaching(map, {0.1f, 0.2f, z});
    EXPECT_LT(here, last) << z;
    EXPECT_GT(here, 0.0f);
    last = here;
  }
  // Out past the sheet's side, nothing stands between the point and the light.
  EXPECT_FLOAT_EQ(light_reaching(map, {1.4f, 0, -0.5f}), 1.0f);
}

}  // namespace
}  // namespace sylva::test

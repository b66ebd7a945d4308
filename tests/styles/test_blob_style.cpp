// The blobs style on a real plant: the rasteriser's one-cluster filter, outlines of visible
// leaves against clusters rasterised alone (Dudley §4.2.1), and the style through the render
// graph with the trunk as its base layer.
#include <gtest/gtest.h>

#include <set>

#include "npr/leaf_clusters.h"
#include "styles/blob_raster.h"
#include "styles/sheet.h"
#include "styles/style.h"
#include "tests/styles/style_rig.h"

namespace sylva {
namespace {

using test::StyleRig;

// Six leaf clusters (k-means; the bush has no hierarchy), uploaded again.
void six_clusters(StyleRig& s) {
  ClusterOptions co;
  co.clusters = 6;
  assign_clusters(s.scene, co);
  s.raster->upload(s.scene);
}

RasterRequest id_request(uint32_t only = 0) {
  RasterRequest r;
  r.targets = Target::Id | Target::Depth;
  r.id_kind = IdKind::Cluster;
  r.only_cluster = only;
  return r;
}

TEST(BlobStyle, RasteriserDrawsOneClusterWithItsHiddenLeaves) {
  StyleRig s(96);
  six_clusters(s);
  const GBuffer all = s.raster->render(s.rs.camera, s.rs.lighting, id_request());
  std::map<int, int> visible;
  for (int y = 0; y < all.id.rows; ++y)
    for (int x = 0; x < all.id.cols; ++x)
      if (all.id.at<int32_t>(y, x)) ++visible[all.id.at<int32_t>(y, x)];
  ASSERT_GE(visible.size(), 4u);
  bool some_hidden = false;
  for (const auto& [c, n] : visible) {
    const GBuffer one = s.raster->render(s.rs.camera, s.rs.lighting, id_request(uint32_t(c)));
    int own = 0, other = 0;
    for (int y = 0; y < one.id.rows; ++y)
      for (int x = 0; x < one.id.cols; ++x) {
        const int32_t v = one.id.at<int32_t>(y, x);
        own += v == c;
        other += v != 0 && v != c;
      }
    EXPECT_EQ(other, 0) << "cluster " << c;
    EXPECT_GE(own, n) << "cluster " << c;  // alone it shows at least its visible pixels
    some_hidden = some_hidden || own > n;
  }
  EXPECT_TRUE(some_hidden);  // a crown hides some of its clusters' leaves
}

TEST(BlobStyle, AloneOutlinesCoverHiddenLeaves) {
  StyleRig s(96);
  six_clusters(s);
  const uint32_t branch = s.scene.branch_cluster_id();
  ASSERT_NE(branch, 0u);
  BlobParams p;
  const auto visible =
      rasterised_blob_outlines(*s.raster, s.rs.camera, s.rs.lighting, {}, p, branch);
  p.outlines = BlobOutlineSource::Alone;
  const auto alone = rasterised_blob_outlines(*s.raster, s.rs.camera, s.rs.lighting, {}, p, branch);
  ASSERT_EQ(alone.size(), visible.size());
  for (size_t i = 0; i < alone.size(); ++i) {
    EXPECT_EQ(alone[i].cluster, visible[i].cluster);
    EXPECT_NE(alone[i].cluster, branch);
    EXPECT_LE(alone[i].min_depth, visible[i].min_depth);
    EXPECT_GE(alone[i].pixels, visible[i].pixels);
  }
}

TEST(BlobStyle, RendersThroughTheGraphOverTheTrunk) {
  StyleRig s(96);
  six_clusters(s);
  SheetScene sheet;
  sheet.raster = s.rs;
  sheet.scene_sphere = s.scene.framing_sphere();
  sheet.branch_cluster = s.scene.branch_cluster_id();
  sheet.foliage = [&](const FoliageSettings&) {  // declared, never read: blobs keeps the normals
    IlluminationSetup is;
    is.scene = &s.scene;
    return is;
  };
  const Style visible("blobs"), alone("blobs", {"blobs.outlines=alone"});
  RenderGraph graph;
  const SheetPlan plan = add_sheet_passes(graph, {&visible, &alone}, sheet);
  EXPECT_TRUE(graph.pass_live("cell-0/blobs"));
  EXPECT_TRUE(graph.pass_live("cell-1/blob-outlines"));
  graph.execute();
  const cv::Mat& a = graph.get<cv::Mat>(plan.outputs[0]);
  const cv::Mat& b = graph.get<cv::Mat>(plan.outputs[1]);
  ASSERT_EQ(a.type(), CV_8UC4);
  EXPECT_GT(cv::norm(a, b, cv::NORM_INF), 0.0);  // other outlines
  // Painted pixels: most of the plant; the background stays the background colour.
  int painted = 0;
  for (int y = 0; y < a.rows; ++y)
    for (int x = 0; x < a.cols; ++x)
      painted += a.at<cv::Vec4b>(y, x) != cv::Vec4b(255, 255, 255, 0);
  EXPECT_GT(painted, a.rows * a.cols / 20);
}

}  // namespace
}  // namespace sylva

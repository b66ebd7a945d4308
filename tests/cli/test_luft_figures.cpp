// Luft, Balzer & Deussen 2007, Fig. 7 as a test: a simple normal-discontinuity edge filter on
// the normal buffer finds leaf noise inside the crown with the model's normals, far fewer
// edges with realigned normals, and fewer still with realigned normals scaled by ka (the
// renderer's "realigned-scaled" normal target).
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "tests/test_support.h"

namespace sylva::test {
namespace {

struct EdgeCount {
  int edges = 0, interior = 0;
};

// Interior foliage pixels: the pixel and its four neighbours show leaves (object id `leaves`),
// so silhouettes and branch outlines do not count. Such a pixel is an edge when
// |N_p - N_q| > 0.4 (~23 deg between unit normals) for its right or lower neighbour.
EdgeCount crown_edges(const cv::Mat& n, const cv::Mat& id, float leaves) {
  EdgeCount c;
  auto covered = [&](int y, int x) { return id.at<float>(y, x) == leaves; };
  for (int y = 1; y + 1 < n.rows; ++y)
    for (int x = 1; x + 1 < n.cols; ++x) {
      if (!covered(y, x) || !covered(y - 1, x) || !covered(y + 1, x) || !covered(y, x - 1) ||
          !covered(y, x + 1))
        continue;
      ++c.interior;
      const cv::Vec3f p = n.at<cv::Vec3f>(y, x);
      if (cv::norm(p - n.at<cv::Vec3f>(y, x + 1)) > 0.4 ||
          cv::norm(p - n.at<cv::Vec3f>(y + 1, x)) > 0.4)
        ++c.edges;
    }
  return c;
}

TEST(LuftFigure7, RealignedNormalsRemoveLeafNoiseFromEdges) {
  const std::string dir = temp_dir("fig7");
  const std::string scene = dir + "/tree.glb";
  ASSERT_EQ(run_sylva("sample tree --leaves 4000 --seed 7 -o " + scene).status, 0);
  std::vector<EdgeCount> counts;
  for (const char* mode : {"original", "realigned", "realigned-scaled"}) {
    const std::string out = dir + "/" + mode;
    RunResult r = run_sylva("buffers " + scene + " --size 384 --buffers normal,id --id object " +
                            "--normals " + mode + " --out-dir " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    const cv::Mat n = cv::imread(out + "/normal.tiff", cv::IMREAD_UNCHANGED);
    const cv::Mat id = cv::imread(out + "/id.tiff", cv::IMREAD_UNCHANGED);
    ASSERT_EQ(n.type(), CV_32FC3);
    ASSERT_EQ(id.type(), CV_32FC1);
    // The sample writes the leaves as the first mesh: object id 1 (the bark is 2).
    counts.push_back(crown_edges(n, id, 1.0f));
  }
  for (size_t i = 0; i < counts.size(); ++i)
    std::printf("Fig. 7 %s: %d edge pixels of %d interior crown pixels (%.1f%%)\n",
                i == 0   ? "original"
                : i == 1 ? "realigned"
                         : "realigned-scaled",
                counts[i].edges, counts[i].interior,
                100.0 * counts[i].edges / std::max(counts[i].interior, 1));
  std::printf("ratios: realigned/original %.3f, realigned-scaled/original %.3f\n",
              double(counts[1].edges) / counts[0].edges, double(counts[2].edges) / counts[0].edges);
  ASSERT_GT(counts[0].interior, 5000);
  // The same geometry is drawn each time.
  EXPECT_EQ(counts[0].interior, counts[1].interior);
  EXPECT_EQ(counts[0].interior, counts[2].interior);
  EXPECT_LT(counts[1].edges * 2, counts[0].edges);  // measured 0.44 of the original
  EXPECT_LT(counts[2].edges, counts[1].edges);
}

}  // namespace
}  // namespace sylva::test

// passes/watercolor_masses.h: leaf clusters gathered into masses in world space.
#include <gtest/gtest.h>

#include "passes/watercolor_masses.h"

namespace sylva::test {
namespace {

// Clusters as little squares of samples around `centre`, `n` samples of area `area` each.
void add_cluster(SurfaceSamples& s, uint32_t id, glm::vec3 centre, int n, float area) {
  for (int i = 0; i < n; ++i) {
    s.positions.push_back(centre + glm::vec3(0.01f * float(i % 3), 0.01f * float(i / 3), 0));
    s.normals.emplace_back(0, 0, 1);
    s.areas.push_back(area);
    s.clusters.push_back(id);
    s.primitives.push_back(id);
  }
}

TEST(WatercolorMasses, NearClustersJoinTheLargestNearFounder) {
  SurfaceSamples s;
  add_cluster(s, 5, {0, 0, 0}, 9, 1.0f);        // the largest: founds a mass
  add_cluster(s, 6, {0.4f, 0, 0}, 3, 1.0f);     // within 0.5 of 5
  add_cluster(s, 7, {2, 0, 0}, 6, 1.0f);        // far: founds another
  add_cluster(s, 8, {1.7f, 0, 0}, 2, 1.0f);     // within 0.5 of 7
  add_cluster(s, 9, {1, 5, 0}, 1, 1.0f);        // alone
  add_cluster(s, 3, {0.1f, 0.1f, 0}, 4, 1.0f);  // the wood: never in a mass
  const auto m = crown_masses(s, 3, 0.5);
  EXPECT_EQ(m.at(5), 5u);
  EXPECT_EQ(m.at(6), 5u);
  EXPECT_EQ(m.at(7), 7u);
  EXPECT_EQ(m.at(8), 7u);
  EXPECT_EQ(m.at(9), 9u);
  EXPECT_EQ(m.count(3), 0u);
  EXPECT_EQ(m.count(0), 0u);
}

TEST(WatercolorMasses, ARadiusOfZeroOrManyPlantsKeepEveryCluster) {
  SurfaceSamples s;
  add_cluster(s, 1, {0, 0, 0}, 4, 1.0f);
  add_cluster(s, 2, {0.1f, 0, 0}, 4, 1.0f);
  EXPECT_EQ(crown_masses(s, 0, 1.0).at(2), 1u);
  EXPECT_TRUE(crown_masses(s, 0, 0.0).empty());
  EXPECT_TRUE(crown_masses(s, 0, -1.0).empty());
  s.instances.assign(s.size(), 1u);
  EXPECT_TRUE(crown_masses(s, 0, 1.0).empty());
}

TEST(WatercolorMasses, IdsAndSamplesCarryTheMass) {
  SurfaceSamples s;
  add_cluster(s, 4, {0, 0, 0}, 5, 1.0f);
  add_cluster(s, 9, {0.2f, 0, 0}, 2, 1.0f);
  const auto m = crown_masses(s, 0, 1.0);
  cv::Mat id(2, 3, CV_32SC1, cv::Scalar(0));
  id.at<int>(0, 1) = 9;
  id.at<int>(1, 2) = 4;
  id.at<int>(1, 0) = 12;  // a cluster the samples do not know stays
  const cv::Mat out = mass_ids(id, m);
  EXPECT_EQ(out.at<int>(0, 1), 4);
  EXPECT_EQ(out.at<int>(1, 2), 4);
  EXPECT_EQ(out.at<int>(1, 0), 12);
  EXPECT_EQ(out.at<int>(0, 0), 0);
  const auto ms = mass_samples(s, m);
  for (uint32_t c : ms->clusters)
    EXPECT_EQ(c, 4u);
  EXPECT_EQ(ms->positions, s.positions);
}

}  // namespace
}  // namespace sylva::test

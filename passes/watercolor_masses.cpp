#include "passes/watercolor_masses.h"

#include <algorithm>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

#include "core/error.h"

namespace sylva {

namespace {

struct ClusterCentre {
  uint32_t id = 0;
  double area = 0.0;
  glm::dvec3 sum{0.0};  // area-weighted positions
  glm::dvec3 centre() const { return sum / std::max(area, 1e-30); }
};

std::vector<ClusterCentre> cluster_centres(const SurfaceSamples& s, uint32_t wood_cluster) {
  std::unordered_map<uint32_t, size_t> index_of;
  std::vector<ClusterCentre> out;
  for (size_t i = 0; i < s.size(); ++i) {
    const uint32_t c = s.clusters[i];
    if (c == 0 || c == wood_cluster) continue;
    auto [it, fresh] = index_of.try_emplace(c, out.size());
    if (fresh) out.push_back({c, 0.0, glm::dvec3(0.0)});
    ClusterCentre& cc = out[it->second];
    cc.area += s.areas[i];
    cc.sum += double(s.areas[i]) * glm::dvec3(s.positions[i]);
  }
  std::sort(out.begin(), out.end(), [](const ClusterCentre& a, const ClusterCentre& b) {
    return a.area != b.area ? a.area > b.area : a.id < b.id;
  });
  return out;
}

}  // namespace

std::unordered_map<uint32_t, uint32_t> crown_masses(const SurfaceSamples& samples,
                                                    uint32_t wood_cluster, double radius) {
  std::unordered_map<uint32_t, uint32_t> mass_of;
  if (!(radius > 0.0) || !samples.instances.empty()) return mass_of;
  const std::vector<ClusterCentre> clusters = cluster_centres(samples, wood_cluster);
  std::vector<size_t> founders;
  std::vector<glm::dvec3> founder_at;
  // Founders first (in order of area), then every other cluster to its nearest founder.
  std::vector<bool> founded(clusters.size(), false);
  for (size_t i = 0; i < clusters.size(); ++i) {
    const glm::dvec3 c = clusters[i].centre();
    bool near = false;
    for (const glm::dvec3& f : founder_at)
      near = near || glm::distance(c, f) <= radius;
    if (near) continue;
    founded[i] = true;
    founders.push_back(i);
    founder_at.push_back(c);
  }
  for (size_t i = 0; i < clusters.size(); ++i) {
    size_t best = i;
    if (!founded[i]) {
      double nearest = std::numeric_limits<double>::infinity();
      for (size_t k = 0; k < founders.size(); ++k)
        if (const double d = glm::distance(clusters[i].centre(), founder_at[k]); d < nearest) {
          nearest = d;
          best = founders[k];
        }
    }
    mass_of[clusters[i].id] = clusters[best].id;
  }
  return mass_of;
}

cv::Mat mass_ids(const cv::Mat& id, const std::unordered_map<uint32_t, uint32_t>& mass_of) {
  SYLVA_CHECK(id.type() == CV_32SC1, "mass_ids: CV_32SC1 ids");
  cv::Mat out = id.clone();
  for (int y = 0; y < out.rows; ++y) {
    int32_t* row = out.ptr<int32_t>(y);
    for (int x = 0; x < out.cols; ++x) {
      if (row[x] == 0) continue;
      const auto it = mass_of.find(uint32_t(row[x]));
      if (it != mass_of.end()) row[x] = int32_t(it->second);
    }
  }
  return out;
}

std::shared_ptr<const SurfaceSamples> mass_samples(
    const SurfaceSamples& samples, const std::unordered_map<uint32_t, uint32_t>& mass_of) {
  auto out = std::make_shared<SurfaceSamples>(samples);
  for (uint32_t& c : out->clusters)
    if (const auto it = mass_of.find(c); it != mass_of.end()) c = it->second;
  return out;
}

bool large_leaved(const LeafPieces* pieces) {
  return pieces && leaf_share(*pieces) >= kLargeLeaf;
}

}  // namespace sylva

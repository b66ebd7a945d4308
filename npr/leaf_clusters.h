// Leaf clusters (groups of leaves for blob and watercolor layers). With a plant hierarchy
// (Dudley §3.2): a leaf belongs to the highest branch on its path to the root whose diameter
// is still below the division diameter; all leaves under one such branch form a cluster.
// Without one: k-means on leaf centroids (cv::kmeans, seeded, deterministic). Foliage gets
// cluster ids 1..K; all non-foliage triangles share cluster K + 1.
#pragma once

#include <cstdint>

#include "core/scene/scene.h"

namespace sylva {

struct ClusterOptions {
  int clusters = 0;             // k-means k; 0 = auto (about sqrt(leaves / 2), in [1, 64])
  uint64_t seed = 1;            // k-means seed
  float division_diameter = 0;  // scene units; 0 = auto (median branch diameter)
  bool use_hierarchy = true;    // false forces k-means even when a hierarchy is present
};

// Valid ranges: clusters in [0, 4096]; division_diameter >= 0. Throws InputError otherwise.
void assign_clusters(Scene& scene, const ClusterOptions& options);

}  // namespace sylva

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
  int clusters = 0;   // wanted cluster count; 0 = auto (about sqrt(leaves / 2), in [1, 64])
  uint64_t seed = 1;  // k-means seed
  float division_diameter = 0;  // scene units; 0 = auto (the hierarchy diameter giving a
                                // count closest to `clusters`)
  bool use_hierarchy = true;    // false forces k-means even when a hierarchy is present
};

// Valid ranges: clusters in [0, 4096]; division_diameter >= 0. Throws InputError otherwise.
// Needs roles and primitive ids (finish_scene). A hierarchy whose leaf count differs from the
// scene's foliage primitives is ignored with a report warning (k-means instead). k is clamped
// to the leaf count; clusters are renumbered by first appearance over leaves. Above 20,000
// leaves the k-means centres are fitted on an evenly strided sample and every leaf takes its
// nearest centre. Writes report.cluster_method.
void assign_clusters(Scene& scene, const ClusterOptions& options);

}  // namespace sylva

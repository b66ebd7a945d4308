// Washes at the picture's scale (issue "Watercolor that paints the tree as a painter would"):
// the leaf clusters gathered into a few masses, as Luft & Deussen abstract a crown into a few
// washes per layer, so the crown is painted as masses rather than as one patch per cluster.
// The grouping is done in world space on the clusters' area-weighted centres (from the scene's
// surface samples), so a mass keeps its clusters as the view turns: the largest cluster not yet
// in a mass founds one, and every cluster whose centre lies within `radius` of a founder's
// joins the nearest (founders in order of area, larger first; ties by id). The wood's cluster
// and the unclustered (0) stay as they are.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <unordered_map>

#include "npr/leaf_pieces.h"
#include "npr/surface_samples.h"

namespace sylva {

// cluster id -> the id of its mass's founder (a cluster id itself). radius: scene units; <= 0,
// or a scene of many plants (samples.instances set: the clusters' centres are not one plant's),
// gives an empty map (every cluster its own wash).
std::unordered_map<uint32_t, uint32_t> crown_masses(const SurfaceSamples& samples,
                                                    uint32_t wood_cluster, double radius);

// The id buffer (CV_32SC1) with each cluster replaced by its mass.
cv::Mat mass_ids(const cv::Mat& id, const std::unordered_map<uint32_t, uint32_t>& mass_of);

// The samples with each cluster replaced by its mass.
std::shared_ptr<const SurfaceSamples> mass_samples(
    const SurfaceSamples& samples, const std::unordered_map<uint32_t, uint32_t>& mass_of);

// A plant of large leaves (a fern's fronds) is painted leaf by leaf: when its elements' typical
// extent (LeafPieces::leaf_extent) is at least kLargeLeaf of the foliage's diagonal (a fern's
// fronds about 0.16, a tree's leaves and leaf cards under 0.05), a mass closes no gaps between
// its leaves and the crown's parts are smoothed kLargeLeafSmoothing as much, so each frond keeps
// its shape instead of melting into one patch per plant. A property of the scene, not the view:
// a turntable's frames all paint the same way.
inline constexpr float kLargeLeaf = 0.1f;
inline constexpr double kLargeLeafSmoothing = 0.25;

// Whether `pieces` (null = unknown: no) are a plant of large leaves.
bool large_leaved(const LeafPieces* pieces);

}  // namespace sylva

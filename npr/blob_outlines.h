// The blobs of one frame (Dudley 2005 §4.2.1, §4.3): every leaf cluster visible in a cluster-id
// buffer, shrink-wrapped (npr/shrink_wrap.h), with the minimum depth of its leaves that orders
// the painter's algorithm. One raster pass serves all clusters, so a cluster's outline follows
// its visible leaves (Dudley rasterises each cluster alone, hidden leaves included).
// Keyframe animation interpolates these between keyframes (npr/blob_keyframes.h).
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "npr/shrink_wrap.h"

namespace sylva {

struct BlobOutline {
  uint32_t cluster = 0;  // cluster id (> 0)
  ShrinkWrap wrap;       // image pixels
  float min_depth = 0;   // nearest leaf's linear view depth, scene units
  int pixels = 0;        // visible leaf pixels of the cluster
  float opacity = 1;     // < 1 while the blob fades in or out between keyframes
};

// The blobs of a frame with their painter's order. Between keyframes whose orders differ the
// frame is a cross-fade (Dudley §5.1): (1 - fade) x the painting in `order` + fade x the
// painting in `next_order`, so a blob passing in front of another does not pop.
struct BlobSet {
  std::vector<BlobOutline> blobs;
  std::vector<size_t> order, next_order;  // indices into blobs, back to front
  float fade = 0;                         // [0, 1)
};

// Morphological closing of a CV_8UC1 mask by a disc of `radius` px (Euclidean, by two distance
// transforms, so the cost does not grow with the radius): gaps between leaves narrower than
// 2 radius fill in, so the shrink-wrap stops at the cluster's hull rather than reaching
// through the gaps. radius <= 0 returns the mask unchanged.
cv::Mat close_gaps(const cv::Mat& mask, float radius);

// One outline per distinct id in `id` (CV_32SC1, 0 = background) other than `exclude` (the
// trunk-and-branches cluster, 0 = none), in increasing cluster id; `depth` (CV_32FC1, same
// size) gives min_depth. Each cluster's mask is closed by `gap_radius` px before it is
// shrink-wrapped. Clusters with no visible pixel are absent.
std::vector<BlobOutline> find_blob_outlines(const cv::Mat& id, const cv::Mat& depth,
                                            uint32_t exclude, const ShrinkWrapParams& params,
                                            float gap_radius = 0);

// One blob from a cluster's pixels: `mask` (CV_8UC1, non-zero = the cluster) covering `box` of
// the image, closed by `gap_radius` px (the mask padded first, so gaps at its edge close too)
// and shrink-wrapped, in image px; min_depth = `depth`, pixels = the mask's count.
BlobOutline blob_outline(const cv::Mat& mask, const cv::Rect& box, uint32_t cluster, float depth,
                         const ShrinkWrapParams& params, float gap_radius);

// Painter's order (Dudley §4.3): indices of `blobs` from the farthest min_depth to the nearest;
// ties by cluster id, so the order is total and deterministic.
std::vector<size_t> painter_order(const std::vector<BlobOutline>& blobs);

// A single frame's set: painter's order, no cross-fade.
BlobSet still_blob_set(std::vector<BlobOutline> blobs);

}  // namespace sylva

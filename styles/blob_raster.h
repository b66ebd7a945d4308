// Blob outlines straight from the rasteriser, for the blobs style's per-cluster option and for
// keyframes (which are shrink-wrapped from their own frame's camera). blobs.outlines =
// "visible" shrink-wraps each cluster's visible leaves in one cluster-id raster pass;
// "alone" rasterises every cluster visible in that pass again on its own, hidden leaves
// included, as Dudley does (§4.2.1: "rendered with all other branches and leaves turned off"),
// at the cost of one more id-and-depth pass per cluster.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "core/gl/rasterizer.h"
#include "npr/blob_outlines.h"
#include "passes/blobs.h"

namespace sylva {

// `request` gives the size-independent settings kept (supersampling, background); targets and
// id kind are set here. `visible_ids` (CV_32SC1 cluster ids of the same camera, or empty)
// saves the first pass when the caller has it.
std::vector<BlobOutline> rasterised_blob_outlines(Rasterizer& rasterizer, const Camera& camera,
                                                  const Lighting& lighting, RasterRequest request,
                                                  const BlobParams& p, uint32_t branch_cluster,
                                                  cv::Mat visible_ids = {});

}  // namespace sylva

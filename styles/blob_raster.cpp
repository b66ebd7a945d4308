#include "styles/blob_raster.h"

#include <set>

namespace sylva {

std::vector<BlobOutline> rasterised_blob_outlines(Rasterizer& rasterizer, const Camera& camera,
                                                  const Lighting& lighting, RasterRequest request,
                                                  const BlobParams& p, uint32_t branch_cluster,
                                                  cv::Mat visible_ids) {
  request.targets = Target::Id | Target::Depth;
  request.id_kind = IdKind::Cluster;
  request.only_cluster = 0;
  const ShrinkWrapParams sw = blob_shrink_wrap(p);
  cv::Mat depth;
  if (visible_ids.empty() || p.outlines == BlobOutlineSource::Visible) {
    GBuffer g = rasterizer.render(camera, lighting, request);
    visible_ids = g.id;
    depth = g.depth;
  }
  const float gap = blob_gap_radius(p, visible_ids.size());
  if (p.outlines == BlobOutlineSource::Visible)
    return find_blob_outlines(visible_ids, depth, branch_cluster, sw, gap);
  std::set<uint32_t> clusters;
  for (int y = 0; y < visible_ids.rows; ++y) {
    const int32_t* row = visible_ids.ptr<int32_t>(y);
    for (int x = 0; x < visible_ids.cols; ++x)
      if (row[x] != 0 && static_cast<uint32_t>(row[x]) != branch_cluster)
        clusters.insert(static_cast<uint32_t>(row[x]));
  }
  std::vector<BlobOutline> out;
  for (uint32_t c : clusters) {
    request.only_cluster = c;
    const GBuffer g = rasterizer.render(camera, lighting, request);
    std::vector<BlobOutline> one = find_blob_outlines(g.id, g.depth, branch_cluster, sw, gap);
    for (BlobOutline& b : one)
      if (b.cluster == c) out.push_back(std::move(b));
  }
  return out;  // increasing cluster id, as find_blob_outlines
}

}  // namespace sylva

#include "npr/blob_outlines.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <opencv2/imgproc.hpp>

#include "core/error.h"

namespace sylva {

cv::Mat close_gaps(const cv::Mat& mask, float radius) {
  SYLVA_CHECK(mask.type() == CV_8UC1, "close_gaps: mask must be CV_8UC1");
  if (!(radius > 0.0f) || mask.empty()) return mask.clone();
  const int pad = static_cast<int>(std::ceil(radius)) + 1;
  cv::Mat padded;
  cv::copyMakeBorder(mask, padded, pad, pad, pad, pad, cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::Mat outside = padded == 0, dist, dilated;
  cv::distanceTransform(outside, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  dilated = dist <= radius;
  cv::distanceTransform(dilated, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::Mat closed = dist > radius;
  // Erosion sees the padding as outside; the image border itself is not an edge of the cluster.
  return closed(cv::Rect(pad, pad, mask.cols, mask.rows)) | mask;
}

std::vector<BlobOutline> find_blob_outlines(const cv::Mat& id, const cv::Mat& depth,
                                            uint32_t exclude, const ShrinkWrapParams& params,
                                            float gap_radius) {
  SYLVA_CHECK(id.type() == CV_32SC1 && depth.type() == CV_32FC1 && id.size() == depth.size(),
              "find_blob_outlines: id CV_32SC1 and depth CV_32FC1 of one size");
  struct Extent {
    int x0 = std::numeric_limits<int>::max(), y0 = std::numeric_limits<int>::max();
    int x1 = -1, y1 = -1, pixels = 0;
    float min_depth = std::numeric_limits<float>::max();
  };
  std::map<uint32_t, Extent> extents;
  uint32_t last_id = 0;
  Extent* last = nullptr;  // ids come in runs: skip the map lookup within one
  for (int y = 0; y < id.rows; ++y) {
    const int32_t* ids = id.ptr<int32_t>(y);
    const float* d = depth.ptr<float>(y);
    for (int x = 0; x < id.cols; ++x) {
      const auto c = static_cast<uint32_t>(ids[x]);
      if (c == 0 || c == exclude) continue;
      if (c != last_id || !last) {
        last = &extents[c];
        last_id = c;
      }
      Extent& e = *last;
      e.x0 = std::min(e.x0, x);
      e.x1 = std::max(e.x1, x);
      e.y0 = std::min(e.y0, y);
      e.y1 = std::max(e.y1, y);
      ++e.pixels;
      if (d[x] > 0.0f) e.min_depth = std::min(e.min_depth, d[x]);
    }
  }
  std::vector<BlobOutline> out;
  out.reserve(extents.size());
  for (const auto& [cluster, e] : extents) {
    // The box grows by the closing radius so gaps at its edge close like any other.
    const int grow = gap_radius > 0 ? static_cast<int>(std::ceil(gap_radius)) : 0;
    const cv::Rect box = (cv::Rect(e.x0 - grow, e.y0 - grow, e.x1 - e.x0 + 1 + 2 * grow,
                                   e.y1 - e.y0 + 1 + 2 * grow) &
                          cv::Rect(0, 0, id.cols, id.rows));
    cv::Mat mask;
    cv::compare(id(box), cv::Scalar(static_cast<double>(static_cast<int32_t>(cluster))), mask,
                cv::CMP_EQ);
    mask = close_gaps(mask, gap_radius);
    BlobOutline b;
    b.cluster = cluster;
    b.wrap = shrink_wrap(mask, params);
    const glm::vec2 offset(static_cast<float>(box.x), static_cast<float>(box.y));
    b.wrap.center += offset;
    for (glm::vec2& p : b.wrap.points)
      p += offset;
    b.min_depth = e.min_depth == std::numeric_limits<float>::max() ? 0.0f : e.min_depth;
    b.pixels = e.pixels;
    out.push_back(std::move(b));
  }
  return out;
}

BlobOutline blob_outline(const cv::Mat& mask, const cv::Rect& box, uint32_t cluster, float depth,
                         const ShrinkWrapParams& params, float gap_radius) {
  SYLVA_CHECK(mask.type() == CV_8UC1 && mask.size() == box.size(),
              "blob_outline: a CV_8UC1 mask of the box's size");
  const int grow = gap_radius > 0 ? static_cast<int>(std::ceil(gap_radius)) : 0;
  cv::Mat padded;
  cv::copyMakeBorder(mask, padded, grow, grow, grow, grow, cv::BORDER_CONSTANT, 0);
  BlobOutline b;
  b.cluster = cluster;
  b.wrap = shrink_wrap(close_gaps(padded, gap_radius), params);
  const glm::vec2 offset(static_cast<float>(box.x - grow), static_cast<float>(box.y - grow));
  b.wrap.center += offset;
  for (glm::vec2& p : b.wrap.points)
    p += offset;
  b.min_depth = depth;
  b.pixels = cv::countNonZero(mask);
  return b;
}

std::vector<size_t> painter_order(const std::vector<BlobOutline>& blobs) {
  std::vector<size_t> order(blobs.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (blobs[a].min_depth != blobs[b].min_depth) return blobs[a].min_depth > blobs[b].min_depth;
    return blobs[a].cluster < blobs[b].cluster;
  });
  return order;
}

BlobSet still_blob_set(std::vector<BlobOutline> blobs) {
  BlobSet s;
  s.blobs = std::move(blobs);
  s.order = painter_order(s.blobs);
  s.next_order = s.order;
  return s;
}

}  // namespace sylva

#include "passes/ink_abstraction.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/error.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

cv::Mat disc(double diameter) {
  const int k = std::max(1, static_cast<int>(std::lround(diameter)) | 1);
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k});
}

// The connected pieces (8-neighbours) of `parts` whose bounding box's diagonal is >= length.
cv::Mat long_pieces(const cv::Mat& parts, double length) {
  return pieces_where(parts, [length](const int* st) {
    return std::hypot(double(st[cv::CC_STAT_WIDTH]), double(st[cv::CC_STAT_HEIGHT])) >= length;
  });
}

// Sets the connected pieces of `mask` (8-neighbours) smaller than `area` px to `value` in
// `mask` and `field_value` in `field`; pieces touching the image's border are kept when
// `keep_border`.
void drop_small(cv::Mat& mask, cv::Mat& field, double area, bool keep_border, uint8_t value,
                float field_value) {
  const cv::Mat small = pieces_where(mask, [&](const int* st) {
    const int x = st[cv::CC_STAT_LEFT], y = st[cv::CC_STAT_TOP];
    const int w = st[cv::CC_STAT_WIDTH], h = st[cv::CC_STAT_HEIGHT];
    const bool border = x == 0 || y == 0 || x + w == mask.cols || y + h == mask.rows;
    return st[cv::CC_STAT_AREA] < area && !(keep_border && border);
  });
  mask.setTo(value, small);
  field.setTo(field_value, small);
}

float bilinear(const cv::Mat& m, float x, float y) {
  const float fx = x - 0.5f, fy = y - 0.5f;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const float ax = fx - float(x0), ay = fy - float(y0);
  auto at = [&m](int xx, int yy) {
    return m.at<float>(std::clamp(yy, 0, m.rows - 1), std::clamp(xx, 0, m.cols - 1));
  };
  return (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x0 + 1, y0)) +
         ay * ((1 - ax) * at(x0, y0 + 1) + ax * at(x0 + 1, y0 + 1));
}

}  // namespace

CrownField crown_field(const cv::Mat& coverage, double detail) {
  SYLVA_CHECK(coverage.type() == CV_32FC1, "crown_field: CV_32FC1 coverage");
  CrownField c;
  if (detail < 2.0) {
    c.field = coverage.clone();
    c.body = coverage >= kCrownLevel;
    return c;
  }
  // Constant borders: the frame's edge neither grows nor eats the plant.
  cv::GaussianBlur(coverage, c.field, {0, 0}, 0.5 * detail, 0, cv::BORDER_CONSTANT);
  // The frame's edge is not part of the crown: a plant the frame cuts gets a closed outline
  // along the edge, as the binary crown_shape's opening gives it.
  if (c.field.rows > 2 && c.field.cols > 2) {
    cv::Mat inner = c.field(cv::Rect(1, 1, c.field.cols - 2, c.field.rows - 2)).clone();
    c.field.setTo(0.0f);
    inner.copyTo(c.field(cv::Rect(1, 1, c.field.cols - 2, c.field.rows - 2)));
  }
  c.body = c.field >= kCrownLevel;
  cv::Mat holes = c.body == 0;
  drop_small(holes, c.field, 4.0 * detail * detail, true, 0, kCrownLevel + 0.05f);
  c.body = holes == 0;
  drop_small(c.body, c.field, 16.0 * detail * detail, false, 0, kCrownLevel - 0.05f);
  return c;
}

void snap_to_level(std::vector<cv::Point2f>& line, const cv::Mat& field, float level, float reach) {
  SYLVA_CHECK(field.type() == CV_32FC1, "snap_to_level: CV_32FC1 field");
  for (cv::Point2f& q : line) {
    cv::Point2f c = q;
    for (int step = 0; step < 4; ++step) {
      const float v = bilinear(field, c.x, c.y) - level;
      const float gx = 0.5f * (bilinear(field, c.x + 1, c.y) - bilinear(field, c.x - 1, c.y));
      const float gy = 0.5f * (bilinear(field, c.x, c.y + 1) - bilinear(field, c.x, c.y - 1));
      const float g2 = gx * gx + gy * gy;
      if (!(g2 > 1e-8f)) break;
      cv::Point2f move(-v * gx / g2, -v * gy / g2);
      const float length = std::hypot(move.x, move.y);
      if (length > 0.5f) move *= 0.5f / length;  // small steps: the field is only bilinear
      c += move;
    }
    if (std::hypot(c.x - q.x, c.y - q.y) <= reach) q = c;
  }
}

CrownShape crown_shape(const cv::Mat& plant, double detail) {
  SYLVA_CHECK(plant.type() == CV_8UC1, "crown_shape: CV_8UC1 coverage");
  CrownShape shape;
  shape.body = plant != 0;
  if (detail < 2.0) {
    shape.thin = cv::Mat(plant.size(), CV_8UC1, cv::Scalar(0));
    return shape;
  }
  const cv::Mat k = disc(detail);
  cv::Mat closed;
  // Constant borders: the frame's edge neither grows nor eats the plant.
  cv::morphologyEx(shape.body, closed, cv::MORPH_CLOSE, k, {-1, -1}, 1, cv::BORDER_CONSTANT, 0);
  cv::morphologyEx(closed, shape.body, cv::MORPH_OPEN, k, {-1, -1}, 1, cv::BORDER_CONSTANT, 0);
  shape.thin = long_pieces(closed & ~shape.body, 2.0 * detail);
  return shape;
}

cv::Mat thin_parts(const cv::Mat& plant, const cv::Mat& body, double detail) {
  SYLVA_CHECK(plant.type() == CV_8UC1 && body.type() == CV_8UC1 && plant.size() == body.size(),
              "thin_parts: CV_8UC1 masks of one size");
  if (detail < 2.0) return cv::Mat(plant.size(), CV_8UC1, cv::Scalar(0));
  cv::Mat near_body;
  cv::dilate(body, near_body, disc(detail));
  return long_pieces((plant != 0) & ~near_body, 2.0 * detail);
}

cv::Mat median_depth(const cv::Mat& depth, const cv::Mat& plant, double window, float& near,
                     float& far) {
  SYLVA_CHECK(depth.type() == CV_32FC1 && plant.type() == CV_8UC1 && depth.size() == plant.size(),
              "median_depth: CV_32FC1 depth and CV_8UC1 coverage of one size");
  near = far = 0.0f;
  double lo = 0, hi = 0;
  if (cv::countNonZero(plant) > 0) cv::minMaxLoc(depth, &lo, &hi, nullptr, nullptr, plant);
  near = static_cast<float>(lo);
  far = static_cast<float>(hi);
  const float scale = far > near ? 253.0f / (far - near) : 0.0f;
  cv::Mat q(depth.size(), CV_8UC1);
  for (int y = 0; y < depth.rows; ++y) {
    const float* z = depth.ptr<float>(y);
    const uint8_t* m = plant.ptr<uint8_t>(y);
    uint8_t* o = q.ptr<uint8_t>(y);
    for (int x = 0; x < depth.cols; ++x)
      o[x] = m[x] != 0
                 ? static_cast<uint8_t>(1.0f + std::clamp((z[x] - near) * scale, 0.0f, 253.0f))
                 : kNoDepth;
  }
  const int k = std::max(3, static_cast<int>(std::lround(window)) | 1);
  cv::Mat median;
  cv::medianBlur(q, median, k);
  return median;
}

namespace {

// Where every non-zero label within `radius` px is the pixel's own (the window's largest label
// and its smallest non-zero one are both the pixel's), so the majority is its own; two
// separable morphology passes instead of a count over the window. Labels as floats: exact
// below 2^24, which the caller checks.
cv::Mat own_windows(const cv::Mat& labels, int radius) {
  cv::Mat f, nonzero, hi, lo;
  labels.convertTo(f, CV_32F);
  nonzero = f.clone();
  nonzero.setTo(std::numeric_limits<float>::max(), labels == 0);
  const cv::Mat k = cv::getStructuringElement(cv::MORPH_RECT, {2 * radius + 1, 2 * radius + 1});
  cv::dilate(f, hi, k);  // the default border value leaves the outside out
  cv::erode(nonzero, lo, k);
  return (hi == f) & (lo == f);
}

// The label most common in the (2 radius + 1)² window at (x, y) of a labelled pixel, its own
// where it ties for the most, else the smallest of those tied (0 is no label). `counts` is
// scratch.
int majority_at(const cv::Mat& labels, int x, int y, int radius,
                std::vector<std::pair<int, int>>& counts) {
  const int own = labels.at<int>(y, x);
  counts.clear();
  for (int v = std::max(0, y - radius); v <= std::min(labels.rows - 1, y + radius); ++v)
    for (int u = std::max(0, x - radius); u <= std::min(labels.cols - 1, x + radius); ++u) {
      const int l = labels.at<int>(v, u);
      if (l == 0) continue;
      auto it = std::find_if(counts.begin(), counts.end(),
                             [l](const std::pair<int, int>& c) { return c.first == l; });
      if (it == counts.end())
        counts.emplace_back(l, 1);
      else
        ++it->second;
    }
  int best = own, most = 0;
  for (const auto& [l, n] : counts)
    if (n > most || (n == most && l != best && best != own && l < best)) {
      best = l;
      most = n;
    } else if (n == most && l == own) {
      best = own;
    }
  return best;
}

}  // namespace

cv::Mat majority_labels(const cv::Mat& labels, int radius) {
  SYLVA_CHECK(labels.type() == CV_32SC1 && radius >= 0, "majority_labels: CV_32SC1 labels");
  cv::Mat out = labels.clone();
  double most_label = 0.0;
  cv::minMaxLoc(labels, nullptr, &most_label);
  const cv::Mat own_only = most_label < double(1 << 24) && labels.total() > 0
                               ? own_windows(labels, radius)
                               : cv::Mat(labels.size(), CV_8UC1, cv::Scalar(0));
  // Rows in parallel: each pixel reads the input labels only.
  for_bands(labels.rows, [&](int y0, int y1) {
    std::vector<std::pair<int, int>> counts;  // label, count
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < labels.cols; ++x) {
        const int own = labels.at<int>(y, x);
        if (own == 0 || own_only.at<uint8_t>(y, x)) continue;
        out.at<int>(y, x) = majority_at(labels, x, y, radius, counts);
      }
  });
  return out;
}

}  // namespace sylva

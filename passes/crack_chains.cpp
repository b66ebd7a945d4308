#include "passes/crack_chains.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/error.h"

namespace sylva {

Cracks::Cracks(cv::Size image)
    : x(image.height, std::max(0, image.width - 1), CV_8UC1, cv::Scalar(0)),
      y(std::max(0, image.height - 1), image.width, CV_8UC1, cv::Scalar(0)) {}

int Cracks::count() const {
  return (x.empty() ? 0 : cv::countNonZero(x)) + (y.empty() ? 0 : cv::countNonZero(y));
}

namespace {

// Directions from a corner: 0 = +x, 1 = +y, 2 = -x, 3 = -y.
constexpr int kStepX[4] = {1, 0, -1, 0};
constexpr int kStepY[4] = {0, 1, 0, -1};

// The cracks meeting at each corner of a W x H image ((H + 1) x (W + 1), CV_8UC1) from the
// 0/255 crack images: a crack of `x` at (row r, column c) joins corners (c + 1, r) and
// (c + 1, r + 1); one of `y` at (r, c) joins (c, r + 1) and (c + 1, r + 1).
cv::Mat corner_degrees(const cv::Mat& x, const cv::Mat& y, int w, int h) {
  cv::Mat degree(h + 1, w + 1, CV_8UC1, cv::Scalar(0));
  // Adds `ones` (1 per crack) to the corners offset by (dx, dy) from the cracks' cells.
  auto add_at = [&](const cv::Mat& ones, int dx, int dy) {
    cv::Mat corners = degree(cv::Rect(dx, dy, ones.cols, ones.rows));
    corners += ones;
  };
  if (!x.empty()) {
    const cv::Mat ones = cv::min(x, 1);
    add_at(ones, 1, 0);
    add_at(ones, 1, 1);
  }
  if (!y.empty()) {
    const cv::Mat ones = cv::min(y, 1);
    add_at(ones, 0, 1);
    add_at(ones, 1, 1);
  }
  return degree;
}

class CornerGraph {
 public:
  explicit CornerGraph(const Cracks& c) : m_w(c.image().width), m_h(c.image().height) {
    SYLVA_CHECK(c.x.type() == CV_8UC1 && c.y.type() == CV_8UC1, "chain_cracks: CV_8UC1 cracks");
    SYLVA_CHECK(c.x.rows == m_h && c.x.cols == std::max(0, m_w - 1) && c.y.cols == m_w &&
                    c.y.rows == std::max(0, m_h - 1),
                "chain_cracks: crack images of mismatched sizes");
    // A one-pixel-wide or -high image has no cracks one way (an empty image).
    m_free_x = c.x.empty() ? cv::Mat() : cv::Mat(c.x != 0);
    m_free_y = c.y.empty() ? cv::Mat() : cv::Mat(c.y != 0);
    m_degree = corner_degrees(m_free_x, m_free_y, m_w, m_h);
    m_left = m_degree.clone();
  }
  // The corners that touch a crack, row by row (y, then x).
  std::vector<cv::Point> corners() const {
    std::vector<cv::Point> out;
    out.reserve(size_t(cv::countNonZero(m_degree)));
    for (int y = 0; y < m_degree.rows; ++y) {
      const uint8_t* row = m_degree.ptr<uint8_t>(y);
      for (int x = 0; x < m_degree.cols; ++x)
        if (row[x] != 0) out.emplace_back(x, y);
    }
    return out;
  }
  int width() const { return m_w; }
  int height() const { return m_h; }

  // The crack leaving corner (cx, cy) in direction d: a cell of the free images, or null when
  // there is none there.
  uint8_t* crack(int cx, int cy, int d) {
    cv::Mat& x = m_free_x;
    cv::Mat& y = m_free_y;
    switch (d) {
      case 0:  // +x: between pixels (cx, cy - 1) and (cx, cy)
        return cy >= 1 && cy < m_h && cx >= 0 && cx < m_w ? y.ptr<uint8_t>(cy - 1) + cx : nullptr;
      case 2:
        return cy >= 1 && cy < m_h && cx >= 1 && cx <= m_w ? y.ptr<uint8_t>(cy - 1) + cx - 1
                                                           : nullptr;
      case 1:  // +y: between pixels (cx - 1, cy) and (cx, cy)
        return cx >= 1 && cx < m_w && cy >= 0 && cy < m_h ? x.ptr<uint8_t>(cy) + cx - 1 : nullptr;
      default:
        return cx >= 1 && cx < m_w && cy >= 1 && cy <= m_h ? x.ptr<uint8_t>(cy - 1) + cx - 1
                                                           : nullptr;
    }
  }
  bool free(int cx, int cy, int d) {
    const uint8_t* c = crack(cx, cy, d);
    return c != nullptr && *c != 0;
  }
  // The cracks meeting at corner (cx, cy), used or not.
  int degree(int cx, int cy) const { return m_degree.at<uint8_t>(cy, cx); }
  // The free cracks left at corner (cx, cy).
  int left(int cx, int cy) const { return m_left.at<uint8_t>(cy, cx); }
  void use(int cx, int cy, int d) {
    *crack(cx, cy, d) = 0;
    --m_left.at<uint8_t>(cy, cx);
    --m_left.at<uint8_t>(cy + kStepY[d], cx + kStepX[d]);
  }

  // Follows free cracks from corner (cx, cy) leaving in direction d (free).
  Polyline walk(int cx, int cy, int d) {
    Polyline p;
    const int x0 = cx, y0 = cy;
    p.points.emplace_back(float(cx), float(cy));
    for (;;) {
      use(cx, cy, d);
      cx += kStepX[d];
      cy += kStepY[d];
      if (cx == x0 && cy == y0) {
        p.closed = p.points.size() > 2;
        if (!p.closed) p.points.emplace_back(float(cx), float(cy));
        return p;
      }
      p.points.emplace_back(float(cx), float(cy));
      const int next = next_direction(cx, cy, d);
      if (next < 0) return p;
      d = next;
    }
  }

 private:
  // Where a chain that arrived at (cx, cy) moving in direction d goes on: the one other crack
  // of a two-crack corner, else straight on if that crack is free; -1 = the chain ends.
  int next_direction(int cx, int cy, int d) {
    if (degree(cx, cy) == 2) {
      for (int e = 0; e < 4; ++e)
        if (e != (d + 2) % 4 && free(cx, cy, e)) return e;
      return -1;
    }
    return free(cx, cy, d) ? d : -1;
  }

  int m_w, m_h;
  cv::Mat m_free_x, m_free_y;
  cv::Mat m_degree;  // CV_8UC1, (H + 1) x (W + 1): the cracks meeting at each corner
  cv::Mat m_left;    // the same, less those a chain has used
};

}  // namespace

std::vector<Polyline> chain_cracks(const Cracks& cracks) {
  CornerGraph g(cracks);
  std::vector<Polyline> out;
  auto walk_all_from = [&](int cx, int cy) {
    if (g.left(cx, cy) == 0) return;
    for (int d = 0; d < 4; ++d)
      if (g.free(cx, cy, d)) out.push_back(g.walk(cx, cy, d));
  };
  // Only corners that touch a crack can start a chain: they are visited in the order a scan of
  // every corner would visit them.
  const std::vector<cv::Point> corners = g.corners();
  for (int pass = 0; pass < 2; ++pass)  // ends first, then junctions
    for (const cv::Point& c : corners) {
      const int deg = g.degree(c.x, c.y);
      if (pass == 0 ? deg == 1 : deg >= 3) walk_all_from(c.x, c.y);
    }
  for (const cv::Point& c : corners)  // what is left are loops
    walk_all_from(c.x, c.y);
  return out;
}

double polyline_length(const Polyline& p) {
  double length = 0;
  for (size_t i = 1; i < p.points.size(); ++i)
    length += cv::norm(p.points[i] - p.points[i - 1]);
  if (p.closed && p.points.size() > 2) length += cv::norm(p.points.front() - p.points.back());
  return length;
}

Polyline smooth_polyline(const Polyline& p, double sigma) {
  const int n = static_cast<int>(p.points.size());
  if (sigma <= 0 || n < 3) return p;
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  std::vector<double> w(size_t(2 * radius + 1));
  for (int k = -radius; k <= radius; ++k)
    w[size_t(k + radius)] = std::exp(-0.5 * k * k / (sigma * sigma));
  auto at = [&](int j) -> cv::Point2d {
    if (p.closed) return p.points[size_t(((j % n) + n) % n)];
    // Reflected through the end point: p(-k) = 2 p(0) - p(k), bounded for short chains.
    if (j < 0)
      return 2.0 * cv::Point2d(p.points[0]) - cv::Point2d(p.points[size_t(std::min(n - 1, -j))]);
    if (j >= n)
      return 2.0 * cv::Point2d(p.points[size_t(n - 1)]) -
             cv::Point2d(p.points[size_t(std::max(0, 2 * (n - 1) - j))]);
    return p.points[size_t(j)];
  };
  double total = 0;
  for (double wk : w)
    total += wk;
  Polyline out;
  out.closed = p.closed;
  out.points.resize(size_t(n));
  for (int i = 0; i < n; ++i) {
    cv::Point2d sum(0, 0);
    if (i >= radius && i + radius < n) {  // inside: the points themselves
      for (int k = -radius; k <= radius; ++k)
        sum += w[size_t(k + radius)] * cv::Point2d(p.points[size_t(i + k)]);
    } else {
      for (int k = -radius; k <= radius; ++k)
        sum += w[size_t(k + radius)] * at(i + k);
    }
    out.points[size_t(i)] = cv::Point2f(sum / total);
  }
  if (!p.closed) {
    out.points.front() = p.points.front();
    out.points.back() = p.points.back();
  }
  return out;
}

Polyline simplify_polyline(const Polyline& p, double tolerance) {
  if (p.points.size() < 3 || tolerance <= 0) return p;
  Polyline out;
  out.closed = p.closed;
  cv::approxPolyDP(p.points, out.points, tolerance, p.closed);
  return out;
}

}  // namespace sylva

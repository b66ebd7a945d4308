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
    m_marked_x = m_free_x.clone();
    m_marked_y = m_free_y.clone();
  }
  int width() const { return m_w; }
  int height() const { return m_h; }

  // The crack leaving corner (cx, cy) in direction d: a cell of the free (or, with `marked`,
  // the original) images, or null when there is none there.
  uint8_t* crack(int cx, int cy, int d, bool marked = false) {
    cv::Mat& x = marked ? m_marked_x : m_free_x;
    cv::Mat& y = marked ? m_marked_y : m_free_y;
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
  int degree(int cx, int cy) {
    int n = 0;
    for (int d = 0; d < 4; ++d) {
      const uint8_t* c = crack(cx, cy, d, true);
      n += c != nullptr && *c != 0;
    }
    return n;
  }
  void use(int cx, int cy, int d) { *crack(cx, cy, d) = 0; }

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
  cv::Mat m_free_x, m_free_y, m_marked_x, m_marked_y;
};

// The corners at the ends of the cracks, row by row (y, then x), each once. A crack of
// `cracks.y` at (row r, column c) joins corners (c, r + 1) and (c + 1, r + 1); one of `cracks.x`
// at (r, c) joins (c + 1, r) and (c + 1, r + 1).
std::vector<cv::Point> cracked_corners(const Cracks& cracks) {
  const cv::Size image = cracks.image();
  cv::Mat touched(image.height + 1, image.width + 1, CV_8UC1, cv::Scalar(0));
  for (int r = 0; r < cracks.y.rows; ++r) {
    const uint8_t* c = cracks.y.ptr<uint8_t>(r);
    uint8_t* t = touched.ptr<uint8_t>(r + 1);
    for (int x = 0; x < cracks.y.cols; ++x)
      if (c[x]) t[x] = t[x + 1] = 1;
  }
  for (int r = 0; r < cracks.x.rows; ++r) {
    const uint8_t* c = cracks.x.ptr<uint8_t>(r);
    uint8_t* t0 = touched.ptr<uint8_t>(r);
    uint8_t* t1 = touched.ptr<uint8_t>(r + 1);
    for (int x = 0; x < cracks.x.cols; ++x)
      if (c[x]) t0[x + 1] = t1[x + 1] = 1;
  }
  std::vector<cv::Point> corners;
  cv::findNonZero(touched, corners);
  return corners;
}

}  // namespace

std::vector<Polyline> chain_cracks(const Cracks& cracks) {
  CornerGraph g(cracks);
  std::vector<Polyline> out;
  auto walk_all_from = [&](int cx, int cy) {
    for (int d = 0; d < 4; ++d)
      if (g.free(cx, cy, d)) out.push_back(g.walk(cx, cy, d));
  };
  // Only corners that touch a crack can start a chain: they are visited in the order a scan of
  // every corner would visit them.
  const std::vector<cv::Point> corners = cracked_corners(cracks);
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
  Polyline out;
  out.closed = p.closed;
  out.points.resize(size_t(n));
  for (int i = 0; i < n; ++i) {
    cv::Point2d sum(0, 0);
    double total = 0;
    for (int k = -radius; k <= radius; ++k) {
      sum += w[size_t(k + radius)] * at(i + k);
      total += w[size_t(k + radius)];
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

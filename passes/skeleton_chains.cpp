#include "passes/skeleton_chains.h"

#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "passes/thinning.h"

namespace sylva {

namespace {

// The skeleton of every connected piece, each thinned in its own bounding box.
cv::Mat thin_pieces(const cv::Mat& mask) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  cv::Mat skeleton(mask.size(), CV_8UC1, cv::Scalar(0));
  const cv::Rect frame(0, 0, mask.cols, mask.rows);
  for (int i = 1; i < n; ++i) {
    const cv::Rect box =
        cv::Rect(stats.at<int>(i, cv::CC_STAT_LEFT) - 1, stats.at<int>(i, cv::CC_STAT_TOP) - 1,
                 stats.at<int>(i, cv::CC_STAT_WIDTH) + 2,
                 stats.at<int>(i, cv::CC_STAT_HEIGHT) + 2) &
        frame;
    const cv::Mat piece = labels(box) == i;
    skeleton(box) |= thin_zhang_suen(piece);
  }
  return skeleton;
}

constexpr int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr int kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};

class SkeletonGraph {
 public:
  explicit SkeletonGraph(const cv::Mat& skeleton) : m_on(skeleton) {
    m_used = cv::Mat(skeleton.size(), CV_8UC1, cv::Scalar(0));
  }
  bool on(int x, int y) const {
    return x >= 0 && y >= 0 && x < m_on.cols && y < m_on.rows && m_on.at<uint8_t>(y, x) != 0;
  }
  // m-adjacency: a diagonal neighbour counts only when neither 4-neighbour between them is on,
  // so an L-shaped corner of the skeleton is a path, not a triangle.
  bool adjacent(int x, int y, int k) const {
    const int nx = x + kDx[k], ny = y + kDy[k];
    if (!on(nx, ny)) return false;
    return k % 2 == 0 || (!on(nx, y) && !on(x, ny));
  }
  int degree(int x, int y) const {
    int d = 0;
    for (int k = 0; k < 8; ++k)
      d += adjacent(x, y, k);
    return d;
  }
  bool used(int x, int y) const { return m_used.at<uint8_t>(y, x) != 0; }

  // From (x, y) (an end, a junction or, for a loop, any pixel) into neighbour k.
  Polyline walk(int x, int y, int k, bool& ends_free) {
    Polyline p;
    const int x0 = x, y0 = y;
    p.points.emplace_back(x + 0.5f, y + 0.5f);
    int px = x, py = y;
    x += kDx[k];
    y += kDy[k];
    for (;;) {
      p.points.emplace_back(x + 0.5f, y + 0.5f);
      const int d = degree(x, y);
      ends_free = d == 1;
      if (d != 2 || used(x, y)) break;
      m_used.at<uint8_t>(y, x) = 1;
      int next = -1;
      for (int j = 0; j < 8 && next < 0; ++j) {
        const int nx = x + kDx[j], ny = y + kDy[j];
        if (adjacent(x, y, j) && !(nx == px && ny == py)) next = j;
      }
      if (next < 0) break;
      px = x;
      py = y;
      x += kDx[next];
      y += kDy[next];
      if (x == x0 && y == y0) {
        p.closed = true;
        break;
      }
    }
    return p;
  }

 private:
  const cv::Mat& m_on;
  cv::Mat m_used;
};

}  // namespace

std::vector<Polyline> skeleton_chains(const cv::Mat& mask, double min_spur) {
  SYLVA_CHECK(mask.type() == CV_8UC1, "skeleton_chains: CV_8UC1 mask");
  const cv::Mat skeleton = thin_pieces(mask != 0);
  SkeletonGraph g(skeleton);
  std::vector<Polyline> out;
  auto start = [&](int x, int y, bool junction) {
    for (int k = 0; k < 8; ++k) {
      if (!g.adjacent(x, y, k)) continue;
      const int nx = x + kDx[k], ny = y + kDy[k];
      const int nd = g.degree(nx, ny);
      if (nd == 2 && g.used(nx, ny)) continue;
      if (nd != 2 && (ny < y || (ny == y && nx < x))) continue;  // node to node: once
      bool ends_free = false;
      Polyline p = g.walk(x, y, k, ends_free);
      const bool spur = junction && ends_free && polyline_length(p) < min_spur;
      if (!spur) out.push_back(std::move(p));
    }
  };
  for (int y = 0; y < skeleton.rows; ++y)
    for (int x = 0; x < skeleton.cols; ++x) {
      if (!g.on(x, y)) continue;
      const int d = g.degree(x, y);
      if (d == 0) out.push_back({{cv::Point2f(x + 0.5f, y + 0.5f)}, false});
      if (d == 1 || d >= 3) start(x, y, d >= 3);
    }
  for (int y = 0; y < skeleton.rows; ++y)  // loops
    for (int x = 0; x < skeleton.cols; ++x)
      if (g.on(x, y) && g.degree(x, y) == 2 && !g.used(x, y)) start(x, y, false);
  return out;
}

}  // namespace sylva

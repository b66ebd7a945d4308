#include "styles/reprojection.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/error.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

constexpr float kDepthTolerance = 0.01f;  // of the reprojected depth
constexpr float kLineReach = 1.5f;        // px

// Carries view-space points of one frame into another frame's image.
class Reprojector {
 public:
  Reprojector(const Camera& from, const CoherenceFrame& to)
      : m_to(to), m_view(to.camera.view * glm::inverse(from.view)) {}

  // Where the point `p` (view space of `from`) lies in `to`: continuous image coordinates (pixel
  // (i, j) centred at (i + 0.5, j + 0.5)), and whether `to` sees it there (its own surface at
  // that pixel within kDepthTolerance of the point's depth).
  bool place(const cv::Vec3f& p, glm::vec2& at) const {
    const glm::vec4 q = m_view * glm::vec4(p[0], p[1], p[2], 1.0f);
    const glm::vec4 clip = m_to.camera.proj * q;
    if (clip.w <= 0.0f || q.z >= 0.0f) return false;
    const float w = float(m_to.image.cols), h = float(m_to.image.rows);
    at = {(clip.x / clip.w * 0.5f + 0.5f) * w, (0.5f - clip.y / clip.w * 0.5f) * h};
    // A point that lands within a thousandth of a pixel centre is on it (a still camera).
    for (float* c : {&at.x, &at.y}) {
      const float centre = std::floor(*c) + 0.5f;
      if (std::abs(*c - centre) < 1e-3f) *c = centre;
    }
    const int x = int(std::floor(at.x)), y = int(std::floor(at.y));
    if (x < 0 || y < 0 || x >= m_to.image.cols || y >= m_to.image.rows) return false;
    const cv::Vec3f seen = m_to.position.at<cv::Vec3f>(y, x);
    if (seen[2] >= 0.0f) return false;  // background
    const float depth = -q.z;
    return std::abs(-seen[2] - depth) <= kDepthTolerance * depth;
  }

  // B, G, R of `to` at continuous coordinates (bilinear between pixel centres).
  cv::Vec3f colour(glm::vec2 at) const {
    const float fx = at.x - 0.5f, fy = at.y - 0.5f;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const float ax = fx - float(x0), ay = fy - float(y0);
    cv::Vec3f sum(0, 0, 0);
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const float wgt = (dx ? ax : 1.0f - ax) * (dy ? ay : 1.0f - ay);
        if (wgt == 0.0f) continue;
        const int x = std::clamp(x0 + dx, 0, m_to.image.cols - 1);
        const int y = std::clamp(y0 + dy, 0, m_to.image.rows - 1);
        const cv::Vec4b c = m_to.image.at<cv::Vec4b>(y, x);
        sum += wgt * cv::Vec3f(c[0], c[1], c[2]);
      }
    return sum;
  }

 private:
  const CoherenceFrame& m_to;
  glm::mat4 m_view;  // from's view space -> to's view space
};

bool on_plant(const CoherenceFrame& f, int x, int y) {
  return f.position.at<cv::Vec3f>(y, x)[2] < 0.0f;
}

// Mean |difference| of `current`'s plant pixels from `previous` where previous sees them; the
// count of those pixels. Rows are summed on their own and then in order, so the result does
// not depend on the number of threads.
double reprojection_error(const CoherenceFrame& previous, const CoherenceFrame& current,
                          size_t& pixels) {
  const Reprojector to_previous(current.camera, previous);
  const int h = current.image.rows;
  std::vector<double> sums(size_t(h), 0.0);
  std::vector<size_t> counts(size_t(h), 0);
  for_bands(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < current.image.cols; ++x) {
        if (!on_plant(current, x, y)) continue;
        glm::vec2 at;
        if (!to_previous.place(current.position.at<cv::Vec3f>(y, x), at)) continue;
        const cv::Vec3f then = to_previous.colour(at);
        const cv::Vec4b now = current.image.at<cv::Vec4b>(y, x);
        sums[size_t(y)] +=
            std::abs(now[0] - then[0]) + std::abs(now[1] - then[1]) + std::abs(now[2] - then[2]);
        ++counts[size_t(y)];
      }
  });
  double sum = 0.0;
  pixels = 0;
  for (int y = 0; y < h; ++y) {
    sum += sums[size_t(y)];
    pixels += counts[size_t(y)];
  }
  return pixels > 0 ? sum / (3.0 * double(pixels)) : 0.0;
}

// For every pixel of `f`, the plant pixel nearest to it (itself on the plant); (-1, -1) when the
// frame shows no plant.
cv::Mat nearest_plant(const CoherenceFrame& f) {
  cv::Mat off(f.position.size(), CV_8UC1), dist, labels;
  for (int y = 0; y < off.rows; ++y)
    for (int x = 0; x < off.cols; ++x)
      off.at<uint8_t>(y, x) = on_plant(f, x, y) ? 0 : 255;
  cv::Mat nearest(off.size(), CV_32SC2, cv::Scalar(-1, -1));
  if (cv::countNonZero(off) == int(off.total())) return nearest;
  cv::distanceTransform(off, dist, labels, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
  std::vector<cv::Vec2i> where(size_t(off.total()) + 1, cv::Vec2i(-1, -1));
  for (int y = 0; y < off.rows; ++y)
    for (int x = 0; x < off.cols; ++x)
      if (!off.at<uint8_t>(y, x)) where[size_t(labels.at<int>(y, x))] = cv::Vec2i(x, y);
  for (int y = 0; y < off.rows; ++y)
    for (int x = 0; x < off.cols; ++x)
      nearest.at<cv::Vec2i>(y, x) =
          off.at<uint8_t>(y, x) ? where[size_t(labels.at<int>(y, x))] : cv::Vec2i(x, y);
  return nearest;
}

// Share of `from`'s line pixels, seen by `to`, with no line of `to` within kLineReach px of
// their place there; `to_reach` is the distance to `to`'s nearest line pixel. A line pixel
// beside the plant moves as the plant pixel nearest to it does (and counts where `to` sees
// that one).
std::optional<double> popped(const CoherenceFrame& from, const CoherenceFrame& to,
                             const cv::Mat& to_reach) {
  const Reprojector into(from.camera, to);
  const cv::Mat nearest = nearest_plant(from);
  size_t seen = 0, lost = 0;
  for (int y = 0; y < from.lines.rows; ++y)
    for (int x = 0; x < from.lines.cols; ++x) {
      if (!from.lines.at<uint8_t>(y, x)) continue;
      const cv::Vec2i q = nearest.at<cv::Vec2i>(y, x);
      if (q[0] < 0) continue;
      glm::vec2 at;
      if (!into.place(from.position.at<cv::Vec3f>(q[1], q[0]), at)) continue;
      at += glm::vec2(float(x - q[0]), float(y - q[1]));
      const int u = int(std::floor(at.x)), v = int(std::floor(at.y));
      if (u < 0 || v < 0 || u >= to_reach.cols || v >= to_reach.rows) continue;
      ++seen;
      lost += to_reach.at<float>(v, u) > kLineReach;
    }
  if (seen == 0) return std::nullopt;
  return double(lost) / double(seen);
}

cv::Mat reach(const cv::Mat& lines) {
  cv::Mat dist;
  cv::distanceTransform(lines == 0, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return dist;
}

void check_frame(const CoherenceFrame& f, const cv::Size& size) {
  SYLVA_CHECK(f.image.type() == CV_8UC4 && f.image.size() == size,
              "frame_coherence: CV_8UC4 images of one size");
  SYLVA_CHECK(f.position.type() == CV_32FC3 && f.position.size() == size,
              "frame_coherence: CV_32FC3 positions of the image's size");
  SYLVA_CHECK(f.lines.empty() || (f.lines.type() == CV_8UC1 && f.lines.size() == size),
              "frame_coherence: CV_8UC1 lines of the image's size");
}

}  // namespace

FrameCoherence frame_coherence(const CoherenceFrame& previous, const CoherenceFrame& current) {
  const cv::Size size = current.image.size();
  check_frame(previous, size);
  check_frame(current, size);
  FrameCoherence c;
  c.reprojection_error = reprojection_error(previous, current, c.pixels);
  if (previous.lines.empty() || current.lines.empty()) return c;
  const std::optional<double> vanish = popped(previous, current, reach(current.lines));
  const std::optional<double> appear = popped(current, previous, reach(previous.lines));
  if (vanish || appear) c.line_pop = std::max(vanish.value_or(0.0), appear.value_or(0.0));
  return c;
}

}  // namespace sylva

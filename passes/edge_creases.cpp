#include "passes/edge_creases.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "passes/edge_lattice.h"

namespace sylva {

namespace {

constexpr uint8_t kMark = 255;

// One row of the crease test (Saito & Takahashi's second-order depth differences): marks on
// pixel centres (`at`) and between pixel i and i+1 (`between`, n - 1 entries).
class CreaseLine {
 public:
  void run(const float* z, const uint8_t* fg, int n, double threshold, uint8_t* at,
           uint8_t* between) {
    m_valid.assign(n, 0);
    m_a.assign(n, 0.0f);
    m_b.assign(n, 0.0f);
    m_key.assign(n, 0.0f);
    for (int i = 1; i + 1 < n; ++i) {
      if (!(fg[i - 1] && fg[i] && fg[i + 1])) continue;
      const float z0 = z[i - 1], z1 = z[i], z2 = z[i + 1];
      if (!(z0 > 0.0f && z1 > 0.0f && z2 > 0.0f)) continue;
      m_valid[i] = 1;
      m_a[i] = (z0 - 2.0f * z1 + z2) / z1;  // on z: 0 on planes seen orthographically
      m_b[i] = z1 / z0 - 2.0f + z1 / z2;    // on 1/z, times z: 0 on planes in perspective
      m_key[i] = std::min(std::abs(m_a[i]), std::abs(m_b[i]));
    }
    for (int i = 1; i + 1 < n; ++i) {
      if (!m_valid[i]) continue;
      const double m = std::min(std::abs(paired(m_a, i)), std::abs(paired(m_b, i)));
      if (!(m > threshold && beats(z, i, i - 1) && beats(z, i, i + 1))) continue;
      // Where the kink lies: a neighbour holding a third or more of the pair's response puts
      // it half-way between the two pixels.
      const int j = partner(i);
      if (j >= 0 && m_key[j] >= 0.5f * m_key[i])
        between[std::min(i, j)] = kMark;
      else
        at[i] = kMark;
    }
  }

 private:
  // The same-signed (on z) valid neighbour with the larger response, or -1.
  int partner(int i) const {
    int best = -1;
    for (int j : {i - 1, i + 1})
      if (m_valid[j] && (m_a[j] > 0.0f) == (m_a[i] > 0.0f) && (best < 0 || m_key[j] > m_key[best]))
        best = j;
    return best;
  }

  // A kink between pixels i and i+1 splits its second difference between them (in proportion
  // to where it falls), so add the same-signed neighbour's share: the response then does not
  // depend on the kink's sub-pixel position.
  double paired(const std::vector<float>& d, int i) const {
    double best = 0.0;
    for (int j : {i - 1, i + 1})
      if (m_valid[j] && (d[j] > 0.0f) == (d[i] > 0.0f) && std::abs(d[j]) > std::abs(best))
        best = d[j];
    return double(d[i]) + best;
  }

  // Non-maximum suppression along the line, so a crease is marked once: the stronger response
  // wins; within 25% (a kink half-way between two pixels, or both sides of a depth jump) the
  // nearer pixel wins, then the first.
  bool beats(const float* z, int i, int j) const {
    if (!m_valid[j]) return true;
    const float ki = m_key[i], kj = m_key[j];
    if (ki > 1.25f * kj) return true;
    if (1.25f * ki < kj) return false;
    return z[i] < z[j] || (z[i] == z[j] && i < j);
  }

  std::vector<uint8_t> m_valid;
  std::vector<float> m_a, m_b, m_key;
};

// Every row of z (in parallel bands, one CreaseLine each).
void mark_rows(const cv::Mat& z, const cv::Mat& fg, double threshold, cv::Mat& at,
               cv::Mat& between) {
  for_bands(z.rows, [&](int y0, int y1) {
    CreaseLine line;
    std::vector<uint8_t> none(size_t(z.cols), 0);  // a one-pixel-wide image has no `between`
    for (int y = y0; y < y1; ++y)
      line.run(z.ptr<float>(y), fg.ptr<uint8_t>(y), z.cols, threshold, at.ptr<uint8_t>(y),
               between.cols > 0 ? between.ptr<uint8_t>(y) : none.data());
  });
}

}  // namespace

// Along rows, then along columns (the rows of the transposed images).
void mark_creases(const cv::Mat& depth, const cv::Mat& fg, double threshold, EdgeMarks& marks) {
  mark_rows(depth, fg, threshold, marks.at, marks.between_x);
  cv::Mat depth_t, fg_t, at_t, between_t;
  cv::transpose(depth, depth_t);
  cv::transpose(fg, fg_t);
  at_t = cv::Mat::zeros(depth_t.size(), CV_8UC1);
  between_t = cv::Mat::zeros(depth_t.rows, std::max(0, depth_t.cols - 1), CV_8UC1);
  mark_rows(depth_t, fg_t, threshold, at_t, between_t);
  cv::Mat back;
  cv::transpose(at_t, back);
  cv::bitwise_or(marks.at, back, marks.at);
  if (!between_t.empty()) {
    cv::transpose(between_t, back);
    cv::bitwise_or(marks.between_y, back, marks.between_y);
  }
}

}  // namespace sylva

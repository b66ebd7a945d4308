#include "passes/edges.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/error.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

constexpr uint8_t kMark = 255;

cv::Size input_size(const EdgeImages& in) {
  for (const cv::Mat* m : {&in.color, &in.depth, &in.normal, &in.id})
    if (!m->empty()) return m->size();
  return {};
}

// Covered pixels (255): colour alpha >= 0.5 when given (the median of the SSAA samples, so the
// silhouette sits where the coverage crosses one half), else any geometric buffer.
cv::Mat foreground(const EdgeImages& in, const cv::Size& size) {
  cv::Mat fg;
  if (!in.color.empty()) {
    cv::Mat alpha;
    cv::extractChannel(in.color, alpha, 3);
    cv::compare(alpha, 128, fg, cv::CMP_GE);
  } else if (!in.depth.empty()) {
    cv::compare(in.depth, 0.0, fg, cv::CMP_GT);
  } else if (!in.id.empty()) {
    cv::compare(in.id, 0, fg, cv::CMP_NE);
  } else if (!in.normal.empty()) {
    fg.create(size, CV_8UC1);
    for (int y = 0; y < size.height; ++y) {
      const cv::Vec3f* n = in.normal.ptr<cv::Vec3f>(y);
      uint8_t* f = fg.ptr<uint8_t>(y);
      for (int x = 0; x < size.width; ++x)
        f[x] = n[x].dot(n[x]) > 0.0f ? kMark : 0;
    }
  } else {
    fg = cv::Mat::zeros(size, CV_8UC1);
  }
  return fg;
}

// Calls visit(p, q, mark) for every covered right and down 4-neighbour pair: p, q flat pixel
// indices, mark the pair's entry in EdgeMarks::between_x or between_y.
template <class Visit>
void for_covered_pairs(const cv::Mat& fg, EdgeMarks& marks, Visit visit) {
  const int w = fg.cols, h = fg.rows;
  for (int y = 0; y < h; ++y) {
    const uint8_t* f = fg.ptr<uint8_t>(y);
    const uint8_t* down = y + 1 < h ? fg.ptr<uint8_t>(y + 1) : nullptr;
    uint8_t* mx = w > 1 ? marks.between_x.ptr<uint8_t>(y) : nullptr;
    uint8_t* my = down ? marks.between_y.ptr<uint8_t>(y) : nullptr;
    for (int x = 0; x < w; ++x) {
      if (!f[x]) continue;
      const int p = y * w + x;
      if (x + 1 < w && f[x + 1]) visit(p, p + 1, mx[x]);
      if (down && down[x]) visit(p, p + w, my[x]);
    }
  }
}

// Between covered and uncovered 4-neighbours. The image border is not background: a drawing
// cropped by the frame is not outlined there. With the colour's alpha, the crossing is placed
// where a straight boundary would give the two pixels their coverage: a covered pixel p and an
// uncovered q with coverages a_p, a_q put it a_p + a_q - 1/2 px from p's centre toward q
// (exact for a boundary square to the line through p and q).
void mark_silhouette(const cv::Mat& fg, const cv::Mat& alpha, EdgeMarks& marks) {
  const int w = fg.cols, h = fg.rows;
  const bool shifts = !alpha.empty();
  if (shifts) {
    marks.shift_x = cv::Mat::zeros(marks.between_x.size(), CV_32FC1);
    marks.shift_y = cv::Mat::zeros(marks.between_y.size(), CV_32FC1);
  }
  // Shift from the midpoint toward q's side (+1: q at +x/+y), for covered p.
  auto shift = [&](int yp, int xp, int yq, int xq, float toward) {
    const float ap = alpha.at<uint8_t>(yp, xp) / 255.0f, aq = alpha.at<uint8_t>(yq, xq) / 255.0f;
    const float t = std::clamp(ap + aq - 0.5f, 0.0f, 1.0f);  // from p's centre
    return toward * (t - 0.5f);
  };
  for (int y = 0; y < h; ++y) {
    const uint8_t* f = fg.ptr<uint8_t>(y);
    for (int x = 0; x + 1 < w; ++x) {
      if ((f[x] != 0) == (f[x + 1] != 0)) continue;
      marks.between_x.at<uint8_t>(y, x) = kMark;
      if (shifts)
        marks.shift_x.at<float>(y, x) =
            f[x] ? shift(y, x, y, x + 1, 1.0f) : shift(y, x + 1, y, x, -1.0f);
    }
    if (y + 1 < h) {
      const uint8_t* down = fg.ptr<uint8_t>(y + 1);
      for (int x = 0; x < w; ++x) {
        if ((f[x] != 0) == (down[x] != 0)) continue;
        marks.between_y.at<uint8_t>(y, x) = kMark;
        if (shifts)
          marks.shift_y.at<float>(y, x) =
              f[x] ? shift(y, x, y + 1, x, 1.0f) : shift(y + 1, x, y, x, -1.0f);
      }
    }
  }
}

// Saito & Takahashi's first-order depth differences, relative to the nearer depth.
void mark_depth(const cv::Mat& depth, const cv::Mat& fg, float threshold, EdgeMarks& marks) {
  const cv::Mat flat = depth.isContinuous() ? depth : depth.clone();
  const float* z = flat.ptr<float>(0);
  for_covered_pairs(fg, marks, [&](int p, int q, uint8_t& mark) {
    const float zp = z[p], zq = z[q];
    if (!(zp > 0.0f && zq > 0.0f)) return;
    if (std::abs(zp - zq) > threshold * std::min(zp, zq)) mark = kMark;
  });
}

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

// Along rows, then along columns (the rows of the transposed images).
void mark_creases(const cv::Mat& depth, const cv::Mat& fg, double threshold, EdgeMarks& marks) {
  CreaseLine line;
  auto rows = [&](const cv::Mat& z, const cv::Mat& f, cv::Mat& at, cv::Mat& between) {
    std::vector<uint8_t> none(size_t(z.cols), 0);
    for (int y = 0; y < z.rows; ++y)
      line.run(z.ptr<float>(y), f.ptr<uint8_t>(y), z.cols, threshold, at.ptr<uint8_t>(y),
               between.cols > 0 ? between.ptr<uint8_t>(y) : none.data());
  };
  rows(depth, fg, marks.at, marks.between_x);
  cv::Mat depth_t, fg_t, at_t, between_t;
  cv::transpose(depth, depth_t);
  cv::transpose(fg, fg_t);
  at_t = cv::Mat::zeros(depth_t.size(), CV_8UC1);
  between_t = cv::Mat::zeros(depth_t.rows, std::max(0, depth_t.cols - 1), CV_8UC1);
  rows(depth_t, fg_t, at_t, between_t);
  cv::Mat back;
  cv::transpose(at_t, back);
  cv::bitwise_or(marks.at, back, marks.at);
  if (!between_t.empty()) {
    cv::transpose(between_t, back);
    cv::bitwise_or(marks.between_y, back, marks.between_y);
  }
}

// Decaudin's normal discontinuities.
void mark_normals(const cv::Mat& normal, const cv::Mat& fg, float threshold_deg, bool vector,
                  EdgeMarks& marks) {
  const int count = normal.rows * normal.cols;
  const cv::Mat flat = normal.isContinuous() ? normal : normal.clone();
  const cv::Vec3f* n = flat.ptr<cv::Vec3f>(0);
  std::vector<cv::Vec3f> unit(size_t(count), cv::Vec3f(0, 0, 0));
  std::vector<uint8_t> has_direction(size_t(count), 0);
  for (int i = 0; i < count; ++i) {
    const float len = std::sqrt(n[i].dot(n[i]));
    if (len > 1e-6f) {
      has_direction[size_t(i)] = 1;
      unit[size_t(i)] = n[i] / len;
    }
  }
  const double t = threshold_deg * CV_PI / 180.0;
  const float cos_t = float(std::cos(t));
  const float chord = float(2.0 * std::sin(t / 2.0));
  const float chord2 = chord * chord;
  for_covered_pairs(fg, marks, [&](int p, int q, uint8_t& mark) {
    // A covered pixel without a normal (zero) has nothing to compare.
    if (!has_direction[size_t(p)] || !has_direction[size_t(q)]) return;
    if (vector) {
      const cv::Vec3f d = n[p] - n[q];
      if (d.dot(d) > chord2) mark = kMark;
    } else if (unit[size_t(p)].dot(unit[size_t(q)]) < cos_t) {
      mark = kMark;
    }
  });
}

void mark_ids(const cv::Mat& id, const cv::Mat& fg, EdgeMarks& marks) {
  const cv::Mat flat = id.isContinuous() ? id : id.clone();
  const int32_t* v = flat.ptr<int32_t>(0);
  for_covered_pairs(fg, marks, [&](int p, int q, uint8_t& mark) {
    if (v[p] != 0 && v[q] != 0 && v[p] != v[q]) mark = kMark;
  });
}

// Exact Euclidean distance from every pixel centre to the nearest mark, on the half-pixel
// lattice: fine coordinates (i, j) = twice the pixel coordinates, pixel (x, y) at (2x, 2y).
// Felzenszwalb & Huttenlocher's separable transform (2012): per fine column the nearest mark
// at each pixel row, then per pixel row the lower envelope of the parabolas over fine columns.
// Returns distances in px (CV_32FC1; kFar without any mark) and the nearest mark's fine
// coordinates (CV_32SC2, (i, j); (-1, -1) without any mark).
constexpr float kFar = 1e9f;

// Marks by fine lattice coordinates (false outside the lattice).
struct Lattice {
  const EdgeMarks& m;
  int fw, fh;
  explicit Lattice(const EdgeMarks& marks)
      : m(marks), fw(2 * marks.at.cols - 1), fh(2 * marks.at.rows - 1) {}
  bool operator()(int i, int j) const {
    if (i < 0 || j < 0 || i >= fw || j >= fh) return false;
    if (j % 2 == 0) {
      const int y = j / 2;
      return i % 2 == 0 ? m.at.at<uint8_t>(y, i / 2) != 0
                        : m.between_x.at<uint8_t>(y, (i - 1) / 2) != 0;
    }
    return i % 2 == 0 && m.between_y.at<uint8_t>((j - 1) / 2, i / 2) != 0;
  }
  // Where the mark at (i, j) lies, with its sub-pixel shift, in fine units relative to (i, j).
  cv::Point2d shift(int i, int j) const {
    if (i % 2 == 1 && !m.shift_x.empty())
      return {2.0 * m.shift_x.at<float>(j / 2, (i - 1) / 2), 0.0};
    if (j % 2 == 1 && !m.shift_y.empty())
      return {0.0, 2.0 * m.shift_y.at<float>((j - 1) / 2, i / 2)};
    return {0.0, 0.0};
  }
};

void lattice_distance(const EdgeMarks& m, cv::Mat& dist, cv::Mat& nearest) {
  const int w = m.at.cols, h = m.at.rows;
  const Lattice is_mark(m);
  const int fw = is_mark.fw, fh = is_mark.fh;
  // Pass 1: row (fine j) of the nearest mark in each fine column, at each pixel row.
  constexpr int kNone = std::numeric_limits<int>::min() / 4;
  cv::Mat row_of(h, fw, CV_32SC1);
  std::vector<int> last(size_t(fw), kNone);
  for (int j = 0; j < fh; ++j) {
    for (int i = 0; i < fw; ++i)
      if (is_mark(i, j)) last[size_t(i)] = j;
    if (j % 2 == 0) std::copy(last.begin(), last.end(), row_of.ptr<int>(j / 2));
  }
  std::vector<int> next(size_t(fw), std::numeric_limits<int>::max() / 4);
  for (int j = fh - 1; j >= 0; --j) {
    for (int i = 0; i < fw; ++i)
      if (is_mark(i, j)) next[size_t(i)] = j;
    if (j % 2 == 0) {
      int* r = row_of.ptr<int>(j / 2);
      for (int i = 0; i < fw; ++i)
        if (int64_t(next[size_t(i)]) - j < int64_t(j) - r[i]) r[i] = next[size_t(i)];
    }
  }
  // Pass 2: per pixel row, the lower envelope of f(i) + (q - i)^2 with f(i) the squared
  // vertical distance, evaluated at the pixel centres q = 2x.
  dist.create(h, w, CV_32FC1);
  nearest.create(h, w, CV_32SC2);
  std::vector<double> f(static_cast<size_t>(fw)), z(static_cast<size_t>(fw) + 1);
  std::vector<int> v(static_cast<size_t>(fw));
  for (int y = 0; y < h; ++y) {
    const int* r = row_of.ptr<int>(y);
    const int j = 2 * y;
    int k = -1;
    for (int i = 0; i < fw; ++i) {
      if (r[i] == kNone || r[i] > fh) continue;  // no mark in this column
      f[size_t(i)] = double(j - r[i]) * double(j - r[i]);
      double s = -std::numeric_limits<double>::infinity();
      while (k >= 0) {
        const int vk = v[size_t(k)];
        s = ((f[size_t(i)] + double(i) * i) - (f[size_t(vk)] + double(vk) * vk)) / (2.0 * (i - vk));
        if (s <= z[size_t(k)])
          --k;
        else
          break;
      }
      ++k;
      v[size_t(k)] = i;
      z[size_t(k)] = k == 0 ? -std::numeric_limits<double>::infinity() : s;
    }
    float* d = dist.ptr<float>(y);
    cv::Vec2i* nr = nearest.ptr<cv::Vec2i>(y);
    if (k < 0) {
      for (int x = 0; x < w; ++x) {
        d[x] = kFar;
        nr[x] = cv::Vec2i(-1, -1);
      }
      continue;
    }
    z[size_t(k) + 1] = std::numeric_limits<double>::infinity();
    int e = 0;
    for (int x = 0; x < w; ++x) {
      const double q = 2.0 * x;
      while (z[size_t(e) + 1] < q)
        ++e;
      const int i = v[size_t(e)];
      d[x] = float(0.5 * std::sqrt((q - i) * (q - i) + f[size_t(i)]));
      nr[x] = cv::Vec2i(i, r[i]);
    }
  }
}

// Coverage of a pixel by a line of width w whose centre line is d px from the pixel centre:
// a one-pixel box filter across the line (exact for straight lines).
inline float line_coverage(float w, float d) {
  return std::clamp(std::min(w, 0.5f * w + 0.5f - d), 0.0f, 1.0f);
}

// The marks sample the boundary at half-pixel steps and zigzag about it by up to half a
// pixel (a binary discontinuity only says between which pixels the boundary passes), so the
// distance to the nearest mark misjudges the distance to the boundary: thin diagonal lines come
// out up to 25% lighter, thick ones a little wider. Where the marks within two pixels of the
// nearest one form a line, that line fitted through them (least squares) is the boundary; at
// corners and crossings, the polyline through the nearest mark and its neighbours. Marks
// count at their sub-pixel positions (EdgeMarks::shift_x/_y). Fine coordinates of the pixel
// (pi, pj) and of the nearest mark (mi, mj) in, px out.
float boundary_distance(const Lattice& is_mark, int pi, int pj, int mi, int mj) {
  constexpr int kWindow = 4;  // fine units: two pixels
  // Positions relative to the nearest mark's lattice point.
  cv::Point2d points[(2 * kWindow + 1) * (2 * kWindow + 1)];
  bool close[(2 * kWindow + 1) * (2 * kWindow + 1)];
  int n = 0;
  cv::Point2d sum(0, 0);
  for (int dj = -kWindow; dj <= kWindow; ++dj)
    for (int di = -kWindow; di <= kWindow; ++di) {
      if (!is_mark(mi + di, mj + dj)) continue;
      points[n] = cv::Point2d(di, dj) + is_mark.shift(mi + di, mj + dj);
      close[n] = std::max(std::abs(di), std::abs(dj)) <= 2;
      sum += points[n++];
    }
  const cv::Point2d a(pi - mi, pj - mj);
  const cv::Point2d m = is_mark.shift(mi, mj);
  // Polyline: segments from the nearest mark to its neighbours within a pixel.
  double polyline = cv::norm(a - m);
  for (int k = 0; k < n; ++k) {
    if (!close[k]) continue;
    const cv::Point2d e = points[k] - m;
    const double len2 = e.dot(e);
    if (len2 <= 1e-12) continue;
    const double t = std::clamp((a - m).dot(e) / len2, 0.0, 1.0);
    polyline = std::min(polyline, cv::norm(a - m - t * e));
  }
  polyline *= 0.5;
  if (n < 4) return float(polyline);
  const cv::Point2d c = sum / double(n);
  double vxx = 0, vyy = 0, vxy = 0;
  for (int k = 0; k < n; ++k) {
    const cv::Point2d q = points[k] - c;
    vxx += q.x * q.x;
    vyy += q.y * q.y;
    vxy += q.x * q.y;
  }
  const double mean = 0.5 * (vxx + vyy);
  const double spread = std::sqrt(0.25 * (vxx - vyy) * (vxx - vyy) + vxy * vxy);
  const double major = mean + spread, minor = mean - spread;
  if (!(major > 0.0) || minor > 0.1 * major) return float(polyline);  // not a line
  const double angle = 0.5 * std::atan2(2.0 * vxy, vxx - vyy);
  const cv::Point2d dir(std::cos(angle), std::sin(angle));
  double lo = 1e30, hi = -1e30;
  for (int k = 0; k < n; ++k) {
    const double t = (points[k] - c).dot(dir);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  const cv::Point2d pc = a - c;
  const double along = pc.dot(dir), across = -pc.x * dir.y + pc.y * dir.x;
  const double beyond = along < lo ? lo - along : (along > hi ? along - hi : 0.0);
  return float(0.5 * std::sqrt(across * across + beyond * beyond));
}

// The depth at a mark: the pixel's, or the nearer covered one of the pair it lies between;
// failing that (coverage from the colour's alpha may reach a pixel the depth misses), the
// nearest covered depth within a pixel; 0 if none.
float mark_depth_at(const cv::Mat& depth, int i, int j) {
  auto nearest = [&](int x0, int x1, int y0, int y1) {
    float v = std::numeric_limits<float>::infinity();
    for (int y = std::max(0, y0); y <= std::min(depth.rows - 1, y1); ++y)
      for (int x = std::max(0, x0); x <= std::min(depth.cols - 1, x1); ++x) {
        const float z = depth.at<float>(y, x);
        if (z > 0.0f) v = std::min(v, z);
      }
    return v;
  };
  // Pixels (x0..x1, y0..y1) holding the mark: 1 x 1, 2 x 1 or 1 x 2.
  const int x0 = i / 2, x1 = (i + 1) / 2, y0 = j / 2, y1 = (j + 1) / 2;
  float v = nearest(x0, x1, y0, y1);
  if (!std::isfinite(v)) v = nearest(x0 - 1, x1 + 1, y0 - 1, y1 + 1);
  return std::isfinite(v) ? v : 0.0f;
}

// Marks of other kinds within `apart` (fine units) of a silhouette mark would draw a second
// line beside the outline: a surface seen edge-on turns its normal and depth fastest right at
// its outline. The outline wins. Silhouettes do not depend on any threshold, so the counts
// still fall as thresholds rise.
void keep_apart_from_silhouette(const EdgeMarks& silhouette, EdgeMarks& other, int apart) {
  const Lattice is_outline(silhouette);
  auto clear_near = [&](cv::Mat& m, int i_of_x, int i_step, int j_of_y, int j_step) {
    for (int y = 0; y < m.rows; ++y) {
      uint8_t* row = m.ptr<uint8_t>(y);
      for (int x = 0; x < m.cols; ++x) {
        if (!row[x]) continue;
        const int i = i_step * x + i_of_x, j = j_step * y + j_of_y;
        bool near = false;
        for (int dj = -apart; dj <= apart && !near; ++dj)
          for (int di = -apart; di <= apart && !near; ++di)
            near = is_outline(i + di, j + dj);
        if (near) row[x] = 0;
      }
    }
  };
  clear_near(other.at, 0, 2, 0, 2);
  clear_near(other.between_x, 1, 2, 0, 2);
  clear_near(other.between_y, 0, 2, 1, 2);
}

// Marks connected (each within a pixel of the next) in groups of one or two are specks, not
// lines (at the steps of a grazing outline, a normal or depth change can show in a single
// pixel pair): drop them. A mark kept at a higher threshold has its group there too, so counts
// still fall as thresholds rise.
void drop_specks(EdgeMarks& marks) {
  const EdgeMarks before{
      marks.between_x.clone(), marks.between_y.clone(), marks.at.clone(), {}, {}};
  const Lattice is_mark(before);
  // Up to two neighbours of (i, j) within a pixel; returns how many (capped at 2).
  auto neighbours = [&](int i, int j, cv::Point2i* found) {
    int n = 0;
    for (int dj = -2; dj <= 2 && n < 2; ++dj)
      for (int di = -2; di <= 2 && n < 2; ++di)
        if ((di != 0 || dj != 0) && is_mark(i + di, j + dj)) found[n++] = {i + di, j + dj};
    return n;
  };
  auto drop = [&](cv::Mat& m, int i_of_x, int j_of_y) {
    for (int y = 0; y < m.rows; ++y) {
      uint8_t* row = m.ptr<uint8_t>(y);
      for (int x = 0; x < m.cols; ++x) {
        if (!row[x]) continue;
        cv::Point2i first[2], second[2];
        const int n = neighbours(2 * x + i_of_x, 2 * y + j_of_y, first);
        // A group of three or more: two neighbours, or one that has another.
        const bool line = n == 2 || (n == 1 && neighbours(first[0].x, first[0].y, second) == 2);
        if (!line) row[x] = 0;
      }
    }
  };
  drop(marks.at, 0, 0);
  drop(marks.between_x, 1, 0);
  drop(marks.between_y, 0, 1);
}

EdgeMarks empty_marks(const cv::Size& size) {
  EdgeMarks marks;
  marks.at = cv::Mat::zeros(size, CV_8UC1);
  marks.between_x = cv::Mat::zeros(size.height, std::max(0, size.width - 1), CV_8UC1);
  marks.between_y = cv::Mat::zeros(std::max(0, size.height - 1), size.width, CV_8UC1);
  return marks;
}

cv::Mat widen(const EdgeMarks& marks, const EdgeImages& in, const cv::Mat& fg,
              const EdgeParams& p) {
  const cv::Size size = marks.at.size();
  cv::Mat lines = cv::Mat::zeros(size, CV_32FC1);
  if (marks.count() == 0) return lines;
  cv::Mat dist, nearest;
  lattice_distance(marks, dist, nearest);
  const Lattice is_mark(marks);

  const float base = float(p.width * reference_scale(size));
  const bool by_depth = (p.depth_width > 1.0f || p.fade > 0.0f) && !in.depth.empty();
  double z_min = 0.0, z_max = 0.0;
  if (by_depth) {
    // Width and opacity follow the nearest mark's depth over the frame's covered range.
    cv::Mat covered;
    cv::compare(in.depth, 0.0, covered, cv::CMP_GT);
    cv::bitwise_and(covered, fg, covered);
    if (cv::countNonZero(covered) > 0)
      cv::minMaxLoc(in.depth, &z_min, &z_max, nullptr, nullptr, covered);
  }
  const double range = z_max - z_min;
  // Segments to the marks around the nearest one reach at most this much closer.
  const float reach = 0.5f * base + 0.5f + float(std::numbers::sqrt2 / 2.0);
  for (int y = 0; y < size.height; ++y) {
    const float* d = dist.ptr<float>(y);
    const cv::Vec2i* nr = nearest.ptr<cv::Vec2i>(y);
    float* l = lines.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      if (d[x] > reach) continue;
      const float dl = boundary_distance(is_mark, 2 * x, 2 * y, nr[x][0], nr[x][1]);
      if (!by_depth) {
        l[x] = line_coverage(base, dl);
        continue;
      }
      const float z = mark_depth_at(in.depth, nr[x][0], nr[x][1]);
      const double t = (z > 0.0f && range > 0.0) ? std::clamp((z - z_min) / range, 0.0, 1.0) : 0.0;
      const float width = base * float(1.0 + (1.0 / p.depth_width - 1.0) * t);
      l[x] = line_coverage(width, dl) * float(1.0 - p.fade * t);
    }
  }
  return lines;
}

void check_inputs(const EdgeImages& in, const EdgeParams& p, const cv::Size& size) {
  SYLVA_CHECK(!size.empty(), "edges: no input image");
  if (!in.color.empty()) expect_image(in.color, CV_8UC4, size, "color");
  if (!in.depth.empty()) expect_image(in.depth, CV_32FC1, size, "depth");
  if (!in.normal.empty()) expect_image(in.normal, CV_32FC3, size, "normal");
  if (!in.id.empty()) expect_image(in.id, CV_32SC1, size, "id");
  SYLVA_CHECK(!p.uses_depth() || !in.depth.empty(), "edges: the parameters need depth");
  SYLVA_CHECK(!p.uses_normal() || !in.normal.empty(), "edges: the parameters need normals");
  SYLVA_CHECK(!p.uses_id() || !in.id.empty(), "edges: the parameters need ids");
  SYLVA_CHECK(p.normal_metric == "angle" || p.normal_metric == "vector",
              "edges: unknown normal metric " + p.normal_metric);
}

EdgeMarks find_marks(const EdgeImages& in, const EdgeParams& p, cv::Mat& fg) {
  const cv::Size size = input_size(in);
  check_inputs(in, p, size);
  fg = foreground(in, size);
  EdgeMarks marks = empty_marks(size);
  if (p.depth) mark_depth(in.depth, fg, p.depth_threshold, marks);
  EdgeMarks creases = empty_marks(size);
  if (p.crease)
    mark_creases(in.depth, fg, p.crease_threshold / (1000.0 * reference_scale(size)), creases);
  if (p.normal) mark_normals(in.normal, fg, p.normal_threshold, p.normal_metric == "vector", marks);
  if (p.id) mark_ids(in.id, fg, marks);
  EdgeMarks outline;
  if (p.silhouette) {
    outline = empty_marks(size);
    cv::Mat alpha;
    if (!in.color.empty()) cv::extractChannel(in.color, alpha, 3);
    mark_silhouette(fg, alpha, outline);
    // 1.5 px, which also clears the risers of the outline's steps; 2.5 px for creases, as the
    // depth of a smooth body curves fastest in the last pixels before its outline.
    keep_apart_from_silhouette(outline, marks, 3);
    keep_apart_from_silhouette(outline, creases, 5);
  }
  for (auto m : {&EdgeMarks::at, &EdgeMarks::between_x, &EdgeMarks::between_y})
    if (!(marks.*m).empty()) cv::bitwise_or(marks.*m, creases.*m, marks.*m);
  drop_specks(marks);
  if (p.silhouette) {
    marks.shift_x = outline.shift_x;  // the other kinds' marks sit on their midpoints
    marks.shift_y = outline.shift_y;
    cv::bitwise_or(marks.at, outline.at, marks.at);
    if (!marks.between_x.empty())
      cv::bitwise_or(marks.between_x, outline.between_x, marks.between_x);
    if (!marks.between_y.empty())
      cv::bitwise_or(marks.between_y, outline.between_y, marks.between_y);
  }
  return marks;
}

}  // namespace

bool EdgeParams::uses_depth() const {
  return depth || crease || depth_width > 1.0f || fade > 0.0f;
}

void bind_edge_params(ParamSet& set, EdgeParams& p) {
  set.add_bool("edges.silhouette", p.silhouette, "outline against the background, from coverage");
  set.add_bool("edges.depth", p.depth, "lines at depth discontinuities (Saito & Takahashi)");
  set.add_float("edges.depth_threshold", p.depth_threshold, 0.001, 10.0, "relative depth",
                "a line where neighbouring depths differ by more than this fraction of the "
                "nearer one");
  set.add_bool("edges.crease", p.crease, "lines at creases, from second-order depth");
  set.add_float("edges.crease_threshold", p.crease_threshold, 0.01, 100.0,
                "per mille of depth per reference px",
                "a line where the second difference of depth exceeds this");
  set.add_bool("edges.normal", p.normal, "lines at normal discontinuities (Decaudin)");
  set.add_float("edges.normal_threshold", p.normal_threshold, 0.0, 180.0, "degrees",
                "a line where neighbouring normals are more than this angle apart", true);
  set.add_choice("edges.normal_metric", p.normal_metric, {"angle", "vector"},
                 "angle: between directions; vector: |N_p - N_q|, so short (low-ka) normals "
                 "give fewer lines (Luft et al. Fig. 7c)");
  set.add_bool("edges.id", p.id, "lines where the id (primitive, cluster, object) changes");
  set.add_color("edges.color", p.color, "line colour");
  set.add_float("edges.width", p.width, 0.25, 16.0, "px at 1024 px", "line width");
  set.add_float("edges.depth_width", p.depth_width, 1.0, 8.0, "ratio",
                "nearest lines are this many times thicker than the farthest (1 = even)");
  set.add_float("edges.fade", p.fade, 0.0, 1.0, "",
                "opacity the farthest lines lose (0 = none, 1 = they vanish)");
}

int EdgeMarks::count() const {
  int n = 0;
  for (const cv::Mat* m : {&at, &between_x, &between_y})
    if (!m->empty()) n += cv::countNonZero(*m);
  return n;
}

EdgeMarks mark_edges(const EdgeImages& in, const EdgeParams& p) {
  cv::Mat fg;
  return find_marks(in, p, fg);
}

cv::Mat detect_edges(const EdgeImages& in, const EdgeParams& p) {
  cv::Mat fg;
  const EdgeMarks marks = find_marks(in, p, fg);
  return widen(marks, in, fg, p);
}

int add_edges_pass(RenderGraph& g, const EdgeResources& in, const EdgeParams& p) {
  std::vector<int> reads;
  EdgeResources used;  // what the pass reads; the rest stays -1
  auto need = [&](int EdgeResources::*field, bool wanted, const char* what) {
    if (!wanted) return;
    SYLVA_CHECK(in.*field >= 0, std::string("edges pass needs the ") + what + " resource");
    used.*field = in.*field;
    reads.push_back(in.*field);
  };
  need(&EdgeResources::normal, p.uses_normal(), "normal");
  need(&EdgeResources::depth, p.uses_depth(), "depth");
  need(&EdgeResources::id, p.uses_id(), "id");
  // Coverage: the colour's alpha when given; else whatever geometric buffer is read anyway;
  // and with nothing read at all, one image for the output size.
  if ((p.silhouette || reads.empty()) && in.color >= 0) {
    used.color = in.color;
    reads.push_back(in.color);
  }
  if (reads.empty()) {
    for (int EdgeResources::*field :
         {&EdgeResources::depth, &EdgeResources::id, &EdgeResources::normal})
      if (in.*field >= 0) {
        used.*field = in.*field;
        reads.push_back(in.*field);
        break;
      }
  }
  SYLVA_CHECK(!reads.empty(), "edges pass has no input resource");

  const int out = g.resource("edges");
  g.add_pass("edges", reads, {out}, [used, p, out](PassContext& ctx) {
    EdgeImages images;
    if (used.normal >= 0) images.normal = ctx.read<cv::Mat>(used.normal);
    if (used.depth >= 0) images.depth = ctx.read<cv::Mat>(used.depth);
    if (used.id >= 0) images.id = ctx.read<cv::Mat>(used.id);
    if (used.color >= 0) images.color = ctx.read<cv::Mat>(used.color);
    ctx.write(out, detect_edges(images, p));
  });
  return out;
}

}  // namespace sylva

#include "passes/edge_lines.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "passes/edge_lattice.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

// Exact Euclidean distance from every pixel centre to the nearest mark, on the half-pixel
// lattice (fine coordinates, pixel (x, y) at (2x, 2y)). Felzenszwalb & Huttenlocher's
// separable transform (2012): per fine column the nearest mark at each pixel row (pass 1),
// then per pixel row the lower envelope of the parabolas over fine columns (pass 2).

constexpr int kNone = std::numeric_limits<int>::min() / 4;

// Pass 1: the fine row j of the nearest mark in each fine column i, at each pixel row y
// (CV_32SC1, H x fine width; kNone or beyond the lattice when the column has no mark).
// Columns are independent: bands of them run in parallel.
cv::Mat nearest_mark_rows(const MarkLattice& lattice, int h) {
  const int fw = lattice.width(), fh = lattice.height();
  cv::Mat row_of(h, fw, CV_32SC1);
  for_bands(fw, [&](int i0, int i1) {
    const int n = i1 - i0;
    std::vector<int> last(size_t(n), kNone);
    for (int j = 0; j < fh; ++j) {
      const uint8_t* m = lattice.row(j) + i0;
      int* l = last.data();
      for (int k = 0; k < n; ++k)  // branch-free, so it vectorises
        l[k] = m[k] ? j : l[k];
      if (j % 2 == 0) std::copy(last.begin(), last.end(), row_of.ptr<int>(j / 2) + i0);
    }
    std::vector<int> next(size_t(n), std::numeric_limits<int>::max() / 4);
    for (int j = fh - 1; j >= 0; --j) {
      const uint8_t* m = lattice.row(j) + i0;
      int* nx = next.data();
      for (int k = 0; k < n; ++k)
        nx[k] = m[k] ? j : nx[k];
      if (j % 2 == 0) {
        int* r = row_of.ptr<int>(j / 2) + i0;
        for (int k = 0; k < n; ++k)
          if (int64_t(next[size_t(k)]) - j < int64_t(j) - r[k]) r[k] = next[size_t(k)];
      }
    }
  });
  return row_of;
}

// Pass 2 for one pixel row: the lower envelope of f(i) + (q - i)^2, f(i) the squared vertical
// distance, evaluated at the pixel centres q = 2x. Only distances up to `reach` px matter, so
// columns whose nearest mark is farther than that vertically are left out: wherever the
// nearest mark is within reach, its column and every column tying with it are kept, and the
// envelope picks the same mark (the leftmost of equals; all intersections are quotients of
// integers, exact enough that rounding never reorders them). Holds its buffers, one per band.
class RowEnvelope {
 public:
  RowEnvelope(int fw, float reach) : m_f(size_t(fw)), m_z(size_t(fw) + 1), m_v(size_t(fw)) {
    // The largest squared fine distance whose distance in px, computed as below, is in reach.
    m_max_f = std::floor(4.0 * double(reach) * double(reach)) + 4.0;
    while (m_max_f >= 0.0 && float(0.5 * std::sqrt(m_max_f)) > reach)
      m_max_f -= 1.0;
  }

  // For pixel row y (r = its row of nearest_mark_rows): distances in px (`dist`) and the
  // nearest mark's fine coordinates (`nearest`) for the w pixels; where the distance exceeds
  // reach, only that it does. False when no mark is within reach of the row.
  bool run(const int* r, int y, int fh, int w, float* dist, cv::Vec2i* nearest) {
    const int fw = int(m_f.size());
    const int j = 2 * y;
    std::vector<double>& f = m_f;
    std::vector<double>& z = m_z;
    std::vector<int>& v = m_v;
    int k = -1;
    for (int i = 0; i < fw; ++i) {
      if (r[i] == kNone || r[i] > fh) continue;  // no mark in this column
      const double fi = double(j - r[i]) * double(j - r[i]);
      if (fi > m_max_f) continue;  // out of reach
      f[size_t(i)] = fi;
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
    if (k < 0) return false;
    z[size_t(k) + 1] = std::numeric_limits<double>::infinity();
    int e = 0;
    for (int x = 0; x < w; ++x) {
      const double q = 2.0 * x;
      while (z[size_t(e) + 1] < q)
        ++e;
      const int i = v[size_t(e)];
      dist[x] = float(0.5 * std::sqrt((q - i) * (q - i) + f[size_t(i)]));
      nearest[x] = cv::Vec2i(i, r[i]);
    }
    return true;
  }

 private:
  std::vector<double> m_f, m_z;
  std::vector<int> m_v;
  double m_max_f = 0.0;
};

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
// count at their sub-pixel positions (EdgeMarks::shift_x/_y).
//
// The fit depends only on the nearest mark, which several pixels share (those across the
// line from it), so it is kept in a small cache per band of rows: a pure function of the mark, it
// gives the same bytes whichever pixel computes it first.
class BoundaryDistance {
 public:
  explicit BoundaryDistance(const MarkLattice& lattice) : m_lattice(lattice), m_fits(kSlots) {}

  // Fine coordinates of the pixel (pi, pj) and of the nearest mark (mi, mj) in, px out.
  float operator()(int pi, int pj, int mi, int mj) {
    const MarkLattice& is_mark = m_lattice;
    const cv::Point2d a(pi - mi, pj - mj);
    const cv::Point2d m = is_mark.shift(mi, mj);
    // Polyline: segments from the nearest mark to its neighbours within a pixel. Squared
    // distances, with one square root of the least (sqrt is monotonic and correctly rounded,
    // so this is the least of the distances to the last bit).
    const cv::Point2d am = a - m;
    double nearest2 = am.dot(am);
    for (int dj = -kClose; dj <= kClose; ++dj) {
      constexpr unsigned kCloseBits = ((1u << (2 * kClose + 1)) - 1) << (kWindow - kClose);
      for (unsigned bits = is_mark.bits(mi - kWindow, mj + dj) & kCloseBits; bits;
           bits &= bits - 1) {
        const int di = std::countr_zero(bits) - kWindow;
        const cv::Point2d e = cv::Point2d(di, dj) + is_mark.shift(mi + di, mj + dj) - m;
        const double len2 = e.dot(e);
        if (len2 <= 1e-12) continue;
        const double t = std::clamp(am.dot(e) / len2, 0.0, 1.0);
        const cv::Point2d off = am - t * e;
        nearest2 = std::min(nearest2, off.dot(off));
      }
    }
    double polyline = std::sqrt(nearest2);
    polyline *= 0.5;
    const Fit& f = fit(mi, mj);
    if (!f.line) return float(polyline);
    const cv::Point2d pc = a - f.c;
    const double along = pc.dot(f.dir), across = -pc.x * f.dir.y + pc.y * f.dir.x;
    const double beyond = along < f.lo ? f.lo - along : (along > f.hi ? along - f.hi : 0.0);
    return float(0.5 * std::sqrt(across * across + beyond * beyond));
  }

 private:
  static constexpr int kWindow = 4;  // fine units: two pixels
  static constexpr int kClose = 2;   // fine units: one pixel
  static_assert(kWindow <= MarkLattice::kPad);
  static constexpr unsigned kWindowBits = (1u << (2 * kWindow + 1)) - 1;
  static constexpr int kSlots = 4096;

  // The least-squares line through the marks in the window around a mark, positions relative
  // to the mark's lattice point: centroid c, direction dir, extent [lo, hi] along it.
  struct Fit {
    int64_t key = -1;
    bool line = false;  // at least four marks, close to collinear
    cv::Point2d c, dir;
    double lo = 0.0, hi = 0.0;
  };

  const Fit& fit(int mi, int mj) {
    const int64_t key = int64_t(mj) * (m_lattice.width() + 1) + mi;
    Fit& f = m_fits[size_t((mi * 7 + mj * 1031) & (kSlots - 1))];
    if (f.key == key) return f;
    f.key = key;
    f.line = false;
    const MarkLattice& is_mark = m_lattice;
    cv::Point2d points[(2 * kWindow + 1) * (2 * kWindow + 1)];
    int n = 0;
    cv::Point2d sum(0, 0);
    for (int dj = -kWindow; dj <= kWindow; ++dj) {
      // In row-major order, as the sums below depend on it.
      for (unsigned bits = is_mark.bits(mi - kWindow, mj + dj) & kWindowBits; bits;
           bits &= bits - 1) {
        const int di = std::countr_zero(bits) - kWindow;
        points[n] = cv::Point2d(di, dj) + is_mark.shift(mi + di, mj + dj);
        sum += points[n++];
      }
    }
    if (n < 4) return f;
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
    if (!(major > 0.0) || minor > 0.1 * major) return f;  // not a line
    const double angle = 0.5 * std::atan2(2.0 * vxy, vxx - vyy);
    const cv::Point2d dir(std::cos(angle), std::sin(angle));
    double lo = 1e30, hi = -1e30;
    for (int k = 0; k < n; ++k) {
      const double t = (points[k] - c).dot(dir);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    f.line = true;
    f.c = c;
    f.dir = dir;
    f.lo = lo;
    f.hi = hi;
    return f;
  }

  const MarkLattice& m_lattice;
  std::vector<Fit> m_fits;
};

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

}  // namespace

cv::Mat draw_edge_lines(const EdgeMarks& marks, const cv::Mat& depth, const cv::Mat& fg,
                        const EdgeParams& p) {
  const cv::Size size = marks.at.size();
  cv::Mat lines = cv::Mat::zeros(size, CV_32FC1);
  if (marks.count() == 0) return lines;
  const MarkLattice lattice(marks);
  const cv::Mat row_of = nearest_mark_rows(lattice, size.height);

  const float base = float(p.width * reference_scale(size));
  const float min_width = std::max(0.0f, p.min_width);
  const float widest = std::max(base, min_width);
  const bool by_depth = (p.depth_width > 1.0f || p.fade > 0.0f) && !depth.empty();
  double z_min = 0.0, z_max = 0.0;
  if (by_depth) {
    // Width and opacity follow the nearest mark's depth over the frame's covered range.
    cv::Mat covered;
    cv::compare(depth, 0.0, covered, cv::CMP_GT);
    cv::bitwise_and(covered, fg, covered);
    if (cv::countNonZero(covered) > 0)
      cv::minMaxLoc(depth, &z_min, &z_max, nullptr, nullptr, covered);
  }
  const double range = z_max - z_min;
  // Segments to the marks around the nearest one reach at most this much closer.
  const float reach = 0.5f * widest + 0.5f + float(std::numbers::sqrt2 / 2.0);
  for_bands(size.height, [&](int y0, int y1) {
    RowEnvelope envelope(lattice.width(), reach);
    BoundaryDistance boundary_distance(lattice);
    std::vector<float> dist(size_t(size.width));
    std::vector<cv::Vec2i> nearest(size_t(size.width));
    for (int y = y0; y < y1; ++y) {
      if (!envelope.run(row_of.ptr<int>(y), y, lattice.height(), size.width, dist.data(),
                        nearest.data()))
        continue;
      float* l = lines.ptr<float>(y);
      for (int x = 0; x < size.width; ++x) {
        if (dist[size_t(x)] > reach) continue;
        const cv::Vec2i nr = nearest[size_t(x)];
        const float dl = boundary_distance(2 * x, 2 * y, nr[0], nr[1]);
        if (!by_depth) {
          l[x] = line_coverage(widest, dl);
          continue;
        }
        const float z = mark_depth_at(depth, nr[0], nr[1]);
        const double t =
            (z > 0.0f && range > 0.0) ? std::clamp((z - z_min) / range, 0.0, 1.0) : 0.0;
        const float width =
            std::max(min_width, base * float(1.0 + (1.0 / p.depth_width - 1.0) * t));
        l[x] = line_coverage(width, dl) * float(1.0 - p.fade * t);
      }
    }
  });
  return lines;
}

}  // namespace sylva

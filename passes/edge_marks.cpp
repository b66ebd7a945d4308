#include "passes/edge_marks.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/error.h"
#include "passes/edge_creases.h"
#include "passes/edge_lattice.h"
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
cv::Mat foreground(const EdgeImages& in, const cv::Mat& alpha, const cv::Size& size) {
  cv::Mat fg;
  if (!alpha.empty()) {
    cv::compare(alpha, 128, fg, cv::CMP_GE);
  } else if (!in.depth.empty()) {
    cv::compare(in.depth, 0.0, fg, cv::CMP_GT);
  } else if (!in.id.empty()) {
    cv::compare(in.id, 0, fg, cv::CMP_NE);
  } else if (!in.normal.empty()) {
    fg.create(size, CV_8UC1);
    for_bands(size.height, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) {
        const cv::Vec3f* n = in.normal.ptr<cv::Vec3f>(y);
        uint8_t* f = fg.ptr<uint8_t>(y);
        for (int x = 0; x < size.width; ++x)
          f[x] = n[x].dot(n[x]) > 0.0f ? kMark : 0;
      }
    });
  } else {
    fg = cv::Mat::zeros(size, CV_8UC1);
  }
  return fg;
}

// Calls visit(p, q, mark) for every covered right and down 4-neighbour pair: p, q flat pixel
// indices, mark the pair's entry in EdgeMarks::between_x or between_y. Rows run in parallel,
// so visit must only read shared state.
template <class Visit>
void for_covered_pairs(const cv::Mat& fg, EdgeMarks& marks, Visit visit) {
  const int w = fg.cols, h = fg.rows;
  for_bands(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
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
  });
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
  auto shift = [](uint8_t alpha_p, uint8_t alpha_q, float toward) {
    const float ap = alpha_p / 255.0f, aq = alpha_q / 255.0f;
    const float t = std::clamp(ap + aq - 0.5f, 0.0f, 1.0f);  // from p's centre
    return toward * (t - 0.5f);
  };
  for_bands(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const uint8_t* f = fg.ptr<uint8_t>(y);
      const uint8_t* a = shifts ? alpha.ptr<uint8_t>(y) : nullptr;
      if (w > 1) {
        uint8_t* mx = marks.between_x.ptr<uint8_t>(y);
        float* sx = shifts ? marks.shift_x.ptr<float>(y) : nullptr;
        for (int x = 0; x + 1 < w; ++x) {
          if ((f[x] != 0) == (f[x + 1] != 0)) continue;
          mx[x] = kMark;
          if (sx) sx[x] = f[x] ? shift(a[x], a[x + 1], 1.0f) : shift(a[x + 1], a[x], -1.0f);
        }
      }
      if (y + 1 < h) {
        const uint8_t* down = fg.ptr<uint8_t>(y + 1);
        const uint8_t* a_down = shifts ? alpha.ptr<uint8_t>(y + 1) : nullptr;
        uint8_t* my = marks.between_y.ptr<uint8_t>(y);
        float* sy = shifts ? marks.shift_y.ptr<float>(y) : nullptr;
        for (int x = 0; x < w; ++x) {
          if ((f[x] != 0) == (down[x] != 0)) continue;
          my[x] = kMark;
          if (sy) sy[x] = f[x] ? shift(a[x], a_down[x], 1.0f) : shift(a_down[x], a[x], -1.0f);
        }
      }
    }
  });
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

// Decaudin's normal discontinuities.
void mark_normals(const cv::Mat& normal, const cv::Mat& fg, float threshold_deg, bool vector,
                  EdgeMarks& marks) {
  const int count = normal.rows * normal.cols;
  const cv::Mat flat = normal.isContinuous() ? normal : normal.clone();
  const cv::Vec3f* n = flat.ptr<cv::Vec3f>(0);
  // The vector metric compares the normals as they are; only the angle needs directions.
  std::vector<cv::Vec3f> unit(vector ? 0 : size_t(count));
  std::vector<uint8_t> has_direction(size_t(count), 0);
  for_bands(normal.rows, [&](int y0, int y1) {
    for (int i = y0 * normal.cols; i < y1 * normal.cols; ++i) {
      const float len = std::sqrt(n[i].dot(n[i]));
      if (len > 1e-6f) {
        has_direction[size_t(i)] = 1;
        if (!vector) unit[size_t(i)] = n[i] / len;
      }
    }
  });
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

// Clears the marks of m (one of EdgeMarks' three images; its entry (x, y) at fine (2x + i_of_x,
// 2y + j_of_y)) where drop(i, j) holds. Rows in parallel: drop must only read shared state.
template <class Drop>
void clear_marks(cv::Mat& m, int i_of_x, int j_of_y, Drop drop) {
  for_bands(m.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      uint8_t* row = m.ptr<uint8_t>(y);
      for (int x = 0; x < m.cols; ++x)
        if (row[x] && drop(2 * x + i_of_x, 2 * y + j_of_y)) row[x] = 0;
    }
  });
}

template <class Drop>
void clear_all_marks(EdgeMarks& m, Drop drop) {
  clear_marks(m.at, 0, 0, drop);
  clear_marks(m.between_x, 1, 0, drop);
  clear_marks(m.between_y, 0, 1, drop);
}

// Marks of other kinds within `apart` (fine units, a square window) of a silhouette mark would
// draw a second line beside the outline: a surface seen edge-on turns its normal and depth
// fastest right at its outline. The outline wins. Silhouettes do not depend on any threshold,
// so the counts still fall as thresholds rise.
void keep_apart_from_silhouette(const MarkLattice& outline, EdgeMarks& other, int apart) {
  SYLVA_CHECK(apart <= MarkLattice::kPad, "edges: window wider than the lattice's border");
  const unsigned window = (1u << (2 * apart + 1)) - 1;
  clear_all_marks(other, [&](int i, int j) {
    for (int dj = -apart; dj <= apart; ++dj)
      if (outline.bits(i - apart, j + dj) & window) return true;
    return false;
  });
}

// Marks connected (each within a pixel of the next) in groups of one or two are specks, not
// lines (at the steps of a grazing outline, a normal or depth change can show in a single
// pixel pair): drop them. A mark kept at a higher threshold has its group there too, so counts
// still fall as thresholds rise.
void drop_specks(EdgeMarks& marks) {
  const MarkLattice before(marks);
  // Up to two neighbours of (i, j) within a pixel, in row-major order; returns how many
  // (capped at 2).
  auto neighbours = [&](int i, int j, cv::Point2i* found) {
    int n = 0;
    for (int dj = -2; dj <= 2 && n < 2; ++dj) {
      unsigned bits = before.bits(i - 2, j + dj) & (dj == 0 ? 0x1Bu : 0x1Fu);  // not (i, j)
      for (; bits && n < 2; bits &= bits - 1)
        found[n++] = {i - 2 + std::countr_zero(bits), j + dj};
    }
    return n;
  };
  clear_all_marks(marks, [&](int i, int j) {
    cv::Point2i first[2], second[2];
    const int n = neighbours(i, j, first);
    // A group of three or more: two neighbours, or one that has another.
    return !(n == 2 || (n == 1 && neighbours(first[0].x, first[0].y, second) == 2));
  });
}

// Groups of marks on 8-neighbouring pixels (a mark lies on its pixel, or on the left or upper
// pixel of the pair it lies between) whose pixels' bounding box has a diagonal under
// `min_px` are dropped: at small sizes leaf-level discontinuities give isolated specks and
// dashes that read as dirt, not lines. One connected-component labelling of those pixels; its
// groups and their boxes do not depend on how OpenCV splits the work, so neither do the bytes.
// A mark kept at a higher threshold has at least as large a group at a lower one, so counts
// still fall as thresholds rise.
void drop_short_lines(EdgeMarks& marks, double min_px) {
  const int w = marks.at.cols, h = marks.at.rows;
  if (!(min_px > 0.0) || w == 0 || h == 0) return;
  cv::Mat cells = marks.at.clone();
  if (w > 1) {
    cv::Mat left = cells(cv::Rect(0, 0, w - 1, h));
    cv::bitwise_or(left, marks.between_x, left);
  }
  if (h > 1) {
    cv::Mat upper = cells(cv::Rect(0, 0, w, h - 1));
    cv::bitwise_or(upper, marks.between_y, upper);
  }
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(cells, labels, stats, centroids, 8, CV_32S);
  std::vector<uint8_t> keep(size_t(n), 1);
  bool any_short = false;
  for (int k = 1; k < n; ++k) {
    const double extent =
        std::hypot(stats.at<int>(k, cv::CC_STAT_WIDTH), stats.at<int>(k, cv::CC_STAT_HEIGHT));
    keep[size_t(k)] = extent >= min_px;
    any_short = any_short || !keep[size_t(k)];
  }
  if (!any_short) return;
  clear_all_marks(marks, [&](int i, int j) { return !keep[size_t(labels.at<int>(j / 2, i / 2))]; });
}

EdgeMarks empty_marks(const cv::Size& size) {
  EdgeMarks marks;
  marks.at = cv::Mat::zeros(size, CV_8UC1);
  marks.between_x = cv::Mat::zeros(size.height, std::max(0, size.width - 1), CV_8UC1);
  marks.between_y = cv::Mat::zeros(std::max(0, size.height - 1), size.width, CV_8UC1);
  return marks;
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
}

void or_marks(EdgeMarks& into, const EdgeMarks& from) {
  for (auto m : {&EdgeMarks::at, &EdgeMarks::between_x, &EdgeMarks::between_y})
    if (!(into.*m).empty()) cv::bitwise_or(into.*m, from.*m, into.*m);
}

}  // namespace

EdgeMarks find_edge_marks(const EdgeImages& in, const EdgeParams& p, cv::Mat& fg) {
  const cv::Size size = input_size(in);
  check_inputs(in, p, size);
  cv::Mat alpha;
  if (!in.color.empty()) cv::extractChannel(in.color, alpha, 3);
  fg = foreground(in, alpha, size);
  EdgeMarks marks = empty_marks(size);
  if (p.depth) mark_depth(in.depth, fg, p.depth_threshold, marks);
  EdgeMarks creases;
  if (p.crease) {
    creases = empty_marks(size);
    mark_creases(in.depth, fg, p.crease_threshold / (1000.0 * reference_scale(size)), creases);
  }
  if (p.normal)
    mark_normals(in.normal, fg, p.normal_threshold, p.normal_metric == NormalMetric::Vector, marks);
  if (p.id) mark_ids(in.id, fg, marks);
  EdgeMarks outline;
  if (p.silhouette) {
    outline = empty_marks(size);
    mark_silhouette(fg, alpha, outline);
    // 1.5 px, which also clears the risers of the outline's steps; 2.5 px for creases, as the
    // depth of a smooth body curves fastest in the last pixels before its outline.
    const MarkLattice is_outline(outline);
    keep_apart_from_silhouette(is_outline, marks, 3);
    if (p.crease) keep_apart_from_silhouette(is_outline, creases, 5);
  }
  if (p.crease) or_marks(marks, creases);
  drop_specks(marks);
  if (p.silhouette) {
    marks.shift_x = outline.shift_x;  // the other kinds' marks sit on their midpoints
    marks.shift_y = outline.shift_y;
    or_marks(marks, outline);
  }
  drop_short_lines(marks, p.min_length * reference_scale(size));
  return marks;
}

int EdgeMarks::count() const {
  int n = 0;
  for (const cv::Mat* m : {&at, &between_x, &between_y})
    if (!m->empty()) n += cv::countNonZero(*m);
  return n;
}

}  // namespace sylva

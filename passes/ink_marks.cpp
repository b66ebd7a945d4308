#include "passes/ink_marks.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "passes/edge_marks.h"
#include "passes/ink_abstraction.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

// Sets every crack (p, q) of `c` for which mark(p_index, q_index) holds (indices y * W + x),
// in parallel row bands; each band writes only its own rows.
template <class Mark>
void mark_cracks(Cracks& c, Mark mark) {
  const cv::Size size = c.image();
  const int w = size.width, h = size.height;
  for_bands(h, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      uint8_t* cx = c.x.empty() ? nullptr : c.x.ptr<uint8_t>(y);
      for (int x = 0; x + 1 < w; ++x)
        cx[x] = mark(y * w + x, y * w + x + 1) ? 255 : 0;
      if (y + 1 >= h) continue;
      uint8_t* cy = c.y.ptr<uint8_t>(y);
      for (int x = 0; x < w; ++x)
        cy[x] = mark(y * w + x, (y + 1) * w + x) ? 255 : 0;
    }
  });
}

cv::Mat disc(double diameter) {
  const int k = std::max(1, static_cast<int>(std::lround(diameter)) | 1);
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k});
}

// Pixels within `distance` px of the boundary of `mask` (on either side).
cv::Mat near_boundary(const cv::Mat& mask, double distance) {
  cv::Mat grown, shrunk;
  cv::dilate(mask, grown, cv::Mat());
  cv::erode(mask, shrunk, cv::Mat(), {-1, -1}, 1, cv::BORDER_CONSTANT, 0);
  cv::Mat band = grown & ~shrunk;
  if (distance > 1.0) cv::dilate(band, band, disc(2.0 * distance));
  return band;
}

// The images every class reads, flattened (continuous copies where needed).
struct Flat {
  const uint8_t* plant;
  const uint8_t* wood;
  const float* depth;
  cv::Mat keep[3];
};

const uint8_t* flat_u8(const cv::Mat& m, cv::Mat& keep) {
  keep = m.isContinuous() ? m : m.clone();
  return keep.ptr<uint8_t>();
}

// Wood outlines where the wood is the nearer side: against the background, foliage behind it,
// or other wood behind it by more than `jump` (relative depth).
void mark_wood(Cracks& c, const Flat& f, const uint8_t* near_sil, float jump) {
  mark_cracks(c, [&](int p, int q) {
    if ((f.wood[p] | f.wood[q]) == 0 || (near_sil[p] | near_sil[q]) != 0) return false;
    if (f.wood[p] != 0 && f.wood[q] != 0) {
      const float zp = f.depth[p], zq = f.depth[q];
      return std::abs(zp - zq) > jump * std::min(zp, zq);
    }
    const int a = f.wood[p] != 0 ? p : q, b = a == p ? q : p;
    return f.plant[b] == 0 || f.depth[b] > f.depth[a] * (1.0f + jump);
  });
}

// The pixels on either side of the marked cracks.
cv::Mat crack_pixels(const Cracks& c) {
  const cv::Size size = c.image();
  cv::Mat m(size, CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x) {
      if (x + 1 < size.width && c.x.at<uint8_t>(y, x))
        m.at<uint8_t>(y, x) = m.at<uint8_t>(y, x + 1) = 255;
      if (y + 1 < size.height && c.y.at<uint8_t>(y, x))
        m.at<uint8_t>(y, x) = m.at<uint8_t>(y + 1, x) = 255;
    }
  return m;
}

// Crown-part contours: steps of the median-filtered depth larger than `levels`. With crown
// parts (CV_32SC1 labels, may be empty), a step counts only where two parts meet, so a line
// outlines a part in front of another, not the folds inside one.
void mark_interior(Cracks& c, const cv::Mat& median, const cv::Mat& crown, const cv::Mat& parts,
                   const uint8_t* near_sil, const cv::Mat& near_wood, int levels) {
  cv::Mat k0, k1, k2, k3;
  const uint8_t* z = flat_u8(median, k0);
  const uint8_t* in = flat_u8(crown, k1);
  const uint8_t* nw = flat_u8(near_wood, k2);
  k3 = parts.empty() || parts.isContinuous() ? parts : parts.clone();
  const int* part = parts.empty() ? nullptr : k3.ptr<int>();
  mark_cracks(c, [&](int p, int q) {
    if ((in[p] & in[q]) == 0 || (near_sil[p] | near_sil[q] | nw[p] | nw[q]) != 0) return false;
    if (z[p] == kNoDepth || z[q] == kNoDepth) return false;
    if (part != nullptr && (part[p] == part[q] || part[p] == 0 || part[q] == 0)) return false;
    return std::abs(int(z[p]) - int(z[q])) > levels;
  });
}

// The leaf-exact lines of edges.* (passes/edge_marks.h) sorted into silhouette, wood and
// `foliage_class`: a crack on the plant's boundary is silhouette, one with wood on its nearer
// side is wood, the rest `foliage_class`. A crease on a pixel centre counts as the crack to its
// right.
void sort_edge_marks(const EdgeMarks& m, const Flat& f, const cv::Size size, InkMarks& out,
                     LineClass foliage_class, bool silhouette) {
  const int w = size.width;
  auto cls = [&](int p, int q) {
    if ((f.plant[p] != 0) != (f.plant[q] != 0)) return LineClass::Silhouette;
    const int nearer = f.depth[p] <= f.depth[q] ? p : q;
    return f.wood[nearer] != 0 ? LineClass::Wood : foliage_class;
  };
  auto put = [&](int p, int q, bool vertical_pair) {
    const LineClass c = cls(p, q);
    if (c == LineClass::Silhouette && !silhouette) return;
    Cracks& k = out.of[size_t(c)];
    const int x = p % w, y = p / w;
    (vertical_pair ? k.y : k.x).at<uint8_t>(y, x) = 255;
  };
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < w; ++x) {
      const int p = y * w + x;
      if (x + 1 < w && (m.between_x.at<uint8_t>(y, x) != 0 || m.at.at<uint8_t>(y, x) != 0))
        put(p, p + 1, false);
      if (y + 1 < size.height && m.between_y.at<uint8_t>(y, x) != 0) put(p, p + w, true);
    }
}

EdgeImages edge_images(const InkLineImages& in) {
  EdgeImages e;
  e.color = in.color;
  e.depth = in.depth;
  e.normal = in.normal;
  e.id = in.id;
  return e;
}

// The working resolution of the crown's lines: the detail kWorkingDetail px across, never above
// the output's own resolution.
constexpr double kWorkingDetail = 5.0;

struct Working {
  double factor = 1.0;  // output px per working px, >= 1
  cv::Mat plant, depth, wood;
  cv::Mat parts;  // CV_32SC1 crown parts (leaf clusters, majority-filtered), or empty
};

// Coverage, wood and the covered pixels' mean depth, area-averaged down to the working size.
Working working_images(const cv::Mat& depth, const cv::Mat& plant, const cv::Mat& wood,
                       const cv::Mat& id, double detail) {
  Working w;
  w.factor = std::max(1.0, detail / kWorkingDetail);
  const cv::Size size(std::max(1, int(std::lround(plant.cols / w.factor))),
                      std::max(1, int(std::lround(plant.rows / w.factor))));
  w.factor = double(plant.cols) / size.width;
  // Coverage as a density: area-averaged, then blurred by a quarter of the detail, so the
  // crown is the same level set whether one working pixel averages 1 or 16 rendered ones.
  cv::Mat cover, weighted, mean, density, spread, wood_share;
  plant.convertTo(cover, CV_32F, 1.0 / 255.0);
  cv::resize(depth.mul(cover), weighted, size, 0, 0, cv::INTER_AREA);
  cv::resize(cover, cover, size, 0, 0, cv::INTER_AREA);
  const double sigma = 0.25 * kWorkingDetail;
  cv::GaussianBlur(cover, density, {0, 0}, sigma);
  w.plant = density >= 0.25f;
  // Depth: the covered pixels' mean in each working pixel (steps between crown parts stay
  // sharp); where none is covered, the blurred mean around it.
  cv::divide(weighted, cv::max(cover, 1e-6f), mean);
  cv::GaussianBlur(weighted, spread, {0, 0}, sigma);
  cv::divide(spread, cv::max(density, 1e-6f), spread);
  spread.copyTo(mean, cover <= 0.0f);
  w.depth = cv::Mat(size, CV_32FC1, cv::Scalar(0));
  mean.copyTo(w.depth, w.plant);
  wood.convertTo(wood_share, CV_32F, 1.0 / 255.0);
  cv::resize(wood_share, wood_share, size, 0, 0, cv::INTER_AREA);
  w.wood = (wood_share >= 0.25f) & w.plant;
  if (!id.empty()) {
    cv::resize(id, w.parts, size, 0, 0, cv::INTER_NEAREST);
    w.parts.setTo(0, ~w.plant);
    w.parts = majority_labels(w.parts, int(std::lround(0.5 * kWorkingDetail)));
  }
  return w;
}

}  // namespace

InkMarks mark_ink_lines(const InkLineImages& in, const EdgeParams& edges, const InkLineParams& p,
                        uint32_t branch_cluster, double scale) {
  const cv::Size size = in.color.size();
  expect_image(in.color, CV_8UC4, {}, "color");
  expect_image(in.depth, CV_32FC1, size, "depth");
  if (!in.id.empty()) expect_image(in.id, CV_32SC1, size, "id");
  InkMarks out;
  for (Cracks& c : out.of)
    c = Cracks(size);
  cv::Mat alpha;
  cv::extractChannel(in.color, alpha, 3);
  out.plant = alpha >= 128;
  cv::Mat wood = in.id.empty() || branch_cluster == 0
                     ? cv::Mat(size, CV_8UC1, cv::Scalar(0))
                     : (in.id == static_cast<int>(branch_cluster)) & out.plant;
  Flat f;
  f.plant = flat_u8(out.plant, f.keep[0]);
  f.wood = flat_u8(wood, f.keep[1]);
  f.keep[2] = in.depth.isContinuous() ? in.depth : in.depth.clone();
  f.depth = f.keep[2].ptr<float>();
  if (cv::countNonZero(out.plant) > 0) {
    double lo = 0, hi = 0;
    cv::minMaxLoc(in.depth, &lo, &hi, nullptr, nullptr, out.plant);
    out.near = static_cast<float>(lo);
    out.far = static_cast<float>(hi);
  }
  const double detail = p.detail * scale;
  out.thin = cv::Mat(size, CV_8UC1, cv::Scalar(0));
  out.crown_scale = 1.0;
  if (detail < 2.0) {  // leaf-exact: today's lines, sorted into classes
    EdgeParams e = edges;
    e.id = e.id && !in.id.empty();
    cv::Mat fg;
    sort_edge_marks(find_edge_marks(edge_images(in), e, fg), f, size, out, LineClass::Interior,
                    edges.silhouette);
    return out;
  }
  // The crown's lines are found at a working resolution where the detail is kWorkingDetail px,
  // so renders of any size see the same shapes (and large ones cost less).
  const Working w = working_images(in.depth, out.plant, wood, in.id, detail);
  out.crown_scale = w.factor;
  const double px = 1.0 / w.factor;  // working px per output px
  const CrownShape shape = crown_shape(w.plant, detail * px);
  const cv::Mat& crown = shape.body;
  out.thin = edges.silhouette ? shape.thin : cv::Mat(w.plant.size(), CV_8UC1, cv::Scalar(0));
  for (LineClass c : {LineClass::Silhouette, LineClass::Interior})
    out.of[size_t(c)] = Cracks(w.plant.size());
  if (edges.silhouette)
    mark_cracks(out.of[size_t(LineClass::Silhouette)],
                [c = crown.ptr<uint8_t>()](int a, int b) { return c[a] != c[b]; });
  // Wood and interior lines keep off the outline, and off the centre lines of thin parts.
  cv::Mat thin_band;
  cv::dilate(out.thin, thin_band, disc(2.0 * std::max(1.0, 2.5 * scale * px) + 1.0));
  const cv::Mat near_sil_w = near_boundary(crown, std::max(1.0, 2.5 * scale * px)) | thin_band;
  if (p.wood.on) {
    Flat fw;
    fw.plant = flat_u8(w.plant, fw.keep[0]);
    fw.wood = flat_u8(w.wood, fw.keep[1]);
    fw.keep[2] = w.depth;
    fw.depth = fw.keep[2].ptr<float>();
    cv::Mat keep;
    out.of[size_t(LineClass::Wood)] = Cracks(w.plant.size());
    mark_wood(out.of[size_t(LineClass::Wood)], fw, flat_u8(near_sil_w, keep),
              edges.depth_threshold);
  }
  if (p.interior.on && edges.depth) {
    cv::Mat near_wood, keep;
    // Where wood lines are drawn (wood in front), the crown's lines keep off; the parts'
    // borders with wood behind foliage are interior lines.
    cv::dilate(crack_pixels(out.of[size_t(LineClass::Wood)]), near_wood,
               disc(2.0 * std::max(1.0, 1.5 * scale * px) + 1.0));
    float near = 0, far = 0;
    const cv::Mat median = median_depth(w.depth, w.plant, detail * px, near, far);
    // Deussen & Strothotte's depth threshold, relative to the picture: detail / 256 of the
    // plant's depth extent (4 % at the default 10 px).
    const int levels = static_cast<int>(std::lround(253.0 * std::min(1.0, p.detail / 256.0)));
    mark_interior(out.of[size_t(LineClass::Interior)], median, crown, w.parts,
                  flat_u8(near_sil_w, keep), near_wood, levels);
  }
  if (p.detail_lines.on) {
    EdgeParams e = edges;
    e.silhouette = false;
    e.id = false;
    e.normal = e.normal && !in.normal.empty();
    cv::Mat fg;
    InkMarks leaf;
    for (Cracks& c : leaf.of)
      c = Cracks(size);
    sort_edge_marks(find_edge_marks(edge_images(in), e, fg), f, size, leaf, LineClass::Detail,
                    false);
    out.of[size_t(LineClass::Detail)] = leaf.of[size_t(LineClass::Detail)];
  }
  return out;
}

}  // namespace sylva

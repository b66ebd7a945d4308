#include "passes/ink_marks.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "passes/crown_coverage.h"
#include "passes/edge_marks.h"
#include "passes/ink_abstraction.h"
#include "passes/ink_working.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

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

// Crown-part contours from the scene: where the front parts (passes/crown_coverage.h) of two
// neighbouring pixels differ and the parts' mean depths differ by more than `jump` (scene units).
void mark_part_contours(Cracks& c, const CrownParts& parts, const cv::Mat& crown,
                        const uint8_t* near_sil, const cv::Mat& near_wood, float jump) {
  cv::Mat k0, k1;
  const uint8_t* in = flat_u8(crown, k0);
  const uint8_t* nw = flat_u8(near_wood, k1);
  const int* label = parts.label.ptr<int>();
  const float* z = parts.depth.ptr<float>();
  mark_cracks(c, [&](int p, int q) {
    if ((in[p] & in[q]) == 0 || (near_sil[p] | near_sil[q] | nw[p] | nw[q]) != 0) return false;
    if (label[p] == 0 || label[q] == 0 || label[p] == label[q]) return false;
    return std::abs(z[p] - z[q]) > jump;
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

// The crown's parts for interior lines: smoothed over the detail, a part where its own coverage
// is at least a half.
constexpr float kPartLevel = 0.5f;

// The class masks the crown's classes read, at the working resolution.
struct CrownMasks {
  cv::Mat crown;     // the crown's body (crown_field)
  cv::Mat near_sil;  // within reach of the outline or of a thin part's centre line
};

// In a scene of many plants, each plant's outline where its crown stands in front of another's
// (project_plant_parts, at the crown field's smoothing and level), inside the crown's body.
void mark_plant_outlines(InkMarks& out, const SurfaceSamples& samples, const InkWorking& w,
                         const cv::Mat& body, double detail, uint32_t wood) {
  const CrownParts plants = project_plant_parts(samples, w.camera, 0.5 * detail, kCrownLevel, wood);
  if (plants.order.size() < 2) return;
  out.plants = Cracks(body.size());
  out.plant_depth = plants.depth;
  Cracks& c = out.plants;
  cv::Mat keep;
  const uint8_t* in = flat_u8(body, keep);
  const int* label = plants.label.ptr<int>();
  mark_cracks(c, [&](int p, int q) {
    return (in[p] & in[q]) != 0 && label[p] != 0 && label[q] != 0 && label[p] != label[q];
  });
}

// The silhouette: the crown field's outline, the plants' outlines in a scene of many plants and
// the thin parts' centre lines (InkMarks::thin).
CrownMasks mark_outline(const InkLineImages& in, const InkWorking& w, const EdgeParams& edges,
                        double detail, double scale, uint32_t wood, bool plants, InkMarks& out) {
  const double px = 1.0 / w.factor;  // working px per output px
  const CrownField shape = crown_field(w.coverage, detail * px);
  out.field = shape.field;
  out.thin = edges.silhouette ? thin_parts(w.coverage >= kPlantLevel, shape.body, detail * px)
                              : cv::Mat(w.plant.size(), CV_8UC1, cv::Scalar(0));
  if (edges.silhouette)
    mark_cracks(out.of[size_t(LineClass::Silhouette)],
                [c = shape.body.ptr<uint8_t>()](int a, int b) { return c[a] != c[b]; });
  if (edges.silhouette && plants && in.samples)
    mark_plant_outlines(out, *in.samples, w, shape.body, detail * px, wood);
  // Wood and interior lines keep off the outline (which lies up to half the detail outside the
  // crown's leaves, crown_field), and off the centre lines of thin parts.
  cv::Mat thin_band;
  const double band = std::max(1.0, 2.5 * scale * px);
  cv::dilate(out.thin, thin_band, disc(2.0 * band + 1.0));
  return {shape.body, near_boundary(shape.body, band + 0.5 * detail * px) | thin_band};
}

void mark_wood_lines(const InkWorking& w, const CrownMasks& m, const EdgeParams& edges,
                     InkMarks& out) {
  Flat fw;
  fw.plant = flat_u8(w.plant, fw.keep[0]);
  fw.wood = flat_u8(w.wood, fw.keep[1]);
  fw.keep[2] = w.depth;
  fw.depth = fw.keep[2].ptr<float>();
  cv::Mat keep;
  mark_wood(out.of[size_t(LineClass::Wood)], fw, flat_u8(m.near_sil, keep), edges.depth_threshold);
}

// Interior crown contours: from the crown's parts in the scene when there are surface samples,
// else from the depth median-filtered and the id buffer's parts.
void mark_interior_lines(const InkLineImages& in, const InkWorking& w, const CrownMasks& m,
                         const InkLineParams& p, uint32_t branch_cluster, double scale,
                         InkMarks& out) {
  const double px = 1.0 / w.factor, detail = p.detail * scale;
  cv::Mat near_wood, keep;
  // Where wood lines are drawn (wood in front), the crown's lines keep off; the parts' borders
  // with wood behind foliage are interior lines.
  cv::dilate(crack_pixels(out.of[size_t(LineClass::Wood)]), near_wood,
             disc(2.0 * std::max(1.0, 1.5 * scale * px) + 1.0));
  // Deussen & Strothotte's depth threshold, relative to the picture: detail / 256 of the
  // plant's depth extent (4 % at the default 10 px).
  const double share = std::min(1.0, p.detail / 256.0);
  Cracks& c = out.of[size_t(LineClass::Interior)];
  if (in.samples) {
    const CrownParts parts =
        project_crown_parts(*in.samples, w.camera, detail * px, kPartLevel, branch_cluster);
    out.part_depth = parts.depth;
    mark_part_contours(c, parts, m.crown, flat_u8(m.near_sil, keep), near_wood,
                       float(share * (out.far - out.near)));
  } else {
    float near = 0, far = 0;
    const cv::Mat median = median_depth(w.depth, w.plant, detail * px, near, far);
    mark_interior(c, median, m.crown, w.parts, flat_u8(m.near_sil, keep), near_wood,
                  int(std::lround(253.0 * share)));
  }
}

// The leaf-level lines of edges.* at the frame's resolution, as `cls` (and silhouette and wood
// where they are, when `silhouette`).
void mark_leaf_lines(const InkLineImages& in, const EdgeParams& edges, const Flat& f, LineClass cls,
                     bool silhouette, InkMarks& out) {
  EdgeParams e = edges;
  e.silhouette = e.silhouette && silhouette;
  e.id = e.id && silhouette && !in.id.empty();
  e.normal = e.normal && !in.normal.empty();
  cv::Mat fg;
  sort_edge_marks(find_edge_marks(edge_images(in), e, fg), f, in.color.size(), out, cls,
                  e.silhouette);
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
  if (detail < 2.0) {  // leaf-exact: the edges' lines, sorted into classes
    mark_leaf_lines(in, edges, f, LineClass::Interior, true, out);
    return out;
  }
  const InkWorking w = ink_working_images(in, out.plant, wood, detail);
  out.crown_scale = w.factor;
  for (LineClass c : {LineClass::Silhouette, LineClass::Interior, LineClass::Wood})
    out.of[size_t(c)] = Cracks(w.plant.size());
  const CrownMasks masks =
      mark_outline(in, w, edges, detail, scale, branch_cluster, p.silhouette.on && p.plants, out);
  if (p.wood.on) mark_wood_lines(w, masks, edges, out);
  if (p.interior.on && edges.depth)
    mark_interior_lines(in, w, masks, p, branch_cluster, scale, out);
  if (p.detail_lines.on) {
    InkMarks leaf;
    for (Cracks& c : leaf.of)
      c = Cracks(size);
    mark_leaf_lines(in, edges, f, LineClass::Detail, false, leaf);
    out.of[size_t(LineClass::Detail)] = leaf.of[size_t(LineClass::Detail)];
  }
  return out;
}

}  // namespace sylva

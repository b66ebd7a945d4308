// Painting the blobs (Dudley 2005 §4.2-4.3; passes/blobs.h): colour wash, blend-light alpha,
// leaf detail, outlines and painter's order; parameters and graph wiring in blob_params.cpp.
#include "passes/blobs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <unordered_map>

#include "core/error.h"
#include "core/random.h"
#include "npr/blob_shape.h"
#include "npr/bspline.h"
#include "passes/pass_common.h"
#include "passes/watercolor_common.h"

namespace sylva {

namespace {

using watercolor_internal::encode_srgb;
using watercolor_internal::srgb_tables;

// Per cluster: the mean unlit colour (linear BGR) and the mean view-space position.
struct ClusterMeans {
  cv::Vec3d albedo{0, 0, 0};
  cv::Vec3d position{0, 0, 0};
  double count = 0;
};

std::unordered_map<uint32_t, ClusterMeans> cluster_means(const BlobImages& in) {
  const auto& lin = srgb_tables().to_linear;
  std::unordered_map<uint32_t, ClusterMeans> means;
  uint32_t last_id = 0;
  ClusterMeans* last = nullptr;
  for (int y = 0; y < in.id.rows; ++y) {
    const int32_t* ids = in.id.ptr<int32_t>(y);
    const cv::Vec4b* a = in.albedo.ptr<cv::Vec4b>(y);
    const cv::Vec3f* pos = in.position.empty() ? nullptr : in.position.ptr<cv::Vec3f>(y);
    for (int x = 0; x < in.id.cols; ++x) {
      const auto c = static_cast<uint32_t>(ids[x]);
      if (c == 0) continue;
      if (c != last_id || !last) {
        last = &means[c];
        last_id = c;
      }
      for (int k = 0; k < 3; ++k)
        last->albedo[k] += lin[a[x][k]];
      if (pos) last->position += cv::Vec3d(pos[x]);
      last->count += 1;
    }
  }
  for (auto& [id, m] : means) {
    m.albedo /= m.count;
    m.position /= m.count;
  }
  return means;
}

struct ViewLight {
  glm::vec3 v;  // direction toward the light, or position
  bool point;
  glm::vec3 color;
};

glm::vec3 toward(const ViewLight& l, const glm::vec3& at) {
  if (!l.point) return l.v;
  const glm::vec3 d = l.v - at;
  const float len = glm::length(d);
  return len > 1e-12f ? d / len : glm::vec3(0, 0, 1);
}

// The colour target is drawn over the background's colour with alpha = coverage (the blobs style
// clears alpha to 0, Style::configure), and supersampling averages in linear light, so a
// partly covered pixel holds coverage x surface + (1 - coverage) x background: the surface's
// own colour (linear BGR) and its coverage.
glm::vec3 surface_color(const cv::Vec4b& c, const glm::vec3& background,
                        const std::array<float, 256>& lin, float* coverage) {
  const float a = c[3] / 255.0f;
  *coverage = a;
  const glm::vec3 v(lin[c[0]], lin[c[1]], lin[c[2]]);
  if (a >= 1.0f || a <= 0.0f) return v;
  return glm::clamp((v - (1.0f - a) * background) / a, 0.0f, 1.0f);
}

// The outline polygon of a blob (pixel coordinates, closed) and its bounding box.
std::vector<glm::vec2> outline_polygon(const BlobOutline& b) {
  return sample_closed_bspline(b.wrap.points, 8);
}

// cv drawing coordinates: integer = pixel centre, 4 fractional bits.
constexpr int kShift = 4;
cv::Point fixed_point(glm::vec2 p, cv::Point2f origin) {
  return {static_cast<int>(std::lround((p.x - 0.5f - origin.x) * (1 << kShift))),
          static_cast<int>(std::lround((p.y - 0.5f - origin.y) * (1 << kShift)))};
}

void check_inputs(const BlobImages& in, const BlobFrame& frame, const BlobParams& p) {
  validate_blob_params(p);
  const cv::Size size = in.id.size();
  expect_image(in.id, CV_32SC1, {}, "blobs: id");
  expect_image(in.color, CV_8UC4, size, "blobs: color");
  expect_image(in.albedo, CV_8UC4, size, "blobs: albedo");
  if (blob_needs_position(frame.lighting, p)) expect_image(in.position, CV_32FC3, size, "position");
  if (!in.lines.empty()) expect_image(in.lines, CV_32FC1, size, "blobs: lines");
}

// Ground: background, then trunk and branches as the raster pass drew them (CV_32FC4, linear
// BGR and coverage).
cv::Mat paint_ground(const BlobImages& in, const BlobFrame& frame, const glm::vec3& bg_bgr) {
  const cv::Size size = in.id.size();
  const auto& lin = srgb_tables().to_linear;
  cv::Mat out(size, CV_32FC4);
  const glm::vec4 bg = frame.background;
  out.setTo(cv::Scalar(bg.b, bg.g, bg.r, bg.a));
  if (frame.branch_cluster == 0) return out;
  for_bands(size.height, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const int32_t* ids = in.id.ptr<int32_t>(y);
      const cv::Vec4b* c = in.color.ptr<cv::Vec4b>(y);
      cv::Vec4f* o = out.ptr<cv::Vec4f>(y);
      for (int x = 0; x < size.width; ++x) {
        if (static_cast<uint32_t>(ids[x]) != frame.branch_cluster) continue;
        float a = 0;
        const glm::vec3 s = surface_color(c[x], bg_bgr, lin, &a);
        for (int k = 0; k < 3; ++k)
          o[x][k] += (s[k] - o[x][k]) * a;
        o[x][3] += (1.0f - o[x][3]) * a;
      }
    }
  });
  return out;
}

// One blob's colour and lighting: its wash (the cluster's mean albedo, varied per cluster), the
// blend light's direction and each light's direction at the cluster's mean position.
struct BlobLook {
  glm::vec3 wash;  // B, G, R
  glm::vec3 blend_dir;
  std::vector<glm::vec3> light_dirs;
};

BlobLook blob_look(const ClusterMeans& m, uint32_t cluster, const std::vector<ViewLight>& lights,
                   const BlobParams& p) {
  BlobLook look;
  // Two rounds of the stream: one alone leaves neighbouring cluster ids' tones close.
  uint64_t state = static_cast<uint64_t>(p.seed) ^ (uint64_t{cluster} * 0xD1B54A32D192ED03ull);
  splitmix64(state);
  const float tone = 1.0f + p.variation * (2.0f * static_cast<float>(uniform01(state)) - 1.0f);
  look.wash =
      glm::vec3(static_cast<float>(m.albedo[0]) * tone, static_cast<float>(m.albedo[1]) * tone,
                static_cast<float>(m.albedo[2]) * tone);
  const glm::vec3 at(static_cast<float>(m.position[0]), static_cast<float>(m.position[1]),
                     static_cast<float>(m.position[2]));
  look.blend_dir = glm::normalize(glm::vec3(p.blend_right, p.blend_up, 1.0f));
  if (p.blend_light == BlendLight::Point) {
    const float d = std::max(-at.z, 1e-6f);
    look.blend_dir = toward({glm::vec3(p.blend_right * d, p.blend_up * d, 0.0f), true, {}}, at);
  }
  for (const ViewLight& l : lights)
    look.light_dirs.push_back(toward(l, at));
  return look;
}

// The outline's bounding box padded by `pad` px, clipped to the image.
cv::Rect blob_box(const std::vector<glm::vec2>& poly, int pad, const cv::Size& size) {
  glm::vec2 lo(1e30f), hi(-1e30f);
  for (const glm::vec2& q : poly) {
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  return cv::Rect(cv::Point(static_cast<int>(std::floor(lo.x)) - pad,
                            static_cast<int>(std::floor(lo.y)) - pad),
                  cv::Point(static_cast<int>(std::ceil(hi.x)) + pad + 1,
                            static_cast<int>(std::ceil(hi.y)) + pad + 1)) &
         cv::Rect(cv::Point(0, 0), size);
}

// The antialiased inside of the outline over `box` (CV_8UC1).
cv::Mat blob_inside(const std::vector<glm::vec2>& poly, const cv::Rect& box) {
  const cv::Point2f origin(static_cast<float>(box.x), static_cast<float>(box.y));
  std::vector<cv::Point> pts;
  pts.reserve(poly.size());
  for (const glm::vec2& q : poly)
    pts.push_back(fixed_point(q, origin));
  cv::Mat inside = cv::Mat::zeros(box.size(), CV_8UC1);
  cv::fillPoly(inside, std::vector<std::vector<cv::Point>>{pts}, cv::Scalar(255), cv::LINE_AA,
               kShift);
  return inside;
}

// The outline's edge stroke over `box` (CV_8UC1), `edge_px` wide and wider on the left by
// edge_left; clipped to the inside when painted.
cv::Mat blob_edge(const std::vector<glm::vec2>& poly, const cv::Rect& box, float edge_px,
                  float edge_left) {
  const cv::Point2f origin(static_cast<float>(box.x), static_cast<float>(box.y));
  cv::Mat edge = cv::Mat::zeros(box.size(), CV_8UC1);
  double area = 0;  // shoelace, image coordinates: > 0 clockwise on screen
  for (size_t i = 0; i < poly.size(); ++i) {
    const glm::vec2 a = poly[i], c = poly[(i + 1) % poly.size()];
    area += static_cast<double>(a.x) * c.y - static_cast<double>(c.x) * a.y;
  }
  const float orient = area >= 0 ? 1.0f : -1.0f;
  for (size_t i = 0; i < poly.size(); ++i) {
    const glm::vec2 a = poly[i], c = poly[(i + 1) % poly.size()];
    const glm::vec2 d = c - a;
    const float len = glm::length(d);
    const float nx = len > 0 ? orient * d.y / len : 0.0f;  // outward normal's x
    const float w = edge_px * (1.0f + edge_left * std::max(0.0f, -nx));
    // The stroke is centred on the outline and clipped to the inside: twice the width,
    // less the pixel an antialiased cv::line adds to its thickness.
    const int thickness = std::max(1, static_cast<int>(std::lround(2.0f * w)) - 1);
    cv::line(edge, fixed_point(a, origin), fixed_point(c, origin), cv::Scalar(255), thickness,
             cv::LINE_AA, kShift);
  }
  return edge;
}

// The smoothing of a blob's own leaves in its detail: px at 1024 px.
constexpr double kOwnSigma = 2.0;

// Paints blobs over an image in painter's order (Dudley §4.2-4.3), with what every blob of a
// frame shares.
class BlobPainter {
 public:
  BlobPainter(const BlobImages& in, const BlobFrame& frame, const BlobParams& p,
              const glm::vec3& bg_bgr)
      : m_in(in),
        m_frame(frame),
        m_p(p),
        m_bg(bg_bgr),
        m_means(cluster_means(in)),
        m_opacity(1.0f - p.translucency),
        m_edge_px(static_cast<float>(p.edge_width * reference_scale(in.id.size()))) {
    for (const Light& l : frame.lighting.lights)
      m_lights.push_back({light_in_view(l, frame.view), l.type == Light::Type::Point, l.color});
  }

  void paint(cv::Mat& img, const BlobOutline& b) const {
    if (b.wrap.empty() || !(b.opacity > 0.0f)) return;
    const auto mean_it = m_means.find(b.cluster);
    const ClusterMeans m = mean_it == m_means.end() ? ClusterMeans{} : mean_it->second;
    const BlobLook look = blob_look(m, b.cluster, m_lights, m_p);
    const std::vector<glm::vec2> poly = outline_polygon(b);
    const int pad = 2 + static_cast<int>(std::ceil(m_edge_px * (1.0f + m_p.edge_left)));
    const cv::Rect box = blob_box(poly, pad, img.size());
    if (box.empty()) return;
    const cv::Mat inside = blob_inside(poly, box);
    const cv::Mat edge = m_edge_px > 0 ? blob_edge(poly, box, m_edge_px, m_p.edge_left) : cv::Mat();
    const BlobShape shape =
        make_blob_shape(b.wrap.points, b.wrap.center, m_p.peaks, m_p.peak_height);
    const OwnLeaves own = own_leaves(box, b.cluster);
    for_bands(box.height, [&](int r0, int r1) {
      for (int r = r0; r < r1; ++r)
        paint_row(img, b, look, shape, box, inside, edge, own, r);
    });
  }

 private:
  // The blob's own leaves in its box, as the raster drew them, smoothed a little (kOwnSigma px
  // at 1024 px) so the detail does not flicker with the leaves and needles that land on pixel
  // centres or miss them as the view turns: their share of each pixel and their colour there
  // (linear BGR surface colour).
  struct OwnLeaves {
    cv::Mat share;  // CV_32FC1 in [0, 1]
    cv::Mat color;  // CV_32FC3
  };
  OwnLeaves own_leaves(const cv::Rect& box, uint32_t cluster) const {
    const auto& lin = srgb_tables().to_linear;
    OwnLeaves o;
    o.share = cv::Mat(box.size(), CV_32FC1, cv::Scalar(0));
    o.color = cv::Mat(box.size(), CV_32FC3, cv::Scalar(0, 0, 0));
    for (int r = 0; r < box.height; ++r) {
      const int32_t* ids = m_in.id.ptr<int32_t>(box.y + r) + box.x;
      const cv::Vec4b* col = m_in.color.ptr<cv::Vec4b>(box.y + r) + box.x;
      float* sh = o.share.ptr<float>(r);
      cv::Vec3f* c = o.color.ptr<cv::Vec3f>(r);
      for (int x = 0; x < box.width; ++x) {
        if (static_cast<uint32_t>(ids[x]) != cluster) continue;
        float coverage = 0;
        const glm::vec3 v = surface_color(col[x], m_bg, lin, &coverage);
        sh[x] = coverage;
        c[x] = coverage * cv::Vec3f(v.x, v.y, v.z);
      }
    }
    const double sigma = kOwnSigma * reference_scale(m_in.id.size());
    if (sigma >= 0.3) {
      cv::GaussianBlur(o.share, o.share, {0, 0}, sigma);
      cv::GaussianBlur(o.color, o.color, {0, 0}, sigma);
    }
    for (int r = 0; r < box.height; ++r) {
      const float* sh = o.share.ptr<float>(r);
      cv::Vec3f* c = o.color.ptr<cv::Vec3f>(r);
      for (int x = 0; x < box.width; ++x)
        c[x] = sh[x] > 1e-6f ? c[x] / sh[x] : cv::Vec3f(0, 0, 0);
    }
    return o;
  }

  // Row r of the blob's box: the shaded wash, the leaf detail blended in by the blend light
  // where the blob's own cluster is, the edge's ink, composited with the blob's opacity.
  void paint_row(cv::Mat& img, const BlobOutline& b, const BlobLook& look, const BlobShape& shape,
                 const cv::Rect& box, const cv::Mat& inside, const cv::Mat& edge,
                 const OwnLeaves& own, int r) const {
    const glm::vec3 sil = glm::min(glm::vec3(1.0f), m_p.silhouette_tone * look.wash);
    const int y = box.y + r;
    const uint8_t* ins = inside.ptr<uint8_t>(r);
    const uint8_t* eg = edge.empty() ? nullptr : edge.ptr<uint8_t>(r);
    const float* share = own.share.ptr<float>(r);
    const cv::Vec3f* own_color = own.color.ptr<cv::Vec3f>(r);
    const float* ln = m_in.lines.empty() ? nullptr : m_in.lines.ptr<float>(y);
    cv::Vec4f* o = img.ptr<cv::Vec4f>(y);
    for (int cx = 0; cx < box.width; ++cx) {
      if (!ins[cx]) continue;
      const int x = box.x + cx;
      const glm::vec3 n = blob_normal(shape, glm::vec2(x + 0.5f, y + 0.5f));
      glm::vec3 light(m_frame.lighting.ambient);
      for (size_t k = 0; k < m_lights.size(); ++k)
        light += m_lights[k].color * std::max(0.0f, glm::dot(n, look.light_dirs[k]));
      const glm::vec3 approx = look.wash * glm::vec3(light.b, light.g, light.r);
      glm::vec3 c = approx;
      if (share[cx] > 0.0f) {
        const float alpha = std::clamp(
            m_p.blend_ambient + m_p.blend_diffuse * std::max(0.0f, glm::dot(n, look.blend_dir)),
            0.0f, 1.0f);
        const float coverage = share[cx];
        glm::vec3 detail(own_color[cx][0], own_color[cx][1], own_color[cx][2]);
        if (ln) detail += (sil - detail) * ln[x];
        // Where the leaf covers the pixel partly, the wash fills the rest.
        c = approx + (approx * alpha + detail * (1.0f - alpha) - approx) * coverage;
      }
      if (eg && eg[cx]) {
        const glm::vec3 ink = glm::min(glm::vec3(1.0f), m_p.edge_tone * approx);
        c += (ink - c) * (eg[cx] / 255.0f);
      }
      const float a = ins[cx] / 255.0f * m_opacity * b.opacity;
      for (int k = 0; k < 3; ++k)
        o[x][k] += (c[k] - o[x][k]) * a;
      o[x][3] += (1.0f - o[x][3]) * a;
    }
  }

  const BlobImages& m_in;
  const BlobFrame& m_frame;
  const BlobParams& m_p;
  glm::vec3 m_bg;
  std::unordered_map<uint32_t, ClusterMeans> m_means;
  float m_opacity, m_edge_px;
  std::vector<ViewLight> m_lights;
};

// Linear BGR + coverage (CV_32FC4) as 8-bit sRGB BGRA.
cv::Mat encode_bgra(const cv::Mat& out) {
  const auto& tables = srgb_tables();
  cv::Mat result(out.size(), CV_8UC4);
  for_bands(out.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const cv::Vec4f* o = out.ptr<cv::Vec4f>(y);
      cv::Vec4b* r = result.ptr<cv::Vec4b>(y);
      for (int x = 0; x < out.cols; ++x) {
        for (int k = 0; k < 3; ++k)
          r[x][k] = encode_srgb(tables, o[x][k]);
        r[x][3] = cv::saturate_cast<uint8_t>(std::lround(o[x][3] * 255.0f));
      }
    }
  });
  return result;
}

}  // namespace

cv::Mat paint_blobs(const BlobImages& in, const BlobSet& blobs, const BlobFrame& frame,
                    const BlobParams& p) {
  check_inputs(in, frame, p);
  const glm::vec3 bg_bgr(frame.background.b, frame.background.g, frame.background.r);
  cv::Mat out = paint_ground(in, frame, bg_bgr);
  const cv::Mat ground = blobs.fade > 0.0f ? out.clone() : cv::Mat();
  const BlobPainter painter(in, frame, p, bg_bgr);
  for (size_t i : blobs.order)
    painter.paint(out, blobs.blobs[i]);
  if (blobs.fade > 0.0f && blobs.next_order != blobs.order) {
    // Dudley §5.1: cross-fade to the next keyframe's order instead of popping.
    cv::Mat next = ground.clone();
    for (size_t i : blobs.next_order)
      painter.paint(next, blobs.blobs[i]);
    cv::addWeighted(out, 1.0 - blobs.fade, next, blobs.fade, 0.0, out);
  }
  return encode_bgra(out);
}

}  // namespace sylva

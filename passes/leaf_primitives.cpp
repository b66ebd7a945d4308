#include "passes/leaf_primitives.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <tuple>

#include "core/error.h"
#include "npr/sample_shadow.h"
#include "passes/crack_chains.h"
#include "passes/ink_working.h"
#include "passes/pass_common.h"
#include "passes/tone_rank.h"

namespace sylva {

void bind_leaf_params(ParamSet& set, LeafParams& p) {
  set.add_choice("leaves.shape", p.shape, {{"auto", LeafShape::Auto}, {"disc", LeafShape::Disc}},
                 "the foliage primitives' shape: each leaf's own projected shape (auto: "
                 "needles and willow leaves long, broad leaves round) or round");
  set.add_float("leaves.size", p.size, 0.1, 8.0, "x ink.detail",
                "the smallest foliage primitive's diameter (larger: fewer, bigger clumps)");
  set.add_float("leaves.depth_step", p.depth_step, 0.001, 1.0, "share of the plant's depth",
                "a primitive is outlined where it stands this far in front of what is behind "
                "it (at ink.detail 10; in proportion to the detail)");
  set.add_float("leaves.fade", p.fade, 0.0, 0.95, "share of the step",
                "band on either side of the depth step over which outlines fade in");
  set.add_float("leaves.lit", p.lit, 0.0, 1.0, "share of the plant",
                "the lightest share of the plant drawn as lit (fewer outlines)");
  set.add_float("leaves.lit_step", p.lit_step, 1.0, 20.0, "ratio",
                "the depth step is this many times larger where lit");
  set.add_float("leaves.shadow", p.shadow, 0.0, 1.0, "",
                "how much the key light's shadow through the crown darkens the tone (0 = the "
                "shaded colour alone)");
  set.add_float("leaves.shadow_depth", p.shadow_depth, 0.02, 2.0, "share of the scene's radius",
                "how deep into the crown the key light reaches (it falls to 1/e over this "
                "behind the first leaves)");
  set.add_float("leaves.black", p.black, 0.0, 1.0, "share of the plant",
                "the darkest share of the plant filled black (0 = none)");
  set.add_float("leaves.black_fade", p.black_fade, 0.01, 0.5, "share of the plant",
                "tone over which a primitive's black fill grows from a dot to all of it");
}

namespace {

// One frame's view-facing ellipse, at the working resolution.
struct Primitive {
  cv::Point2f c;         // centre, working px
  float cos_t, sin_t;    // the major axis's direction
  float a, b;            // semi-axes, working px, a >= b > 0
  float depth;           // view depth of the piece's centre, scene units
  glm::vec3 world;       // the piece's centre, world space
  float area = 0;        // the piece's leaves' area, scene units²
  float extent = 0;      // the depth extent of the plant it belongs to (plant_extents)
  float rank = 0;        // tone rank at the centre
  uint32_t cluster = 0;  // the piece's leaf cluster
  // The quadratic form d^T Q d <= 1 of the ellipse about c.
  double qa() const { return cos_t * cos_t / (a * a) + sin_t * sin_t / (b * b); }
  double qb() const { return cos_t * sin_t * (1.0 / (a * a) - 1.0 / (b * b)); }
  double qc() const { return sin_t * sin_t / (a * a) + cos_t * cos_t / (b * b); }
};

// Where a world point lands, in output px; false behind the eye.
bool to_image(const glm::mat4& view_proj, const glm::vec3& p, cv::Size out, glm::vec2& at) {
  const glm::vec4 clip = view_proj * glm::vec4(p, 1.0f);
  if (!(clip.w > 0.0f)) return false;
  at = {(clip.x / clip.w * 0.5f + 0.5f) * float(out.width),
        (0.5f - clip.y / clip.w * 0.5f) * float(out.height)};
  return std::isfinite(at.x) && std::isfinite(at.y);
}

// The piece's ellipse: its covariance carried to the image by the projection's Jacobian at its
// centre (a uniform disc of radius r has variance r^2 / 4 along every axis), no smaller than
// `least` semi-axis (working px), round for LeafShape::Disc; false when it does not land in front
// of the eye or near the frame.
bool make_primitive(const LeafPiece& piece, const glm::mat4& view, const glm::mat4& view_proj,
                    cv::Size out, double f, float h, LeafShape shape, float least, Primitive& p) {
  glm::vec2 c;
  if (!to_image(view_proj, piece.centre, out, c)) return false;
  float jac[2][3];
  for (int k = 0; k < 3; ++k) {
    glm::vec3 q = piece.centre;
    q[k] += h;
    glm::vec2 d;
    if (!to_image(view_proj, q, out, d)) return false;
    jac[0][k] = (d.x - c.x) / (h * float(f));
    jac[1][k] = (d.y - c.y) / (h * float(f));
  }
  const float* v = piece.cov;
  const float s3[3][3] = {{v[0], v[1], v[2]}, {v[1], v[3], v[4]}, {v[2], v[4], v[5]}};
  double s2[2][2] = {{0, 0}, {0, 0}};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          s2[i][j] += double(jac[i][k]) * s3[k][l] * double(jac[j][l]);
  const double mean = 0.5 * (s2[0][0] + s2[1][1]);
  const double spread = std::hypot(0.5 * (s2[0][0] - s2[1][1]), s2[0][1]);
  const double angle = 0.5 * std::atan2(2.0 * s2[0][1], s2[0][0] - s2[1][1]);
  float a = float(2.0 * std::sqrt(std::max(0.0, mean + spread)));
  float b = float(2.0 * std::sqrt(std::max(0.0, mean - spread)));
  if (shape == LeafShape::Disc) {
    a = b = std::max(std::sqrt(a * b), least);
  } else {
    // Small elements keep up to 2:1 of their elongation: a needle stays a short stroke.
    a = std::max(a, least);
    b = std::clamp(b, 0.5f * least, a);
  }
  p.c = {c.x / float(f), c.y / float(f)};
  const float reach = a + 2.0f;
  if (p.c.x < -reach || p.c.y < -reach || p.c.x > float(out.width) / float(f) + reach ||
      p.c.y > float(out.height) / float(f) + reach || !std::isfinite(a))
    return false;
  p.cos_t = float(std::cos(angle));
  p.sin_t = float(std::sin(angle));
  p.a = a;
  p.b = std::max(b, 0.25f);
  p.depth = -(view * glm::vec4(piece.centre, 1.0f)).z;
  p.world = piece.centre;
  p.area = piece.area;
  p.cluster = piece.cluster;
  return p.depth > 0.0f;
}

// Calls span(y, x0, x1) for each row of pixels whose centres lie in the ellipse `p` scaled by
// `k`, the centres x0..x1 (inclusive), clipped to `size`.
template <class Span>
void ellipse_spans(const Primitive& p, float k, cv::Size size, int y_from, int y_to, Span span) {
  const double a = p.a * k, b = p.b * k;
  if (!(a > 0.0) || !(b > 0.0)) return;
  const double c2 = p.cos_t * p.cos_t, s2 = p.sin_t * p.sin_t;
  const double qa = c2 / (a * a) + s2 / (b * b),
               qb = p.cos_t * p.sin_t * (1 / (a * a) - 1 / (b * b)),
               qc = s2 / (a * a) + c2 / (b * b);
  const double ry = std::sqrt(a * a * s2 + b * b * c2);
  const int y0 = std::max(y_from, int(std::ceil(p.c.y - ry - 0.5))),
            y1 = std::min(y_to - 1, int(std::floor(p.c.y + ry - 0.5)));
  for (int y = y0; y <= y1; ++y) {
    const double dy = y + 0.5 - p.c.y;
    const double disc = qb * qb * dy * dy - qa * (qc * dy * dy - 1.0);
    if (disc < 0.0) continue;
    const double r = std::sqrt(disc);
    const int x0 = std::max(0, int(std::ceil(p.c.x + (-qb * dy - r) / qa - 0.5)));
    const int x1 = std::min(size.width - 1, int(std::floor(p.c.x + (-qb * dy + r) / qa - 0.5)));
    if (x0 <= x1) span(y, x0, x1);
  }
}

// The wood seen (passes/seen_wood.h), which no leaf hides, at the working resolution: in front
// of every primitive.
void paint_wood(const SeenWood& seen, double f, LeafLayer& out) {
  if (seen.mask.empty()) return;
  for (int y = 0; y < seen.mask.rows; ++y)
    for (int x = 0; x < seen.mask.cols; ++x) {
      if (!seen.mask.at<uint8_t>(y, x)) continue;
      const float z = seen.depth.at<float>(y, x);
      const int u = std::min(out.front.cols - 1, int(x / f)),
                v = std::min(out.front.rows - 1, int(y / f));
      out.front.at<int>(v, u) = kWoodFront;
      float& d = out.depth.at<float>(v, u);
      d = std::min(d, z);
    }
}

// Each primitive a flat solid at its depth (a z-buffer; the lower index wins a tie, so the
// result does not depend on the threads).
void paint_primitives(const std::vector<Primitive>& prims, LeafLayer& out) {
  const cv::Size size = out.front.size();
  for_bands(size.height, [&](int y0, int y1) {
    for (size_t i = 0; i < prims.size(); ++i)
      ellipse_spans(prims[i], 1.0f, size, y0, y1, [&](int y, int x0, int x1) {
        int* front = out.front.ptr<int>(y);
        float* depth = out.depth.ptr<float>(y);
        for (int x = x0; x <= x1; ++x)
          if (front[x] != kWoodFront && prims[i].depth < depth[x]) {
            depth[x] = prims[i].depth;
            front[x] = int(i + 1);
          }
      });
  });
}

float smoothstep(float e0, float e1, float x) {
  if (e1 <= e0) return x >= e1 ? 1.0f : 0.0f;
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

struct ArcStyle {
  float step = 0;     // the depth step (scene units) at half-shadow
  float fade = 0.5f;  // leaves.fade
  float lit = 0, lit_step = 1;
  float width[2] = {1, 1};  // px: interior (Foliage), against the paper (Silhouette)
  float tone[2] = {1, 1};
  bool on[2] = {true, true};
  float inset = 0;        // output px the line lies inside the primitive's edge
  size_t min_points = 2;  // the shortest open arc drawn, in points (about a working px apart)
};

struct ArcPoint {
  glm::vec2 p;   // output px
  float weight;  // 0 = not drawn
  int cls;       // 0 interior, 1 against the paper
};

// The depth step that outlines primitive `p`: larger where it is lit.
float step_of(const Primitive& p, const ArcStyle& s) {
  const float lit = 1.0f - smoothstep(s.lit - 0.05f, s.lit + 0.05f, p.rank);
  return s.step * p.extent * (1.0f + (s.lit_step - 1.0f) * lit);
}

int front_at(const cv::Mat& front, cv::Point2f q) {
  const int x = int(std::floor(q.x)), y = int(std::floor(q.y));
  if (x < 0 || y < 0 || x >= front.cols || y >= front.rows) return 0;
  return front.at<int>(y, x);
}

// Points around primitive i's outline, about one per working px, each weighted by how far the
// primitive stands in front of what lies just outside it there (0 where it is hidden).
std::vector<ArcPoint> arc_points(const std::vector<Primitive>& prims, size_t i,
                                 const LeafLayer& layer, const ArcStyle& s) {
  const Primitive& p = prims[i];
  const double perimeter = std::numbers::pi * std::sqrt(2.0 * (p.a * p.a + p.b * p.b));
  const int n = std::clamp(int(std::ceil(perimeter)), 12, 256);
  const float step = step_of(p, s);
  const double qa = p.qa(), qb = p.qb(), qc = p.qc();
  std::vector<ArcPoint> pts(static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) {
    const double phi = 2.0 * std::numbers::pi * j / n;
    const double lx = p.a * std::cos(phi), ly = p.b * std::sin(phi);
    const cv::Point2f d(float(p.cos_t * lx - p.sin_t * ly), float(p.sin_t * lx + p.cos_t * ly));
    cv::Point2f g(float(qa * d.x + qb * d.y), float(qb * d.x + qc * d.y));  // outward
    g *= 1.0f / std::max(1e-12f, std::hypot(g.x, g.y));
    const cv::Point2f q = p.c + d;
    ArcPoint& a = pts[size_t(j)];
    // The line lies on the primitive's side of its edge, over what it outlines.
    const cv::Point2f on = q * float(layer.factor) - s.inset * g;
    a.p = {on.x, on.y};
    a.weight = 0.0f;
    a.cls = 0;
    if (front_at(layer.front, q - 0.75f * g) != int(i + 1)) continue;
    const cv::Point2f o = q + 0.75f * g;
    const int behind = front_at(layer.front, o);
    if (behind == 0) {
      a.weight = 1.0f;
      a.cls = 1;
      continue;
    }
    if (behind == int(i + 1)) continue;
    const int x = std::clamp(int(std::floor(o.x)), 0, layer.depth.cols - 1),
              y = std::clamp(int(std::floor(o.y)), 0, layer.depth.rows - 1);
    const float gap = layer.depth.at<float>(y, x) - p.depth;
    a.weight = smoothstep(step * (1.0f - s.fade), step * (1.0f + s.fade), gap);
  }
  return pts;
}

// The runs of drawn points, each a stroke of its class whose width follows the weight (so an
// outline thins out as its step nears the threshold).
void add_arcs(const std::vector<ArcPoint>& pts, const ArcStyle& s, std::vector<Stroke> (&out)[2]) {
  const size_t n = pts.size();
  auto drawn = [&](size_t j) { return pts[j].weight > 0.02f && s.on[pts[j].cls]; };
  size_t start = n;
  for (size_t j = 0; j < n; ++j)
    if (!drawn(j) || pts[j].cls != pts[(j + n - 1) % n].cls) {
      start = j;
      break;
    }
  auto emit = [&](std::vector<size_t>& run, bool closed) {
    const int cls = run.empty() ? 0 : pts[run[0]].cls;
    // An open interior arc shorter than min_points (the detail) is dust, not a leaf's edge: it
    // thins out from there to nothing at half of it, so it fades rather than vanishes as it
    // shortens. The silhouette keeps every arc: its pieces join into the plant's outline.
    const float keep =
        closed || cls == 1
            ? 1.0f
            : std::clamp(2.0f * float(run.size()) / float(std::max<size_t>(2, s.min_points)) - 1.0f,
                         0.0f, 1.0f);
    if (run.size() >= (closed ? 3u : 2u) && keep > 0.0f) {
      Stroke st;
      st.cls = cls == 1 ? LineClass::Silhouette : LineClass::Foliage;
      st.opacity = s.tone[cls];
      st.closed = closed;
      st.width = s.width[cls];
      bool even = keep >= 1.0f;
      for (size_t j : run) {
        st.points.push_back(pts[j].p);
        st.widths.push_back(s.width[cls] * keep * std::min(1.0f, pts[j].weight));
        even = even && pts[j].weight >= 1.0f;
      }
      if (even) st.widths.clear();
      out[cls].push_back(std::move(st));
    }
    run.clear();
  };
  std::vector<size_t> run;
  if (start == n) {  // drawn all round, one class: a closed outline
    for (size_t j = 0; j < n; ++j)
      run.push_back(j);
    emit(run, true);
    return;
  }
  for (size_t k = 0; k < n; ++k) {
    const size_t j = (start + k) % n;
    if (!drawn(j) || (!run.empty() && pts[j].cls != pts[run.back()].cls)) emit(run, false);
    if (drawn(j)) run.push_back(j);
  }
  emit(run, false);
}

// The deep shadow's black: each primitive's visible part within its ellipse scaled by its fill
// (0..1 by rank), traced as filled regions.
std::vector<Stroke> black_fills(const std::vector<Primitive>& prims, const LeafLayer& layer,
                                const LeafParams& p, float opacity) {
  std::vector<Stroke> fills;
  const float black = p.black;
  if (black <= 0.0f) return fills;
  cv::Mat dark(layer.front.size(), CV_8UC1, cv::Scalar(0));
  const float from = 1.0f - black;
  for (size_t i = 0; i < prims.size(); ++i) {
    const float k = smoothstep(from, from + p.black_fade, prims[i].rank);
    // A core under a working pixel across is a speck, not shadow.
    if (k * prims[i].b < 0.5f) continue;
    ellipse_spans(prims[i], k, dark.size(), 0, dark.rows, [&](int y, int x0, int x1) {
      const int* front = layer.front.ptr<int>(y);
      uint8_t* row = dark.ptr<uint8_t>(y);
      for (int x = x0; x <= x1; ++x)
        if (front[x] == int(i + 1)) row[x] = 255;
    });
  }
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> tree;
  cv::findContours(dark, contours, tree, cv::RETR_CCOMP, cv::CHAIN_APPROX_NONE);
  auto ring = [&](const std::vector<cv::Point>& c) {
    Polyline line;
    line.closed = true;
    for (const cv::Point& q : c)
      line.points.emplace_back(float(q.x) + 0.5f, float(q.y) + 0.5f);
    line = simplify_polyline(smooth_polyline(line, 0.7), 0.3);
    std::vector<glm::vec2> out;
    for (const cv::Point2f& q : line.points)
      out.emplace_back(q.x * float(layer.factor), q.y * float(layer.factor));
    return out;
  };
  for (size_t i = 0; i < contours.size(); ++i) {
    if (tree[i][3] >= 0 || contours[i].size() < 3) continue;  // holes go with their outer ring
    Stroke s;
    s.cls = LineClass::Shadow;
    s.filled = true;
    s.closed = true;
    s.opacity = opacity;
    s.points = ring(contours[i]);
    for (int h = tree[i][2]; h >= 0; h = tree[size_t(h)][0])
      if (contours[size_t(h)].size() >= 3) s.holes.push_back(ring(contours[size_t(h)]));
    fills.push_back(std::move(s));
  }
  return fills;
}

// The pieces merged into clumps of one leaf cluster within one cell of `cell` scene units (a
// grid fixed in world space, so a clump keeps its leaves as the view turns): the clump's area,
// centre and covariance from its pieces' moments. Pieces of a cut element stay as they are
// (first). cell <= 0 keeps the pieces.
std::vector<LeafPiece> clumps(const LeafPieces& pieces, double cell) {
  if (!(cell > 0.0) || !std::isfinite(cell)) return pieces.pieces;
  struct Key {
    uint32_t instance, cluster;
    int64_t x, y, z;
    auto tie() const { return std::tie(instance, cluster, x, y, z); }
  };
  std::vector<std::pair<Key, uint32_t>> keyed;
  keyed.reserve(pieces.size());
  std::vector<LeafPiece> out;
  for (size_t i = 0; i < pieces.size(); ++i) {
    const LeafPiece& q = pieces.pieces[i];
    if (q.cut) {
      out.push_back(q);
      continue;
    }
    auto c = [&](float v) { return int64_t(std::floor(double(v) / cell)); };
    keyed.push_back(
        {{q.instance, q.cluster, c(q.centre.x), c(q.centre.y), c(q.centre.z)}, uint32_t(i)});
  }
  std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
    return a.first.tie() < b.first.tie() || (a.first.tie() == b.first.tie() && a.second < b.second);
  });
  for (size_t begin = 0; begin < keyed.size();) {
    size_t end = begin + 1;
    while (end < keyed.size() && keyed[end].first.tie() == keyed[begin].first.tie())
      ++end;
    const LeafPiece& first = pieces.pieces[keyed[begin].second];
    const glm::dvec3 origin(first.centre);
    double w = 0.0, m2[6] = {0, 0, 0, 0, 0, 0};
    glm::dvec3 m(0.0);
    for (size_t k = begin; k < end; ++k) {
      const LeafPiece& q = pieces.pieces[keyed[k].second];
      const double a = q.area;
      const glm::dvec3 c = glm::dvec3(q.centre) - origin;
      w += a;
      m += a * c;
      const double cc[6] = {c.x * c.x, c.x * c.y, c.x * c.z, c.y * c.y, c.y * c.z, c.z * c.z};
      for (int j = 0; j < 6; ++j)
        m2[j] += a * (double(q.cov[j]) + cc[j]);
    }
    LeafPiece clump = first;
    const glm::dvec3 c = m / w;
    const double cc[6] = {c.x * c.x, c.x * c.y, c.x * c.z, c.y * c.y, c.y * c.z, c.z * c.z};
    for (int j = 0; j < 6; ++j)
      clump.cov[j] = float(m2[j] / w - cc[j]);
    for (int j : {0, 3, 5})
      clump.cov[j] = std::max(clump.cov[j], 0.0f);
    clump.centre = glm::vec3(origin + c);
    clump.area = float(w);
    out.push_back(clump);
    begin = end;
  }
  return out;
}

std::vector<Primitive> frame_primitives(const LeafImages& in, const LeafParams& p, double f,
                                        float least, double cell) {
  std::vector<Primitive> prims;
  if (!in.pieces) return prims;
  const glm::mat4 view_proj = in.camera.proj * in.camera.view;
  const float h = std::max(1e-6f, 0.05f * in.pieces->cell);
  const std::vector<LeafPiece> merged = clumps(*in.pieces, cell);
  prims.reserve(merged.size());
  for (const LeafPiece& piece : merged) {
    Primitive q;
    if (make_primitive(piece, in.camera.view, view_proj, in.color.size(), f, h, p.shape, least, q))
      prims.push_back(q);
  }
  return prims;
}

// The light reaching each primitive: the shaded colour's darkness around its centre (Luft's
// realigned normals and ka) and the key light's share reaching its centre through the crown
// (npr/sample_shadow.h), as one darkness; each primitive's rank among the plant's, weighted by
// the pixels it shows; the layer's rank image, clusters, centres and depth range.
void rank_primitives(const LeafImages& in, const LeafParams& p, double sigma,
                     std::vector<Primitive>& prims, LeafLayer& layer) {
  const cv::Size work = layer.front.size();
  const ToneRank tone = tone_rank(in.color, work, sigma);
  SampleShadow shadow;
  if (in.light.on && in.samples && p.shadow > 0.0f && !in.light.sphere.empty())
    shadow = sample_shadow_map(*in.samples, in.light.sphere, in.light.toward, in.light.point,
                               kShadowMapSize, p.shadow_depth);
  std::vector<double> shown(prims.size(), 0.0);
  for (int y = 0; y < work.height; ++y)
    for (int x = 0; x < work.width; ++x)
      if (const int f = layer.front.at<int>(y, x); f > 0) shown[size_t(f - 1)] += 1.0;
  std::vector<std::pair<float, size_t>> dark(prims.size());
  double total = 0.0;
  for (size_t i = 0; i < prims.size(); ++i) {
    const float colour = tone.empty() ? 0.0f : tone.dark_near(prims[i].c);
    const float light = 1.0f - p.shadow * (1.0f - light_reaching(shadow, prims[i].world));
    dark[i] = {1.0f - (1.0f - colour) * light, i};
    total += shown[i];
  }
  std::sort(dark.begin(), dark.end());
  double below = 0.0;
  for (const auto& [d, i] : dark) {
    prims[i].rank = total > 0.0 ? float((below + 0.5 * shown[i]) / total) : 0.0f;
    below += shown[i];
  }
  layer.rank = cv::Mat(work, CV_32FC1, cv::Scalar(0));
  for (int y = 0; y < work.height; ++y)
    for (int x = 0; x < work.width; ++x)
      if (const int f = layer.front.at<int>(y, x); f > 0)
        layer.rank.at<float>(y, x) = prims[size_t(f - 1)].rank;
  layer.near = prims.empty() ? 0.0f : std::numeric_limits<float>::max();
  layer.far = 0.0f;
  for (const Primitive& q : prims) {
    layer.near = std::min(layer.near, q.depth);
    layer.far = std::max(layer.far, q.depth);
    layer.clusters.push_back(q.cluster);
    layer.centres.push_back(q.c);
    layer.areas.push_back(q.area);
  }
}

// Each primitive's plant depth extent: the depth range of the primitives of its plant as the
// picture shows it (a connected piece of the primitive buffer), so several plants side by side (a
// group of ferns) each get their own step; a primitive whose centre is hidden or out of the
// frame takes the whole picture's.
void plant_extents(const LeafLayer& layer, std::vector<Primitive>& prims) {
  cv::Mat labels;
  const int n = cv::connectedComponents(layer.front != 0, labels, 8, CV_32S);
  std::vector<float> lo(size_t(n), std::numeric_limits<float>::max()), hi(size_t(n), 0.0f);
  std::vector<int> of(prims.size(), 0);
  for (size_t i = 0; i < prims.size(); ++i) {
    const int x = int(std::floor(prims[i].c.x)), y = int(std::floor(prims[i].c.y));
    if (x < 0 || y < 0 || x >= labels.cols || y >= labels.rows) continue;
    const int l = labels.at<int>(y, x);
    of[i] = l;
    lo[size_t(l)] = std::min(lo[size_t(l)], prims[i].depth);
    hi[size_t(l)] = std::max(hi[size_t(l)], prims[i].depth);
  }
  const float whole = layer.far - layer.near;
  for (size_t i = 0; i < prims.size(); ++i)
    prims[i].extent = of[i] > 0 ? hi[size_t(of[i])] - lo[size_t(of[i])] : whole;
}

}  // namespace

LeafLayer leaf_layer(const LeafImages& in, const LeafParams& p, const InkLineParams& lines,
                     const EdgeParams& edges) {
  const cv::Size size = in.color.size();
  const double scale = reference_scale(size);
  const double detail = lines.detail * scale;  // px
  const double least_px = p.size * detail;     // the smallest primitive's diameter, px
  LeafLayer layer;
  layer.factor = std::max(1.0, least_px / kPrimitivePx);
  const cv::Size work(std::max(1, int(std::lround(size.width / layer.factor))),
                      std::max(1, int(std::lround(size.height / layer.factor))));
  layer.drawing.size = size;
  layer.drawing.color = edges.color;
  layer.front = cv::Mat(work, CV_32SC1, cv::Scalar(0));
  layer.depth = cv::Mat(work, CV_32FC1, cv::Scalar(std::numeric_limits<float>::infinity()));
  paint_wood(in.wood, layer.factor, layer);
  std::vector<Primitive> prims =
      frame_primitives(in, p, layer.factor, float(std::max(0.5, 0.5 * least_px / layer.factor)),
                       least_px * in.units_per_px);
  paint_primitives(prims, layer);
  rank_primitives(in, p, std::max(1.0, detail / layer.factor), prims, layer);
  plant_extents(layer, prims);
  ArcStyle s;
  s.step = p.depth_step * float(std::max(lines.detail, 0.5f) / 10.0f);
  s.fade = p.fade;
  s.lit = p.lit;
  s.lit_step = p.lit_step;
  const LineClassParams* cls[2] = {&lines.foliage, &lines.silhouette};
  for (int k = 0; k < 2; ++k) {
    s.width[k] = float(std::max<double>(edges.min_width, cls[k]->width * scale));
    s.tone[k] = cls[k]->tone;
    s.on[k] = cls[k]->on && cls[k]->tone > 0.0f;
  }
  s.inset = 0.5f * s.width[0];
  s.min_points = size_t(std::max(2.0, detail / layer.factor));
  std::vector<Stroke> arcs[2];
  for (size_t i = 0; i < prims.size(); ++i)
    add_arcs(arc_points(prims, i, layer, s), s, arcs);
  layer.drawing.strokes = black_fills(prims, layer, p, 1.0f);
  for (int k = 0; k < 2; ++k) {
    // Arcs of neighbouring primitives that meet become one path (an outline of many leaves).
    chain_strokes(arcs[k], 1.5f * float(layer.factor));
    for (Stroke& st : arcs[k])
      layer.drawing.strokes.push_back(std::move(st));
  }
  return layer;
}

Handle<LeafLayer> add_leaf_layer_pass(RenderGraph& g, const LeafResources& in, const LeafParams& p,
                                      const InkLineParams& lines, const EdgeParams& edges) {
  SYLVA_CHECK(in.pieces.valid() && in.color.valid() && in.depth.valid(),
              "the leaf layer needs the leaf pieces, color and depth resources");
  std::vector<ResourceRef> reads = {in.pieces, in.color, in.depth};
  if (in.wood.valid()) reads.push_back(in.wood);
  if (in.samples.valid()) reads.push_back(in.samples);
  const auto out = g.resource<LeafLayer>("leaf-layer");
  g.add_pass("leaf-layer", reads, {out}, [=](PassContext& ctx) {
    LeafImages images;
    images.pieces = ctx.read<std::shared_ptr<const LeafPieces>>(in.pieces);
    images.camera = in.camera;
    images.units_per_px = in.units_per_px;
    images.color = ctx.read<cv::Mat>(in.color);
    images.depth = ctx.read<cv::Mat>(in.depth);
    if (in.wood.valid()) images.wood = ctx.read<SeenWood>(in.wood);
    if (in.samples.valid())
      images.samples = ctx.read<std::shared_ptr<const SurfaceSamples>>(in.samples);
    images.light = in.light;
    ctx.write(out, leaf_layer(images, p, lines, edges));
  });
  return out;
}

Handle<StrokeDrawing> add_leaf_strokes_pass(RenderGraph& g, Handle<LeafLayer> layer) {
  const auto out = g.resource<StrokeDrawing>("leaf-strokes");
  g.add_pass("leaf-strokes", {layer}, {out},
             [=](PassContext& ctx) { ctx.write(out, ctx.read<LeafLayer>(layer).drawing); });
  return out;
}

}  // namespace sylva

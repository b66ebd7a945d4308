#include "passes/leaf_primitives.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <tuple>

#include "core/error.h"
#include "npr/sample_shadow.h"
#include "passes/crack_chains.h"
#include "passes/ink_working.h"
#include "passes/leaf_outlines.h"
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

// The wood seen (passes/seen_wood.h), which no leaf hides, at the working resolution: in front
// of every primitive.
void paint_wood(const SeenWood& seen, double f, LeafLayer& out) {
  if (seen.mask.empty()) return;
  for (int y = 0; y < seen.mask.rows; ++y) {
    const uint8_t* wood = seen.mask.ptr<uint8_t>(y);
    const float* z = seen.depth.ptr<float>(y);
    const int v = std::min(out.front.rows - 1, int(y / f));
    int* front = out.front.ptr<int>(v);
    float* depth = out.depth.ptr<float>(v);
    for (int x = 0; x < seen.mask.cols; ++x) {
      if (!wood[x]) continue;
      const int u = std::min(out.front.cols - 1, int(x / f));
      front[u] = kWoodFront;
      depth[u] = std::min(depth[u], z[x]);
    }
  }
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

// clumps(pieces, cell), made once per cell size (LeafPieces::clump_memo).
std::shared_ptr<const std::vector<LeafPiece>> kept_clumps(const LeafPieces& pieces, double cell) {
  LeafPieces::ClumpMemo& memo = pieces.clump_memo;
  const std::lock_guard<std::mutex> lock(memo.mutex);
  if (!memo.clumps || memo.size != cell) {
    memo.clumps = std::make_shared<const std::vector<LeafPiece>>(clumps(pieces, cell));
    memo.size = cell;
  }
  return memo.clumps;
}

// The frame's size: the colour's, or the camera's before there is one.
cv::Size frame_size(const LeafImages& in) {
  return in.color.empty() ? cv::Size(in.camera.width, in.camera.height) : in.color.size();
}

std::vector<Primitive> frame_primitives(const LeafImages& in, const LeafParams& p, double f,
                                        float least, double cell) {
  std::vector<Primitive> prims;
  if (!in.pieces) return prims;
  const glm::mat4 view_proj = in.camera.proj * in.camera.view;
  const float h = std::max(1e-6f, 0.05f * in.pieces->cell);
  const std::shared_ptr<const std::vector<LeafPiece>> kept = kept_clumps(*in.pieces, cell);
  const std::vector<LeafPiece>& merged = *kept;
  std::vector<Primitive> all(merged.size());
  std::vector<uint8_t> made(merged.size(), 0);
  cv::parallel_for_(cv::Range(0, int(merged.size())), [&](const cv::Range& r) {
    for (int i = r.start; i < r.end; ++i)
      made[size_t(i)] = make_primitive(merged[size_t(i)], in.camera.view, view_proj, frame_size(in),
                                       f, h, p.shape, least, all[size_t(i)]);
  });
  prims.reserve(merged.size());
  for (size_t i = 0; i < all.size(); ++i)
    if (made[i]) prims.push_back(all[i]);
  return prims;
}

// The key light's share reaching each primitive's centre through the crown
// (npr/sample_shadow.h), weighted by leaves.shadow: 1 = all of it.
void light_primitives(const LeafImages& in, const LeafParams& p, LeafFrame& frame) {
  SampleShadow shadow;
  if (in.light.on && in.samples && p.shadow > 0.0f && !in.light.sphere.empty())
    shadow = sample_shadow_map(*in.samples, in.light.sphere, in.light.toward, in.light.point,
                               kShadowMapSize, p.shadow_depth);
  const std::vector<Primitive>& prims = frame.prims;
  frame.light.assign(prims.size(), 1.0f);
  cv::parallel_for_(cv::Range(0, int(prims.size())), [&](const cv::Range& r) {
    for (int i = r.start; i < r.end; ++i)
      frame.light[size_t(i)] =
          1.0f - p.shadow * (1.0f - light_reaching(shadow, prims[size_t(i)].world));
  });
}

// Each primitive's rank among the plant's by its darkness, weighted by the pixels it shows; the
// layer's rank image.
void rank_primitives(const std::vector<float>& darkness, std::vector<Primitive>& prims,
                     LeafLayer& layer) {
  const cv::Size work = layer.front.size();
  std::vector<double> shown(prims.size(), 0.0);
  for (int y = 0; y < work.height; ++y) {
    const int* front = layer.front.ptr<int>(y);
    for (int x = 0; x < work.width; ++x)
      if (front[x] > 0) shown[size_t(front[x] - 1)] += 1.0;
  }
  std::vector<std::pair<float, size_t>> dark(prims.size());
  for (size_t i = 0; i < prims.size(); ++i)
    dark[i] = {darkness[i], i};
  double total = 0.0;
  for (size_t i = 0; i < prims.size(); ++i)
    total += shown[i];
  sort_unit_keys(dark);
  double below = 0.0;
  for (const auto& [d, i] : dark) {
    prims[i].rank = total > 0.0 ? float((below + 0.5 * shown[i]) / total) : 0.0f;
    below += shown[i];
  }
  layer.rank = cv::Mat(work, CV_32FC1, cv::Scalar(0));
  for (int y = 0; y < work.height; ++y) {
    const int* front = layer.front.ptr<int>(y);
    float* rank = layer.rank.ptr<float>(y);
    for (int x = 0; x < work.width; ++x)
      if (front[x] > 0) rank[x] = prims[size_t(front[x] - 1)].rank;
  }
}

// The primitives' depth range, clusters, centres and areas, into the layer.
void primitive_ranges(const std::vector<Primitive>& prims, LeafLayer& layer) {
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

void paint_primitives(const std::vector<Primitive>& prims, LeafLayer& out) {
  const cv::Size size = out.front.size();
  // Each band of rows visits every primitive: their rows, found once, pass over the others.
  std::vector<std::pair<int, int>> rows(prims.size());
  for (size_t i = 0; i < prims.size(); ++i)
    rows[i] = ellipse_rows(prims[i], 1.0f);
  for_bands(size.height, [&](int y0, int y1) {
    for (size_t i = 0; i < prims.size(); ++i) {
      if (rows[i].second < y0 || rows[i].first >= y1) continue;
      ellipse_spans(prims[i], 1.0f, size, y0, y1, [&](int y, int x0, int x1) {
        int* front = out.front.ptr<int>(y);
        float* depth = out.depth.ptr<float>(y);
        for (int x = x0; x <= x1; ++x)
          if (front[x] != kWoodFront && prims[i].depth < depth[x]) {
            depth[x] = prims[i].depth;
            front[x] = int(i + 1);
          }
      });
    }
  });
}

std::vector<Primitive> project_primitives(const LeafImages& in, LeafShape shape, double f,
                                          float least, double cell) {
  LeafParams p;
  p.shape = shape;
  return frame_primitives(in, p, f, least, cell);
}

LeafFrame leaf_frame(const LeafImages& in, const LeafParams& p, const InkLineParams& lines) {
  const cv::Size size = frame_size(in);
  const double detail = lines.detail * reference_scale(size);  // px
  const double least_px = p.size * detail;  // the smallest primitive's diameter, px
  LeafFrame frame;
  frame.size = size;
  frame.factor = std::max(1.0, least_px / kPrimitivePx);
  frame.work = cv::Size(std::max(1, int(std::lround(size.width / frame.factor))),
                        std::max(1, int(std::lround(size.height / frame.factor))));
  frame.sigma = std::max(1.0, detail / frame.factor);
  frame.prims =
      frame_primitives(in, p, frame.factor, float(std::max(0.5, 0.5 * least_px / frame.factor)),
                       least_px * in.units_per_px);
  light_primitives(in, p, frame);
  return frame;
}

LeafTone leaf_tone(const LeafFrame& frame, const cv::Mat& color) {
  SYLVA_CHECK(color.size() == frame.size, "leaf tone: the colour is not the frame's size");
  // The shaded colour's darkness around each primitive's centre (Luft's realigned normals and
  // ka), darkened where the key light does not reach.
  const ToneRank tone = tone_rank(color, frame.work, frame.sigma, false);
  LeafTone out;
  out.darkness = tone.darkness;
  out.dark.resize(frame.prims.size());
  for (size_t i = 0; i < frame.prims.size(); ++i) {
    const float colour = tone.empty() ? 0.0f : tone.dark_near(frame.prims[i].c);
    out.dark[i] = 1.0f - (1.0f - colour) * frame.light[i];
  }
  return out;
}

LeafLayer wood_layer(const LeafFrame& frame, const SeenWood& wood, const EdgeParams& edges) {
  LeafLayer layer;
  layer.factor = frame.factor;
  layer.drawing.size = frame.size;
  layer.drawing.color = edges.color;
  layer.front = cv::Mat(frame.work, CV_32SC1, cv::Scalar(0));
  layer.depth = cv::Mat(frame.work, CV_32FC1, cv::Scalar(std::numeric_limits<float>::infinity()));
  paint_wood(wood, layer.factor, layer);
  return layer;
}

LeafPaint leaf_paint(const LeafFrame& frame, const LeafLayer& wood) {
  LeafPaint out;
  out.layer = wood;
  out.layer.front = wood.front.clone();
  out.layer.depth = wood.depth.clone();
  out.prims = frame.prims;
  paint_primitives(out.prims, out.layer);
  primitive_ranges(out.prims, out.layer);
  plant_extents(out.layer, out.prims);
  return out;
}

LeafLayer leaf_layer(const LeafPaint& paint, const LeafTone& tone, const LeafParams& p,
                     const InkLineParams& lines, const EdgeParams& edges) {
  const double scale = reference_scale(paint.layer.drawing.size);
  const double detail = lines.detail * scale;  // px
  LeafLayer layer = paint.layer;
  std::vector<Primitive> prims = paint.prims;
  rank_primitives(tone.dark, prims, layer);
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
  outline_primitives(prims, layer, s, arcs);
  // The black fills beside the arcs of each class chained: arcs of neighbouring primitives that
  // meet become one path (an outline of many leaves).
  cv::parallel_for_(cv::Range(0, 3), [&](const cv::Range& r) {
    for (int k = r.start; k < r.end; ++k) {
      if (k == 2)
        layer.drawing.strokes = black_fills(prims, layer, p, 1.0f);
      else
        chain_strokes(arcs[k], 1.5f * float(layer.factor));
    }
  });
  for (std::vector<Stroke>& run : arcs)
    for (Stroke& st : run)
      layer.drawing.strokes.push_back(std::move(st));
  return layer;
}

LeafLayer leaf_layer(const LeafImages& in, const LeafParams& p, const InkLineParams& lines,
                     const EdgeParams& edges) {
  const LeafFrame frame = leaf_frame(in, p, lines);
  const LeafPaint paint = leaf_paint(frame, wood_layer(frame, in.wood, edges));
  return leaf_layer(paint, leaf_tone(frame, in.color), p, lines, edges);
}

}  // namespace sylva

#include "passes/hatch_groups.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/random.h"
#include "passes/ink_abstraction.h"
#include "passes/pass_common.h"
#include "passes/tone_rank.h"

namespace sylva {

namespace {

// One group of parallel lines: its region's label in `regions`, anchor and direction (working
// px, unit, y down) and the box its region spans.
struct Group {
  int label = 0;
  cv::Point2f anchor, dir;
  cv::Rect box;
};

// The tone of a line: lines in an ordered dither of 4 (k = 0, 2, 1, 3 mod 4 get 1/8, 3/8, 5/8,
// 7/8), so every tone has its share of lines, evenly spaced.
float line_level(int64_t k) {
  static constexpr float kLevels[4] = {0.125f, 0.625f, 0.375f, 0.875f};
  return kLevels[((k % 4) + 4) % 4];
}

double group_hash01(uint64_t a, uint64_t b) {
  uint64_t s = a * 0x9e3779b97f4a7c15ull ^ (b + 0x632be59bd9b4e019ull);
  splitmix64(s);
  return uniform01(s);
}

float smooth01(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / std::max(1e-6f, e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

struct HatchStyle {
  double spacing = 4;  // working px between neighbouring lines
  double length = 8;   // working px of a stroke
  float width = 1;     // output px
  float opacity = 1;
  float cross = 1;  // tone from which the crossing layer starts
  uint64_t seed = 1;
  double factor = 1;  // output px per working px
};

// Where group g's layer (0: along dir, 1: across it) is hatched: the lines' direction d, their
// normal m, the group's box's extent along d (u0, u1) and the lines' indices k0..k1 across it.
struct HatchLines {
  cv::Point2f d, m;
  float u0 = 1e30f, u1 = -1e30f;
  int64_t k0 = 0, k1 = -1;
};

HatchLines hatch_lines(const Group& g, int layer, const HatchStyle& s) {
  HatchLines h;
  h.d = layer == 0 ? g.dir : cv::Point2f(-g.dir.y, g.dir.x);
  h.m = cv::Point2f(-h.d.y, h.d.x);
  float v0 = 1e30f, v1 = -1e30f;
  for (const cv::Point2f c : {cv::Point2f(float(g.box.x), float(g.box.y)),
                              cv::Point2f(float(g.box.br().x), float(g.box.y)),
                              cv::Point2f(float(g.box.x), float(g.box.br().y)),
                              cv::Point2f(float(g.box.br().x), float(g.box.br().y))}) {
    const cv::Point2f r = c - g.anchor;
    h.u0 = std::min(h.u0, r.dot(h.d)), h.u1 = std::max(h.u1, r.dot(h.d));
    v0 = std::min(v0, r.dot(h.m)), v1 = std::max(v1, r.dot(h.m));
  }
  h.k0 = int64_t(std::floor(v0 / s.spacing));
  h.k1 = int64_t(std::ceil(v1 / s.spacing));
  return h;
}

// The strokes of line k of group g's layer, where regions == g.label and the tone passes the
// line's level.
void hatch_line(const Group& g, int layer, const HatchLines& h, int64_t k, const cv::Mat& regions,
                const cv::Mat& tone, const HatchStyle& s, std::vector<Stroke>& out) {
  const float from = layer == 0 ? 0.0f : s.cross;
  const float level = from + (1.0f - from) * line_level(k);
  const double stagger =
      s.length * group_hash01(uint64_t(g.label) * 4 + uint64_t(layer), uint64_t(k) ^ s.seed);
  Stroke st;
  st.cls = LineClass::Tone;
  st.opacity = s.opacity;
  st.width = s.width;
  int64_t piece = INT64_MIN;
  auto flush = [&]() {
    if (st.points.size() >= 2 && double(st.points.size()) >= 0.3 * s.length)
      out.push_back(std::move(st));
    st.points.clear();
    st.widths.clear();
  };
  for (double u = std::floor(h.u0); u <= h.u1; u += 1.0) {
    const cv::Point2f q = g.anchor + float(k * s.spacing) * h.m + float(u) * h.d;
    const int x = int(std::floor(q.x)), y = int(std::floor(q.y));
    const int64_t here = int64_t(std::floor((u - stagger) / s.length));
    // A short gap at each stroke's start, so the strokes read as strokes.
    const bool gap = (u - stagger) - double(here) * s.length < 0.15 * s.length;
    float t = -1.0f;
    if (x >= 0 && y >= 0 && x < regions.cols && y < regions.rows &&
        regions.at<int>(y, x) == g.label)
      t = tone.at<float>(y, x);
    if (t <= level || gap || here != piece) flush();
    piece = here;
    if (t <= level || gap) continue;
    st.points.emplace_back(q.x * float(s.factor), q.y * float(s.factor));
    st.widths.push_back(s.width * smooth01(level, level + 0.1f, t));
  }
  flush();
}

// Every group's first layer, then the first `crossed` groups' second, appended to `out` in that
// order (each group's lines in order across it). The lines are hatched in parallel, a run of
// kLinesPerTask lines of one group's layer a task: each stroke depends on its line alone.
constexpr int64_t kLinesPerTask = 8;

void hatch_all(const std::vector<Group>& groups, size_t crossed, const cv::Mat& regions,
               const cv::Mat& tone, const HatchStyle& s, std::vector<Stroke>& out) {
  struct Task {
    size_t group;
    int layer;
    HatchLines lines;
    int64_t k0, k1;  // inclusive
  };
  std::vector<Task> tasks;
  for (size_t j = 0; j < groups.size() + crossed; ++j) {
    const int layer = j < groups.size() ? 0 : 1;
    const size_t i = layer == 0 ? j : j - groups.size();
    const HatchLines h = hatch_lines(groups[i], layer, s);
    for (int64_t k = h.k0; k <= h.k1; k += kLinesPerTask)
      tasks.push_back({i, layer, h, k, std::min(h.k1, k + kLinesPerTask - 1)});
  }
  std::vector<std::vector<Stroke>> each(tasks.size());
  cv::parallel_for_(cv::Range(0, int(tasks.size())), [&](const cv::Range& r) {
    for (int t = r.start; t < r.end; ++t) {
      const Task& task = tasks[size_t(t)];
      for (int64_t k = task.k0; k <= task.k1; ++k)
        hatch_line(groups[task.group], task.layer, task.lines, k, regions, tone, s,
                   each[size_t(t)]);
    }
  });
  for (std::vector<Stroke>& strokes : each)
    std::move(strokes.begin(), strokes.end(), std::back_inserter(out));
}

// Tone t in [0, 1] from a rank image (0 off the regions), smoothed over the regions: within the
// regions' box (0 beyond it), the blur reading the images around it as the whole image's would.
cv::Mat tone_of(const cv::Mat& rank, const cv::Mat& inside, double sigma, const PenParams& p) {
  cv::Mat t(rank.size(), CV_32FC1, cv::Scalar(0));
  const cv::Rect box = cv::boundingRect(inside);
  if (box.empty()) return t;
  cv::Mat mask;
  inside.convertTo(mask, CV_32F, 1.0 / 255.0);
  const cv::Mat weighted = rank.mul(mask);
  const cv::Mat r = normalised_blur(weighted(box), mask(box), sigma);
  const float lo = p.lightest, hi = std::max(p.darkest, p.lightest + 1e-3f);
  for_bands(r.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const float* from = r.ptr<float>(y);
      float* to = t.ptr<float>(y + box.y) + box.x;
      for (int x = 0; x < r.cols; ++x) {
        // pen.gamma > 0: no tone and full tone stay as they are (most of the frame is paper).
        const float c = std::clamp((from[x] - lo) / (hi - lo), 0.0f, 1.0f);
        to[x] = c > 0.0f && c < 1.0f ? std::pow(c, p.gamma) : c;
      }
    }
  });
  return t;
}

// The foliage groups: one per leaf cluster the front buffer shows, anchored at its primitives'
// area-weighted centre, along the surface's tangent.
std::vector<Group> clump_groups(const LeafLayer& layer, const cv::Mat& normal, const PenParams& p,
                                cv::Mat& regions) {
  const cv::Mat& front = layer.front;
  regions = cv::Mat(front.size(), CV_32SC1, cv::Scalar(0));
  std::map<uint32_t, int> label_of;
  std::vector<Group> groups;
  std::vector<cv::Vec3d> normals;
  // Each primitive's label, found in the map once (0 = not yet).
  std::vector<int> label_of_front(layer.clusters.size(), 0);
  for (int y = 0; y < front.rows; ++y)
    for (int x = 0; x < front.cols; ++x) {
      const int f = front.at<int>(y, x);
      if (f <= 0) continue;
      int& label = label_of_front[size_t(f - 1)];
      if (label == 0) {
        auto [it, fresh] =
            label_of.try_emplace(layer.clusters[size_t(f - 1)], int(groups.size()) + 1);
        if (fresh) {
          groups.push_back({it->second, {}, {}, cv::Rect(x, y, 1, 1)});
          normals.emplace_back(0, 0, 0);
        }
        label = it->second;
      }
      Group& g = groups[size_t(label - 1)];
      g.box |= cv::Rect(x, y, 1, 1);
      regions.at<int>(y, x) = label;
      const int ox = std::min(normal.cols - 1, int((x + 0.5) * layer.factor)),
                oy = std::min(normal.rows - 1, int((y + 0.5) * layer.factor));
      const cv::Vec3f n = normal.at<cv::Vec3f>(oy, ox);
      // (cv::norm would take the Vec as an InputArray: a library call per pixel.)
      const double len = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
      if (len > 0.0) normals[size_t(label - 1)] += cv::Vec3d(n) / len;
    }
  std::vector<double> weight(groups.size(), 0.0);
  std::vector<cv::Point2d> sum(groups.size());
  for (size_t i = 0; i < layer.clusters.size(); ++i) {
    const auto it = label_of.find(layer.clusters[i]);
    if (it == label_of.end()) continue;
    const double a = layer.areas[i];
    weight[size_t(it->second - 1)] += a;
    sum[size_t(it->second - 1)] += a * cv::Point2d(layer.centres[i]);
  }
  const double base = p.angle * std::numbers::pi / 180.0;
  const cv::Point2f along(float(std::cos(base)), float(-std::sin(base)));  // y down
  for (size_t i = 0; i < groups.size(); ++i) {
    Group& g = groups[i];
    g.anchor = weight[i] > 0.0 ? cv::Point2f(sum[i] / weight[i])
                               : cv::Point2f(float(g.box.x + 0.5 * g.box.width),
                                             float(g.box.y + 0.5 * g.box.height));
    // The normal's projection (view y up, image y down); the tangent across it.
    const cv::Vec3d n = normals[i] * (1.0 / std::max(1.0, cv::norm(normals[i])));
    cv::Point2f tangent{static_cast<float>(n[1]), static_cast<float>(n[0])};  // ⟂ (n.x, -n.y)
    const float reach = std::hypot(tangent.x, tangent.y);
    if (tangent.dot(along) < 0.0f) tangent = -tangent;
    const float w = std::clamp(reach / 0.6f, 0.0f, 1.0f) * 0.7f;
    cv::Point2f dir = (1.0f - w) * along + (reach > 0.0f ? w / reach : 0.0f) * tangent;
    const float len = std::hypot(dir.x, dir.y);
    g.dir = len > 1e-6f ? dir * (1.0f / len) : along;
  }
  return groups;
}

// The wood's groups are labelled from here up, apart from the crown's clumps (labelled from 1,
// one per cluster): a wood group's strokes, seeded by its label, do not depend on how many
// clumps there are, so `ink` (the wood only) hatches the wood as `pen` does without finding
// the clumps.
constexpr int kWoodLabels = 1 << 24;

// The wood groups: one per connected piece of `wood` (the front buffer's wood, 255), along its
// principal axis; labels after `first`.
std::vector<Group> wood_groups(const cv::Mat& wood, int first, cv::Mat& regions) {
  cv::Mat labels, stats, centres;
  const int n = cv::connectedComponentsWithStats(wood, labels, stats, centres, 8, CV_32S);
  std::vector<Group> groups;
  std::vector<cv::Vec3d> moments(size_t(std::max(0, n)), cv::Vec3d(0, 0, 0));
  for (int y = 0; y < labels.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    int* region = regions.ptr<int>(y);
    for (int x = 0; x < labels.cols; ++x)
      if (const int l = label[x]; l > 0) {
        const double* c = centres.ptr<double>(l);
        const double dx = x - c[0], dy = y - c[1];
        moments[size_t(l)] += cv::Vec3d(dx * dx, dx * dy, dy * dy);
        region[x] = first + l;
      }
  }
  for (int l = 1; l < n; ++l) {
    const cv::Vec3d& mo = moments[size_t(l)];
    const double angle = 0.5 * std::atan2(2.0 * mo[1], mo[0] - mo[2]);
    Group g;
    g.label = first + l;
    g.anchor = cv::Point2f(float(centres.at<double>(l, 0)), float(centres.at<double>(l, 1)));
    g.dir = cv::Point2f(float(std::cos(angle)), float(std::sin(angle)));
    g.box = cv::Rect(stats.at<int>(l, cv::CC_STAT_LEFT), stats.at<int>(l, cv::CC_STAT_TOP),
                     stats.at<int>(l, cv::CC_STAT_WIDTH), stats.at<int>(l, cv::CC_STAT_HEIGHT));
    groups.push_back(g);
  }
  return groups;
}

// The wood's tone: its darkness (the bark's shading) ranked among the wood's pixels, the
// darkness told apart to 1/kRankBins (a histogram, not a sort of every pixel): a pixel's rank is
// the share below its bin plus half its bin's, so ties (an evenly shaded branch) share the middle
// of their run.
constexpr int kRankBins = 1 << 16;

cv::Mat wood_rank(const LeafLayer& layer, const cv::Mat& wood, const cv::Mat& color,
                  const cv::Mat& darkness) {
  cv::Mat rank(layer.front.size(), CV_32FC1, cv::Scalar(0));
  const int n = cv::countNonZero(wood);
  if (n == 0) return rank;
  // The leaf tone's darkness when given (the same image), else the colour's.
  cv::Mat dark = darkness;
  if (dark.empty()) {
    dark = tone_darkness(color);
    cv::resize(dark, dark, layer.front.size(), 0, 0, cv::INTER_AREA);
  }
  const auto bin = [](float v) { return std::clamp(int(v * float(kRankBins)), 0, kRankBins - 1); };
  std::vector<int> count(kRankBins, 0);
  for (int y = 0; y < wood.rows; ++y) {
    const uint8_t* is_wood = wood.ptr<uint8_t>(y);
    const float* d = dark.ptr<float>(y);
    for (int x = 0; x < wood.cols; ++x)
      if (is_wood[x]) ++count[size_t(bin(d[x]))];
  }
  std::vector<float> mid(kRankBins);
  int64_t below = 0;
  for (int b = 0; b < kRankBins; ++b) {
    mid[size_t(b)] = float((double(below) + 0.5 * count[size_t(b)]) / double(n));
    below += count[size_t(b)];
  }
  for (int y = 0; y < wood.rows; ++y) {
    const uint8_t* is_wood = wood.ptr<uint8_t>(y);
    const float* d = dark.ptr<float>(y);
    float* r = rank.ptr<float>(y);
    for (int x = 0; x < wood.cols; ++x)
      if (is_wood[x]) r[x] = mid[size_t(bin(d[x]))];
  }
  return rank;
}

}  // namespace

StrokeDrawing hatch_groups(const LeafLayer& layer, const cv::Mat& normal, const cv::Mat& color,
                           const PenParams& p, double detail, HatchWhat what,
                           const cv::Mat& darkness) {
  StrokeDrawing d;
  d.size = layer.drawing.size;
  d.color = layer.drawing.color;
  if (layer.front.empty()) return d;
  const double scale = reference_scale(d.size), f = layer.factor;
  HatchStyle s;
  s.factor = f;
  s.width = float(std::max(1.0, p.width * scale));
  // Small renders: lines no closer than 4 widths (spacing and length grow together).
  const double grow = std::max(1.0, 4.0 * s.width / (p.spacing * scale));
  s.spacing = p.spacing * scale * grow / f;
  s.length = std::max(2.0, p.length * scale * grow / f);
  s.opacity = p.opacity;
  s.cross = p.cross;
  s.seed = uint64_t(p.seed);
  cv::Mat regions(layer.front.size(), CV_32SC1, cv::Scalar(0));
  cv::Mat tone(layer.front.size(), CV_32FC1, cv::Scalar(0));
  std::vector<Group> groups;
  if (what.foliage) {
    groups = clump_groups(layer, normal, p, regions);
    // A clump as the eye groups it: small pieces of other clusters seen through it belong to it.
    regions = majority_labels(regions, std::max(1, int(std::lround(0.5 * detail * scale / f))));
    tone = tone_of(layer.rank, regions > 0, detail * scale / f, p);
  }
  const size_t clumps = groups.size();
  if (what.wood) {
    const cv::Mat is_wood = layer.front == kWoodFront;
    const std::vector<Group> wood = wood_groups(is_wood, kWoodLabels, regions);
    const cv::Mat wood_tone =
        tone_of(wood_rank(layer, is_wood, color, darkness), is_wood, 0.5 * detail * scale / f, p);
    wood_tone.copyTo(tone, is_wood);
    groups.insert(groups.end(), wood.begin(), wood.end());
  }
  // Wood is hatched along its axis only: crossing lines on a branch read as a net.
  hatch_all(groups, p.cross < 1.0f ? clumps : 0, regions, tone, s, d.strokes);
  return d;
}

Handle<StrokeDrawing> add_hatch_groups_pass(RenderGraph& g, Handle<LeafLayer> layer,
                                            ImageHandle normal, ImageHandle color,
                                            const PenParams& p, double detail, HatchWhat what,
                                            Handle<LeafTone> tone) {
  SYLVA_CHECK(color.valid() && (normal.valid() || !what.foliage),
              "hatching needs the color resource, and the normals for the crown's clumps");
  const auto out = g.resource<StrokeDrawing>("hatching");
  // Only the crown's clumps read the normals (the raster then leaves them out for `ink`).
  std::vector<ResourceRef> reads{layer, color};
  if (what.foliage) reads.push_back(normal);
  if (tone.valid()) reads.push_back(tone);
  g.add_pass(
      "hatching", reads, {out},
      [=](PassContext& ctx) {
        const cv::Mat normals = what.foliage ? ctx.read<cv::Mat>(normal) : cv::Mat();
        const cv::Mat darkness = tone.valid() ? ctx.read<LeafTone>(tone).darkness : cv::Mat();
        ctx.write(out, hatch_groups(ctx.read<LeafLayer>(layer), normals, ctx.read<cv::Mat>(color),
                                    p, detail, what, darkness));
      },
      RenderGraph::Threads::Any);
  return out;
}

}  // namespace sylva

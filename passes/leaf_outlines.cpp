#include "passes/leaf_outlines.h"

#include <algorithm>
#include <iterator>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "passes/crack_chains.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

// The runs outline_primitives splits the primitives into.
constexpr size_t kOutlineRuns = 64;

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

// The most points around an outline (arc_points).
constexpr int kMostArcPoints = 256;

// cos and sin of 2 pi j / n for j < n, for every n up to kMostArcPoints: computed once, read by
// every primitive's outline.
const std::vector<std::pair<double, double>>& unit_circle(int n) {
  static const std::vector<std::vector<std::pair<double, double>>> circles = [] {
    std::vector<std::vector<std::pair<double, double>>> all(size_t(kMostArcPoints + 1));
    for (int m = 1; m <= kMostArcPoints; ++m)
      for (int j = 0; j < m; ++j) {
        const double phi = 2.0 * std::numbers::pi * j / m;
        all[size_t(m)].emplace_back(std::cos(phi), std::sin(phi));
      }
    return all;
  }();
  return circles[size_t(n)];
}

// Points around primitive i's outline, about one per working px, each weighted by how far the
// primitive stands in front of what lies just outside it there (0 where it is hidden), into
// `pts` (resized).
void arc_points(const std::vector<Primitive>& prims, size_t i, const LeafLayer& layer,
                const ArcStyle& s, std::vector<ArcPoint>& pts) {
  const Primitive& p = prims[i];
  const double perimeter = std::numbers::pi * std::sqrt(2.0 * (p.a * p.a + p.b * p.b));
  const int n = std::clamp(int(std::ceil(perimeter)), 12, kMostArcPoints);
  const float step = step_of(p, s);
  const double qa = p.qa(), qb = p.qb(), qc = p.qc();
  pts.resize(static_cast<size_t>(n));
  const std::vector<std::pair<double, double>>& circle = unit_circle(n);
  for (int j = 0; j < n; ++j) {
    const double lx = p.a * circle[size_t(j)].first, ly = p.b * circle[size_t(j)].second;
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

}  // namespace

void outline_primitives(const std::vector<Primitive>& prims, const LeafLayer& layer,
                        const ArcStyle& s, std::vector<Stroke> (&arcs)[2]) {
  // The primitives in a fixed number of runs, outlined in parallel and joined in order: the
  // same strokes in the same order whatever the threads.
  struct Arcs {
    std::vector<Stroke> cls[2];
  };
  const size_t n = prims.size(), runs = std::min<size_t>(n, kOutlineRuns);
  // A primitive no pixel of the front buffer shows has no point of its outline drawn (a point is
  // drawn only just inside a pixel it owns): it is skipped.
  std::vector<uint8_t> shown(n, 0);
  for (int y = 0; y < layer.front.rows; ++y) {
    const int* f = layer.front.ptr<int>(y);
    for (int x = 0; x < layer.front.cols; ++x)
      if (f[x] > 0 && size_t(f[x]) <= n) shown[size_t(f[x] - 1)] = 1;
  }
  std::vector<Arcs> part(runs);
  cv::parallel_for_(cv::Range(0, int(runs)), [&](const cv::Range& r) {
    std::vector<ArcPoint> pts;
    for (int k = r.start; k < r.end; ++k)
      for (size_t i = n * size_t(k) / runs; i < n * size_t(k + 1) / runs; ++i) {
        if (!shown[i]) continue;
        arc_points(prims, i, layer, s, pts);
        add_arcs(pts, s, part[size_t(k)].cls);
      }
  });
  for (Arcs& a : part)
    for (int c = 0; c < 2; ++c)
      std::move(a.cls[c].begin(), a.cls[c].end(), std::back_inserter(arcs[c]));
}

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

}  // namespace sylva

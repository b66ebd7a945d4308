#include "passes/wood_lines.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "core/error.h"
#include "passes/crack_chains.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

// Cracks of the wood: against whatever is not wood and not in front of it by more
// than `cover` (the paper, foliage behind or around it), and against other wood nearer or
// farther by more than `jump` of its depth.
Cracks wood_outline(const cv::Mat& wood, const cv::Mat& depth, float jump, float cover) {
  Cracks c(wood.size());
  const cv::Mat w = wood.isContinuous() ? wood : wood.clone();
  const cv::Mat d = depth.isContinuous() ? depth : depth.clone();
  const uint8_t* is_wood = w.ptr<uint8_t>();
  const float* z = d.ptr<float>();
  mark_cracks(c, [&](int p, int q) {
    if (is_wood[p] && is_wood[q]) return std::abs(z[p] - z[q]) > jump * std::min(z[p], z[q]);
    if (!(is_wood[p] | is_wood[q])) return false;
    const int a = is_wood[p] ? p : q, b = a == p ? q : p;
    return !(z[b] > 0.0f) || z[b] > z[a] - cover;
  });
  return c;
}

// The chained cracks of wood_outline, found within the wood's box and a pixel around it (every
// crack has wood on one side), in the frame's coordinates.
std::vector<Polyline> wood_chains(const SeenWood& seen, float jump) {
  const cv::Rect frame(0, 0, seen.mask.cols, seen.mask.rows);
  const cv::Rect wood = cv::boundingRect(seen.mask);
  if (wood.empty()) return {};
  const cv::Rect box = cv::Rect(wood.x - 1, wood.y - 1, wood.width + 2, wood.height + 2) & frame;
  std::vector<Polyline> chains =
      chain_cracks(wood_outline(seen.mask(box), seen.depth(box), jump, seen.cover));
  const cv::Point2f origin(float(box.x), float(box.y));
  for (Polyline& chain : chains)
    for (cv::Point2f& q : chain.points)
      q += origin;
  return chains;
}

// Moves each point of an outline onto the wood's side of its edge by `offset` px, so the line
// lies over the wood it outlines, not over what is behind it.
void onto_wood(Polyline& line, const cv::Mat& mask, float offset) {
  const size_t n = line.points.size();
  if (n < 2) return;
  auto wood_at = [&](cv::Point2f q) {
    const int x = int(std::floor(q.x)), y = int(std::floor(q.y));
    return x >= 0 && y >= 0 && x < mask.cols && y < mask.rows && mask.at<uint8_t>(y, x) != 0;
  };
  std::vector<cv::Point2f> moved(line.points);
  for (size_t i = 0; i < n; ++i) {
    const cv::Point2f a = line.points[i == 0 ? (line.closed ? n - 1 : 0) : i - 1];
    const cv::Point2f b = line.points[i + 1 < n ? i + 1 : (line.closed ? 0 : n - 1)];
    const cv::Point2f t = b - a;
    const float length = std::hypot(t.x, t.y);
    if (length <= 0.0f) continue;
    const cv::Point2f normal(-t.y / length, t.x / length);
    const bool left = wood_at(line.points[i] + 1.0f * normal),
               right = wood_at(line.points[i] - 1.0f * normal);
    if (left != right) moved[i] += (left ? offset : -offset) * normal;
  }
  line.points = moved;
}

Stroke wood_stroke(const Polyline& chain, float width, float opacity) {
  Stroke s;
  s.cls = LineClass::Wood;
  s.closed = chain.closed;
  s.width = width;
  s.opacity = opacity;
  for (const cv::Point2f& q : chain.points)
    s.points.emplace_back(q.x, q.y);
  return s;
}

}  // namespace

StrokeDrawing wood_strokes(const SeenWood& seen, const InkLineParams& lines,
                           const EdgeParams& edges) {
  StrokeDrawing d;
  d.size = seen.depth.size();
  d.color = edges.color;
  if (seen.mask.empty() || !lines.wood.on || lines.wood.tone <= 0.0f) return d;
  const double scale = reference_scale(d.size);
  const cv::Mat& mask = seen.mask;
  const float width = float(std::max<double>(edges.min_width, lines.wood.width * scale));
  const double min_length = std::max(3.0 * scale, 1.0 * lines.detail * scale);
  const std::vector<Polyline> chains = wood_chains(seen, edges.depth_threshold);
  // Each chain smoothed in parallel (it depends on itself alone), kept in the chains' order.
  std::vector<std::optional<Stroke>> strokes(chains.size());
  cv::parallel_for_(cv::Range(0, int(chains.size())), [&](const cv::Range& r) {
    for (int i = r.start; i < r.end; ++i) {
      const Polyline& chain = chains[size_t(i)];
      // Short pieces thin out toward nothing rather than vanish at a length, so a piece of a
      // branch seen through a gap fades as the gap closes from frame to frame (at half the
      // length it has no width: no stroke).
      const double share = polyline_length(chain) / min_length;
      if (share <= 0.5) continue;
      const float w = width * float(std::min(1.0, (share - 0.5) / 0.5));
      Polyline line = smooth_polyline(chain, std::max(1.0, scale));
      onto_wood(line, mask, 0.5f * w);
      strokes[size_t(i)] = wood_stroke(simplify_polyline(line, 0.4), w, lines.wood.tone);
    }
  });
  for (std::optional<Stroke>& st : strokes)
    if (st) d.strokes.push_back(std::move(*st));
  return d;
}

Handle<StrokeDrawing> add_wood_lines_pass(RenderGraph& g, Handle<SeenWood> wood,
                                          const InkLineParams& lines, const EdgeParams& edges) {
  const auto out = g.resource<StrokeDrawing>("wood-strokes");
  g.add_pass(
      "wood-strokes", {wood}, {out},
      [=](PassContext& ctx) {
        ctx.write(out, wood_strokes(ctx.read<SeenWood>(wood), lines, edges));
      },
      RenderGraph::Threads::Any);
  return out;
}

}  // namespace sylva

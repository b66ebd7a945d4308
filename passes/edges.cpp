#include "passes/edges.h"

#include <string>
#include <vector>

#include "core/error.h"
#include "passes/edge_lines.h"
#include "passes/edge_marks.h"

namespace sylva {

bool EdgeParams::uses_depth() const {
  return depth || crease || depth_width > 1.0f || fade > 0.0f;
}

void bind_edge_params(ParamSet& set, EdgeParams& p) {
  set.add_bool("edges.silhouette", p.silhouette, "outline against the background, from coverage");
  set.add_bool("edges.depth", p.depth, "lines at depth discontinuities (Saito & Takahashi)");
  set.add_float("edges.depth_threshold", p.depth_threshold, 0.001, 10.0, "relative depth",
                "a line where neighbouring depths differ by more than this fraction of the "
                "nearer one");
  set.add_bool("edges.crease", p.crease, "lines at creases, from second-order depth");
  set.add_float("edges.crease_threshold", p.crease_threshold, 0.01, 100.0,
                "per mille of depth per reference px",
                "a line where the second difference of depth exceeds this");
  set.add_bool("edges.normal", p.normal, "lines at normal discontinuities (Decaudin)");
  set.add_float("edges.normal_threshold", p.normal_threshold, 0.0, 180.0, "degrees",
                "a line where neighbouring normals are more than this angle apart", true);
  set.add_choice("edges.normal_metric", p.normal_metric,
                 {{"angle", NormalMetric::Angle}, {"vector", NormalMetric::Vector}},
                 "angle: between directions; vector: |N_p - N_q|, so short (low-ka) normals "
                 "give fewer lines (Luft et al. Fig. 7c)");
  set.add_bool("edges.id", p.id, "lines where the id (primitive, cluster, object) changes");
  set.add_color("edges.color", p.color, "line colour");
  set.add_float("edges.width", p.width, 0.25, 16.0, "px at 1024 px", "line width");
  set.add_float("edges.min_width", p.min_width, 0.0, 4.0, "px",
                "thinnest line in output pixels, whatever the resolution (0 = no floor)");
  set.add_float("edges.min_length", p.min_length, 0.0, 256.0, "px at 1024 px",
                "lines (connected marks) shorter than this are dropped (0 = keep all)");
  set.add_float("edges.depth_width", p.depth_width, 1.0, 8.0, "ratio",
                "nearest lines are this many times thicker than the farthest (1 = even)");
  set.add_float("edges.fade", p.fade, 0.0, 1.0, "",
                "opacity the farthest lines lose (0 = none, 1 = they vanish)");
}

EdgeMarks mark_edges(const EdgeImages& in, const EdgeParams& p) {
  cv::Mat fg;
  return find_edge_marks(in, p, fg);
}

cv::Mat detect_edges(const EdgeImages& in, const EdgeParams& p) {
  cv::Mat fg;
  const EdgeMarks marks = find_edge_marks(in, p, fg);
  return draw_edge_lines(marks, in.depth, fg, p);
}

ImageHandle add_edges_pass(RenderGraph& g, const EdgeResources& in, const EdgeParams& p) {
  std::vector<ResourceRef> reads;
  EdgeResources used;  // what the pass reads; the rest stays none
  auto need = [&](ImageHandle EdgeResources::*field, bool wanted, const char* what) {
    if (!wanted) return;
    SYLVA_CHECK((in.*field).valid(), std::string("edges pass needs the ") + what + " resource");
    used.*field = in.*field;
    reads.push_back(in.*field);
  };
  need(&EdgeResources::normal, p.uses_normal(), "normal");
  need(&EdgeResources::depth, p.uses_depth(), "depth");
  need(&EdgeResources::id, p.uses_id(), "id");
  // Coverage: the colour's alpha when given; else whatever geometric buffer is read anyway;
  // and with nothing read at all, one image for the output size.
  if ((p.silhouette || reads.empty()) && in.color.valid()) {
    used.color = in.color;
    reads.push_back(in.color);
  }
  if (reads.empty()) {
    for (ImageHandle EdgeResources::*field :
         {&EdgeResources::depth, &EdgeResources::id, &EdgeResources::normal})
      if ((in.*field).valid()) {
        used.*field = in.*field;
        reads.push_back(in.*field);
        break;
      }
  }
  SYLVA_CHECK(!reads.empty(), "edges pass has no input resource");

  const auto out = g.resource<cv::Mat>("edges");
  g.add_pass("edges", reads, {out}, [used, p, out](PassContext& ctx) {
    EdgeImages images;
    if (used.normal.valid()) images.normal = ctx.read<cv::Mat>(used.normal);
    if (used.depth.valid()) images.depth = ctx.read<cv::Mat>(used.depth);
    if (used.id.valid()) images.id = ctx.read<cv::Mat>(used.id);
    if (used.color.valid()) images.color = ctx.read<cv::Mat>(used.color);
    ctx.write(out, detect_edges(images, p));
  });
  return out;
}

}  // namespace sylva

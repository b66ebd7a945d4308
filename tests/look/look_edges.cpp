// Edge and ink looks: the cube and sphere's lines (tests/passes/edge_scenes.h) and an ink
// composite of a shaded disc and a square.
#include <algorithm>

#include "core/params.h"
#include "passes/composite.h"
#include "passes/edges.h"
#include "tests/look/look.h"
#include "tests/passes/edge_scenes.h"

namespace sylva::test {

namespace {

InkParams look_ink_params(const char* paper, const char* line, float grain, float fill) {
  InkParams p;
  if (!parse_hex_color(paper, p.paper.color) || !parse_hex_color(line, p.line_color))
    throw std::logic_error("bad look colour");
  p.paper.grain = grain;
  p.fill = fill;
  return p;
}

}  // namespace

// The cube and sphere's lines (edge_scenes.h), as ink over grained paper, and widened by depth.
void edges_look(const Save& save) {
  const EdgeImages in = render(CubeScene{.sphere = true}, 1024);
  EdgeParams p;
  p.crease = true;
  const cv::Mat lines = detect_edges(in, p);
  cv::Mat ink;
  lines.convertTo(ink, CV_8UC1, -255.0, 255.0);
  save("cube-edges.png", ink);
  const InkParams look = look_ink_params("#f4ecd8", "#1e1a16", 0.6f, 0.3f);
  save("cube-ink.png", composite_ink(lines, in.color, make_paper(lines.size(), look.paper), look));
  p.depth_width = 4.0f;
  p.fade = 0.6f;
  p.width = 4.0f;
  detect_edges(in, p).convertTo(ink, CV_8UC1, -255.0, 255.0);
  save("cube-edges-depth.png", ink);
}

// A shaded disc and a square, outlined by the edges pass from coverage and ids, composited
// over grained paper with a wash.
void ink_look(const Save& save) {
  const int s = 512;
  EdgeImages g;
  g.color = cv::Mat::zeros(s, s, CV_8UC4);
  g.id = cv::Mat::zeros(s, s, CV_32SC1);
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x) {
      const double dx = x + 0.5 - 0.45 * s, dy = y + 0.5 - 0.5 * s, r = 0.3 * s;
      const double d2 = dx * dx + dy * dy;
      if (d2 < r * r) {
        const double shade = 0.3 + 0.7 * std::max(0.0, (-dx - dy) / (1.5 * r) + 0.5);
        g.color.at<cv::Vec4b>(y, x) =
            cv::Vec4b(uint8_t(60 * shade), uint8_t(170 * shade), uint8_t(110 * shade), 255);
        g.id.at<int>(y, x) = dx * dy > 0 ? 1 : 2;
      } else if (x > 0.6 * s && x < 0.9 * s && y > 0.15 * s && y < 0.45 * s) {
        g.color.at<cv::Vec4b>(y, x) = cv::Vec4b(50, 120, 200, 255);
        g.id.at<int>(y, x) = 3;
      }
    }
  EdgeParams e;
  e.depth = e.normal = false;
  e.id = true;
  const InkParams p = look_ink_params("#f3ead6", "#1d1a18", 0.5f, 0.35f);
  const cv::Mat lines = detect_edges(g, e);
  save("ink-composite.png", composite_ink(lines, g.color, make_paper(lines.size(), p.paper), p));
}

}  // namespace sylva::test

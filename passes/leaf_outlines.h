// The outlines and the black fills of the foliage's drawing primitives (passes/leaf_primitives.h):
// the primitive itself, its outline arcs where it stands in front of what lies behind it by its
// depth step, and the deep shadow's black. Shared by passes/leaf_primitives.cpp and the
// watercolor's leaf marks (passes/watercolor_marks.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

#include "core/strokes.h"
#include "passes/leaf_primitives.h"

namespace sylva {

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

// Calls span(y, x0, x1) for each row of pixels whose centres lie in the ellipse `p` scaled by
// `k`, the centres x0..x1 (inclusive), clipped to `size`.
template <class Span>
void ellipse_spans(const Primitive& p, float k, cv::Size size, int y_from, int y_to, Span span) {
  const double a = p.a * k, b = p.b * k;
  if (!(a > 0.0) || !(b > 0.0)) return;
  const double c2 = p.cos_t * p.cos_t, s2 = p.sin_t * p.sin_t;
  const double ry = std::sqrt(a * a * s2 + b * b * c2);
  const int y0 = std::max(y_from, int(std::ceil(p.c.y - ry - 0.5))),
            y1 = std::min(y_to - 1, int(std::floor(p.c.y + ry - 0.5)));
  if (y0 > y1) return;
  const double qa = c2 / (a * a) + s2 / (b * b),
               qb = p.cos_t * p.sin_t * (1 / (a * a) - 1 / (b * b)),
               qc = s2 / (a * a) + c2 / (b * b);
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

// The frame's view-facing ellipses at the working resolution (`f` output px per working px):
// each piece of in.pieces, or each clump of a cluster's pieces within one cell of `cell` scene
// units (0 = the pieces), of its own projected shape (LeafShape::Auto) or round, no smaller
// than `least` working px of semi-axis; those in front of the eye and near the frame.
std::vector<Primitive> project_primitives(const LeafImages& in, LeafShape shape, double f,
                                          float least, double cell);

// The rows [first, last] that pixel centres in ellipse `p` scaled by `k` can lie on (unclipped;
// ellipse_spans calls no others).
inline std::pair<int, int> ellipse_rows(const Primitive& p, float k) {
  const double a = p.a * k, b = p.b * k;
  const double ry = std::sqrt(a * a * p.sin_t * p.sin_t + b * b * p.cos_t * p.cos_t);
  return {int(std::floor(p.c.y - ry - 0.5)), int(std::ceil(p.c.y + ry - 0.5))};
}

// Each primitive a flat solid at its depth into out.front (index + 1) and out.depth, behind
// what is marked kWoodFront (the lower index wins a tie, whatever the threads).
void paint_primitives(const std::vector<Primitive>& prims, LeafLayer& out);

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

// Each primitive's outline arcs, by class: [0] interior (LineClass::Foliage), [1] against the
// paper (LineClass::Silhouette); about one point per working px, in output px.
void outline_primitives(const std::vector<Primitive>& prims, const LeafLayer& layer,
                        const ArcStyle& s, std::vector<Stroke> (&arcs)[2]);

// The deep shadow's black: each primitive's visible part within its ellipse scaled by its fill
// (0..1 by rank), traced as filled regions.
std::vector<Stroke> black_fills(const std::vector<Primitive>& prims, const LeafLayer& layer,
                                const LeafParams& p, float opacity);

}  // namespace sylva

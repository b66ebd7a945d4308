// Edges (issue "Styles"): feature lines found in the G-buffer, drawn as antialiased line
// coverage. The kinds are the standard image-space ones: depth discontinuities (first-order
// depth differences, Saito & Takahashi 1990), creases (second-order depth differences, idem),
// normal discontinuities (Decaudin 1996), id boundaries, and the silhouette against the
// background, which always comes from coverage.
//
// Reads (render graph, only what the enabled kinds need):
//   "color"  CV_8UC4 BGRA, alpha = coverage: the silhouette's coverage, when the caller passes it
//   "depth"  CV_32FC1 linear view depth, background 0: depth and crease edges, depth_width, fade
//   "normal" CV_32FC3 view-space normal (unit, or |N| = ka), background 0: normal edges
//   "id"     CV_32SC1, background 0: id boundaries
// Writes "edges": CV_32FC1 line coverage in [0, 1] at the input size (0 = no line).
//
// How a line is drawn: every kind marks where its discontinuity lies on the half-pixel
// lattice: between the two pixels of a 4-neighbour pair that differ (depth, normal, id,
// silhouette; a silhouette shifted to where the colour's alpha puts the boundary), or on a
// pixel centre or between two (a crease, by where its second difference peaks). Lines are
// centred on the boundary, on neither side. The marks are widened by an exact Euclidean
// distance transform on that lattice (Felzenszwalb & Huttenlocher 2012; OpenCV's works on pixel
// centres only), refined near the line by a least-squares line through the nearby marks (a
// binary boundary zigzags by half a pixel about the true one), with a one-pixel box-filter
// falloff: antialiased lines of the same width, within about 7%, in every direction
// (tests/passes/test_edges.cpp). Two clean-ups keep lines single: a mark of another kind
// within 1.5 px (a crease: 2.5 px) of the silhouette is dropped (a surface seen edge-on turns
// its normal and depth fastest right at its outline, which would draw a second, ragged line
// beside it), and so are groups of fewer than three marks (specks, not lines); with
// min_length, also every connected group, outline included, shorter than that. At small sizes
// lines are widened to min_width px, so that none is thinner than a pixel's worth of ink.
//
// Parts: marking in passes/edge_marks.h (creases in passes/edge_creases.h), widening into
// lines in passes/edge_lines.h, both on the lattice of passes/edge_lattice.h. They run row
// bands in parallel, and every output pixel depends only on the inputs, so the bytes do not
// depend on the number of threads.
#pragma once

#include <glm/glm.hpp>
#include <opencv2/core.hpp>
#include <string>

#include "core/graph/render_graph.h"
#include "core/params.h"

namespace sylva {

// edges.normal_metric: how neighbouring normals are compared (see EdgeParams::normal).
enum class NormalMetric { Angle, Vector };

struct EdgeParams {
  // edges.silhouette: outline of the drawing against the background, from coverage (colour
  // alpha >= 0.5 when the colour image is given, else depth > 0, else id != 0, else |N| > 0).
  bool silhouette = true;

  // edges.depth / edges.depth_threshold: a jump between 4-neighbours p, q where
  // |z_p - z_q| / min(z_p, z_q) > threshold. Relative depth, so a jump of 2% is a jump at any
  // distance. A plane changes per pixel by about tan(its angle to the view) times the pixel's
  // angular size, so it stays under 0.02 unless within 2 degrees of edge-on at 1024 px and a
  // 40 degree view (8 degrees at 256 px). Range [0.001, 10], unit "relative depth"; default
  // 0.02.
  bool depth = true;
  float depth_threshold = 0.02f;

  // edges.crease / edges.crease_threshold: a kink in the depth along a row or column, from
  // the second difference |z(x-1) - 2 z(x) + z(x+1)| / z(x). Two refinements of the standard
  // formula: the smaller of that and the same difference taken on 1/z (times z) is used, so a
  // plane gives exactly 0 under both orthographic (z linear on screen) and perspective (1/z
  // linear) projection; and a kink falling between two pixels splits its second difference
  // between them, so each pixel adds its same-signed neighbour's share. The result is scaled
  // to the 1024 px reference (x reference_scale) and expressed in per mille. Depends on the
  // field of view (a narrow view sees flatter depth): at a 40 degree view, the 90 degree edges
  // of a cube seen corner-on give about 2, smooth surfaces well under 0.1. Range [0.01, 100],
  // unit "per mille of depth per reference px"; default 0.5.
  bool crease = false;
  float crease_threshold = 0.5f;

  // edges.normal / edges.normal_threshold / edges.normal_metric: neighbouring normals more
  // than threshold degrees apart (Decaudin 1996). "angle" compares directions (normalised
  // normals); "vector" compares |N_p - N_q| with the chord 2 sin(threshold / 2) of the same
  // angle, identical for unit normals, but realigned-scaled normals (|N| = ka, Luft et al.
  // Fig. 7c) that are short (dark, deep inside the foliage) then differ less, which gives
  // fewer lines inside the crown. Range (0, 180], unit degrees; default 40.
  bool normal = true;
  float normal_threshold = 40.0f;
  NormalMetric normal_metric = NormalMetric::Angle;

  // edges.id: a line wherever the id changes between covered 4-neighbours (primitive, cluster
  // or object, whatever the frame's id buffer holds). No threshold.
  bool id = false;

  // edges.color: line colour, linear RGB (a preset gives "#RRGGBB" sRGB). Default black. Used
  // by the compositing pass (passes/composite.h), not here.
  glm::vec3 color{0.0f, 0.0f, 0.0f};

  // edges.width: line width in px at the 1024 px reference (x reference_scale at other
  // sizes). Range [0.25, 16]; default 1.5.
  float width = 1.5f;

  // edges.min_width: the thinnest a line is drawn, in px of the output image (not scaled with
  // the resolution): width x reference_scale, and the farthest lines of depth_width, are
  // widened to it. A line narrower than a pixel covers no pixel fully and, blended in linear
  // light, comes out a light grey instead of ink. 0 = no floor. Range [0, 4], unit px;
  // default 1.
  float min_width = 1.0f;

  // edges.min_length: connected groups of marks of any kind (marks on 8-neighbouring pixels;
  // a mark between two pixels counts on the left or upper one) whose extent, the diagonal of
  // the bounding box of their pixels, is shorter than this are dropped: the specks and dashes
  // leaf-level discontinuities leave inside a crown, not lines. Scaled like width (x
  // reference_scale). 0 = keep all. Range [0, 256], unit px at 1024 px; default 0.
  float min_length = 0.0f;

  // edges.depth_width: how many times thicker the nearest lines are than the farthest ones
  // (nearest = width, farthest = width / depth_width, linear in depth over the frame's
  // covered depth range). 1 = constant width. Range [1, 8], unit ratio; default 1.
  float depth_width = 1.0f;

  // edges.fade: opacity the farthest lines lose (linear in depth over the frame's covered
  // depth range): 0 = no fade, 1 = the farthest lines vanish. Range [0, 1]; default 0.
  float fade = 0.0f;

  bool uses_depth() const;  // whether depth must be read (depth, crease, depth_width, fade)
  bool uses_normal() const { return normal; }
  bool uses_id() const { return id; }
};

// Binds edges.* with their ranges, units and docs. `set` refers into `p`.
void bind_edge_params(ParamSet& set, EdgeParams& p);

// The G-buffer images; those not needed by the enabled kinds may be empty. All given images
// have the same size.
struct EdgeImages {
  cv::Mat normal;  // CV_32FC3
  cv::Mat depth;   // CV_32FC1
  cv::Mat id;      // CV_32SC1
  cv::Mat color;   // CV_8UC4 (only its alpha, the coverage, is used)
};

// Where the enabled kinds found discontinuities, on the half-pixel lattice (255 = a line
// passes there), before widening.
struct EdgeMarks {
  cv::Mat between_x;  // CV_8UC1, H x (W-1): between pixels (x, y) and (x+1, y)
  cv::Mat between_y;  // CV_8UC1, (H-1) x W: between pixels (x, y) and (x, y+1)
  cv::Mat at;         // CV_8UC1, H x W: on the centre of pixel (x, y)
  // CV_32FC1 like between_x / between_y, or empty: where the boundary crosses between the two
  // pixels, in px from their midpoint toward +x / +y, in [-0.5, 0.5]. Silhouettes take it
  // from the colour's alpha (sub-pixel coverage); every other mark sits on its midpoint (0).
  cv::Mat shift_x, shift_y;
  int count() const;  // number of marks
};
EdgeMarks mark_edges(const EdgeImages& in, const EdgeParams& p);

// Line coverage (CV_32FC1 in [0, 1]) at the input size: mark_edges widened to p.width (with
// depth_width and fade applied).
cv::Mat detect_edges(const EdgeImages& in, const EdgeParams& p);

// Render-graph handles of the G-buffer images the edges pass may read (-1 = not available).
// With color = -1 the silhouette takes coverage from a geometric buffer it reads anyway.
struct EdgeResources {
  ImageHandle normal{}, depth{}, id{}, color{};
};

// Adds the pass "edges", reading only what the enabled kinds of `p` need, and returns its
// output resource "edges" (cv::Mat CV_32FC1). A missing handle the parameters need is a
// programming error (SYLVA_CHECK).
ImageHandle add_edges_pass(RenderGraph& g, const EdgeResources& in, const EdgeParams& p);

}  // namespace sylva

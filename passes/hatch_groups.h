// Pen hatching as illustrators lay it (issue "Pen-and-ink that depicts the tree"; the `pen`
// preset): strokes in parallel groups at even spacing, one group per clump of the crown (a leaf
// cluster as the foliage primitives show it, passes/leaf_primitives.h) and per piece of wood,
// their direction following the form, a second even layer crossing the first where the tone
// is deepest; not strokes scattered at jittered angles.
//
// Tone: the foliage primitives' rank (the shaded colour with Luft's realigned normals and ka,
// and the key light's shadow through the crown), smoothed at ink.detail, t = clamp((rank -
// pen.lightest) / (pen.darkest - pen.lightest), 0, 1)^pen.gamma; the wood's own darkness
// (the bark's shading, its shadow side) ranked among the wood's pixels the same way.
//
// A group: the lines k x spacing apart across its direction d, through the clump's anchor (its
// primitives' centres, area-weighted, so the lines move with the scene), each line drawn where
// the clump is seen and the tone passes the line's level: the levels of neighbouring lines
// interleave (1/8, 5/8, 3/8, 7/8 of the tone, an ordered dither), so the density of lines is the
// tone and the lines stay evenly spaced at every tone. A line is cut into strokes of about
// pen.length with short gaps, staggered from line to line (seeded by pen.seed), as a hand lays
// hatching in short parallel strokes. Direction: a clump's hatching runs along the crown's
// surface (perpendicular to the realigned normal's projection, the implicit surface's
// tangent), blended toward pen.angle where the surface faces the viewer; wood's along the
// branch (the piece's principal axis). The crossing layer turns by 90 degrees where the tone
// passes pen.cross, its own levels spread over the rest of the tone.
//
// Reads a LeafLayer (its front, rank, clusters, centres and areas), the "normal" target
// (CV_32FC3 view space, the frame's size; only when the crown is hatched: empty otherwise) and
// the "color" target (the wood's shading; or, given, "leaf-tone"'s darkness of it); writes
// LineClass::Tone strokes in output px.
#pragma once

#include <opencv2/core.hpp>

#include "core/graph/render_graph.h"
#include "core/strokes.h"
#include "passes/hatching.h"
#include "passes/leaf_primitives.h"

namespace sylva {

// What is hatched: the crown's clumps, the wood, or both.
struct HatchWhat {
  bool foliage = true;
  bool wood = true;
};

// detail: ink.detail, px at 1024 px. Hatching is drawn whatever pen.tone says (the caller
// decides); pen.spacing, length, width, angle, lightest, darkest, gamma, cross, opacity and seed
// shape it.
// darkness: the colour's darkness at the layer's working size (LeafTone::darkness), or empty:
// made here from `color`.
StrokeDrawing hatch_groups(const LeafLayer& layer, const cv::Mat& normal, const cv::Mat& color,
                           const PenParams& p, double detail, HatchWhat what = {},
                           const cv::Mat& darkness = {});

// Adds the pass "hatching" and returns its strokes. tone (optional): "leaf-tone", whose darkness
// ranks the wood (else it is made from the colour).
Handle<StrokeDrawing> add_hatch_groups_pass(RenderGraph& g, Handle<LeafLayer> layer,
                                            ImageHandle normal, ImageHandle color,
                                            const PenParams& p, double detail, HatchWhat what = {},
                                            Handle<LeafTone> tone = {});

}  // namespace sylva

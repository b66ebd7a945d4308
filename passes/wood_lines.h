// Trunk and branches drawn where they are seen (Deussen & Strothotte 2000: the skeleton's
// silhouettes; issue "Pen-and-ink that depicts the tree"): at the frame's own resolution, so a
// branch a few pixels wide seen through a gap in the crown is outlined as the trunk is.
//
// Wood is what passes/seen_wood.h finds seen: where foliage stands in front the foliage wins. A
// crack between a wood pixel and its neighbour is outlined against the paper and anything not
// clearly in front of the wood (foliage behind or around it), and between two pieces of wood
// whose depths differ by more than edges.depth_threshold of theirs. Wood of every width is
// outlined (a twig a pixel or two wide becomes one line): a centre line for thin wood and an
// outline for wide would switch between the two as a branch's width crosses the limit from one
// frame to the next. Each line lies on the wood's side of its edge, over the wood; each chain is
// smoothed over a pixel (the staircase), simplified, and drawn at full width from ink.detail
// long on, thinner down to nothing at half of it (a piece seen through a gap fades as the gap
// closes instead of vanishing at a length).
//
// Reads (render graph): "seen-wood". Writes "wood-strokes", a StrokeDrawing of LineClass::Wood
// strokes.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

#include "core/graph/render_graph.h"
#include "core/strokes.h"
#include "passes/edges.h"
#include "passes/ink_lines.h"
#include "passes/seen_wood.h"

namespace sylva {

// The strokes of the wood seen (passes/seen_wood.h; an empty mask: none) at the frame's size.
// lines: ink.detail and lines.wood; edges: depth_threshold, min_width, color.
StrokeDrawing wood_strokes(const SeenWood& wood, const InkLineParams& lines,
                           const EdgeParams& edges);

// Adds the pass "wood-strokes" and returns its output.
Handle<StrokeDrawing> add_wood_lines_pass(RenderGraph& g, Handle<SeenWood> wood,
                                          const InkLineParams& lines, const EdgeParams& edges);

}  // namespace sylva

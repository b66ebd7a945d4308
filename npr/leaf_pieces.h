// The foliage's drawing primitives (Deussen & Strothotte 2000; issue "Pen-and-ink that depicts
// the tree"): each foliage element (a leaf, a needle, a card cut by its texture's alpha) as the
// surface samples (npr/surface_samples.h) it holds, with their area-weighted centre and
// covariance, from which a frame projects a view-facing ellipse that has the element's own
// shape (passes/leaf_primitives.h). An element larger than a cell of the plant's space
// (kPieceCells of the plant's diagonal: a fern frond, a large leaf) is cut into one piece per
// cell it crosses, so its primitives follow its shape at the scale the picture can hold;
// samples the texture cut away are not in the samples, so the pieces follow alpha-cut shapes.
//
// Made once per scene from its surface samples (a turntable's frames share them): fixed in the
// scene, so what a frame draws from them moves with it. Deterministic (sorted by element and
// cell, no randomness).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <mutex>
#include <vector>

#include "core/graph/render_graph.h"
#include "npr/surface_samples.h"

namespace sylva {

struct LeafPiece {
  glm::vec3 centre{0.0f};  // world space, area-weighted mean of its samples
  // Area-weighted covariance of its samples' positions (world units²): xx, xy, xz, yy, yz, zz.
  float cov[6] = {0, 0, 0, 0, 0, 0};
  float area = 0.0f;      // scene units², the samples' total
  uint32_t cluster = 0;   // the leaf cluster (SurfaceSamples::clusters) of its first sample
  uint32_t instance = 0;  // SurfaceSamples::instances (0 = a flat scene)
  // A piece of an element cut into several (a frond, a large leaf): drawn on its own, never
  // merged with other elements' pieces into a clump, so the element keeps its shape.
  bool cut = false;
};

struct LeafPieces {
  std::vector<LeafPiece> pieces;  // by (instance, element, cell)
  float cell = 0.0f;              // scene units
  // The foliage elements' typical size: the area-weighted median of their extents (the
  // diagonal of the box around an element's samples), scene units; 0 = unknown (the samples
  // name no elements). A fern's fronds span a sixth of its foliage's diagonal, a tree's leaves
  // and leaf cards under a twentieth.
  float leaf_extent = 0.0f;
  size_t size() const { return pieces.size(); }
  // The pieces merged into clumps at one clump size (passes/leaf_primitives.cpp), kept for the
  // next frame that asks for the same size (a turntable's frames share it): the last size's
  // only. A copy of the pieces starts without.
  struct ClumpMemo {
    std::mutex mutex;
    double size = 0.0;
    std::shared_ptr<const std::vector<LeafPiece>> clumps;
    ClumpMemo() = default;
    ClumpMemo(const ClumpMemo&) {}
    ClumpMemo& operator=(const ClumpMemo&) { return *this; }
  };
  mutable ClumpMemo clump_memo;
};

// The share of the foliage's diagonal one cell spans (an element larger than one is cut).
inline constexpr float kPieceCells = 1.0f / 48.0f;

// `pieces.leaf_extent` as a share of the foliage's diagonal (the cell is kPieceCells of it);
// 0 when unknown.
inline float leaf_share(const LeafPieces& pieces) {
  return pieces.cell > 0.0f ? pieces.leaf_extent * kPieceCells / pieces.cell : 0.0f;
}

// The pieces of the foliage samples of `samples` (neither cluster 0 nor `wood`, the trunk and
// branches' cluster; 0 = none) at cells of `cell` scene units (> 0 and finite).
LeafPieces make_leaf_pieces(const SurfaceSamples& samples, uint32_t wood, float cell);

// Shared by the graphs of one scene (a turntable's frames): the pieces are made once.
struct LeafPieceMemo {
  std::mutex mutex;
  std::shared_ptr<const SurfaceSamples> from;  // the samples `pieces` were made from
  std::shared_ptr<const LeafPieces> pieces;
};

using LeafPiecesHandle = Handle<std::shared_ptr<const LeafPieces>>;

// Adds the node "leaf-pieces" reading `samples` (the cell kPieceCells of the foliage samples'
// extent) and returns its output. memo may be null (made on every execute()).
LeafPiecesHandle add_leaf_pieces_pass(RenderGraph& graph, SamplesHandle samples, uint32_t wood,
                                      std::shared_ptr<LeafPieceMemo> memo = nullptr);

}  // namespace sylva

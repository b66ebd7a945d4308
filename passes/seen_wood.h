// The trunk and branches where a drawing shows them (issue "Pen-and-ink that depicts the
// tree": wood outlined where it is seen, through the crown's gaps too): what the raster shows of
// the wood cluster, completed where only the leaves or needles growing on it cover it. The eye
// reads a pine's branch through its own needles, and an illustrator draws it on; a clump of
// foliage standing clearly in front of the branch still hides it (the foliage wins).
//
// The completion comes from the scene: the wood's surface samples (npr/surface_samples.h)
// splatted into a z-buffer of the frame (each a disc of its spacing), and a splatted pixel is
// wood where the plant covers it (never beyond the raster's silhouette) and what the raster
// shows there lies no more than kWoodCover of the plant's depth extent in front of the wood.
// Without samples, gaps up to 0.3 x ink.detail across are closed instead.
//
// Reads (render graph): "id" (CV_32SC1 cluster ids), "depth" (CV_32FC1 linear view depth, 0 =
// background) and, when given, "surface-samples" (splatted by the pass "wood-splat", which does
// not wait for the raster). Writes "seen-wood", a SeenWood.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>

#include "core/gl/camera.h"
#include "core/graph/render_graph.h"
#include "npr/surface_samples.h"

namespace sylva {

// Foliage at most this share of the plant's depth extent in front of the wood does not hide it.
inline constexpr float kWoodCover = 0.01f;

struct SeenWood {
  cv::Mat mask;   // CV_8UC1 at the frame's size, 255 = wood seen; empty = no wood
  cv::Mat depth;  // CV_32FC1 at the frame's size, the wood's view depth where mask, else the
                  // raster's
  // Scene units: what the raster shows at most this far in front of the wood does not hide it
  // (kWoodCover of the plant's depth extent).
  float cover = 0.0f;
};

// The wood's surface samples splatted into a z-buffer of the camera's frame: each a disc of about
// its spacing, the nearest view depth kept; +inf where none (CV_32FC1). It needs no raster, so
// it is made while the raster draws.
struct WoodSplat {
  cv::Mat z;  // empty: none made
};
WoodSplat wood_splat(const SurfaceSamples& s, const Camera& camera, uint32_t wood);

struct WoodImages {
  cv::Mat id, depth;                              // the raster's
  std::shared_ptr<const SurfaceSamples> samples;  // or null
  Camera camera;                                  // the frame's
  WoodSplat splat;  // wood_splat of the samples made beforehand, or empty: made here
};

// wood: the trunk and branches' cluster (0 = none: an empty SeenWood); detail: ink.detail, px
// at 1024 px.
SeenWood seen_wood(const WoodImages& in, uint32_t wood, double detail);

struct WoodResources {
  ImageHandle id{}, depth{};
  SamplesHandle samples{};  // or none
  Camera camera;
};

// Adds the passes "wood-splat" (with samples) and "seen-wood"; returns the seen wood.
Handle<SeenWood> add_seen_wood_pass(RenderGraph& g, const WoodResources& in, uint32_t wood,
                                    double detail);

}  // namespace sylva

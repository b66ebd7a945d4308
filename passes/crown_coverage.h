// The plant's coverage and crown parts computed from the scene (issue "Temporal coherence"):
// the surface samples (npr/surface_samples.h) projected into the frame. Unlike the raster's
// coverage, whose sub-pixel leaves and needles land on pixel centres or miss them as the view
// turns, these move with the scene point by point, so the ink lines drawn from them
// (passes/ink_lines.h) stay put from one frame of a turntable to the next.
//
// Density: each sample adds the area it covers on screen, area x |cos| x (px per scene unit
// at its depth)², spread bilinearly over the four pixels around its projection and divided by
// a pixel's area: ~0 off the plant, about 1 where one layer of leaves faces the camera, more
// where layers overlap (no occlusion: every layer counts). |cos| is between the sample's
// normal and the direction to the eye (orthographic: the view axis). 1 - exp(-density) is the
// share of a pixel that randomly overlapping leaves cover.
//
// The camera's width and height are the image's: pass a copy sized to a working resolution to
// project there (the projection itself does not depend on the size). Deterministic (one
// thread, samples in order).
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "core/gl/camera.h"
#include "npr/surface_samples.h"

namespace sylva {

// CV_32FC1 of the camera's size. The samples of cluster `skip` (0 = none) are left out.
cv::Mat project_surface_density(const SurfaceSamples& samples, const Camera& camera,
                                uint32_t skip = 0);

// The crown's coverage at `size` (the camera's frame at another resolution): the density
// blurred by a Gaussian of `sigma` px, as 1 - exp(-density), CV_32FC1 in [0, 1]; the samples of
// cluster `skip` (0 = none: the wood's, for the leaves' coverage alone) left out.
cv::Mat crown_coverage(const SurfaceSamples& samples, const Camera& camera, cv::Size size,
                       double sigma, uint32_t skip = 0);

// Each part (leaf cluster) of the crown on its own, back to front by mean view depth: where its
// coverage 1 - exp(-density), the density of its samples alone smoothed by a Gaussian of `sigma`
// px, reaches `level` (the wood, see project_crown_parts, first where its own reaches
// wood_level). As Dudley renders a cluster for its blob "with all other branches and leaves
// turned off" (§4.2.1), but from the scene, so the masks move with it.
struct PartMask {
  uint32_t cluster = 0;
  float depth = 0;     // mean view depth, scene units
  cv::Point2f centre;  // where the samples' area-weighted mean position lands, px
  cv::Rect box;        // the mask's place in the image (may be empty)
  cv::Mat mask;        // CV_8UC1 of box's size, 255 = the part
};
// `wood_sigma` (px, > 0) smooths the wood's part instead of `sigma` (0 = sigma): a trunk and
// branches kept apart where a crown's parts are smoothed into masses.
std::vector<PartMask> project_part_masks(const SurfaceSamples& samples, const Camera& camera,
                                         double sigma, float level, uint32_t wood,
                                         float wood_level = 0.0f, double wood_sigma = 0.0);

// The crown's parts (leaf clusters) painted back to front, as Dudley's blobs are: each part
// covers the pixels where its own coverage 1 - exp(-density), the density smoothed by a
// Gaussian of `sigma` px, reaches `level`, and the parts are painted in the order of their mean
// view depth (area-weighted over their samples), the nearest last. So the map changes with the
// view only as the parts' projections move, and two parts swap order only where their mean
// depths cross. Samples of cluster 0 take no part; those of the `wood` cluster (trunk and
// branches; 0 = none) none either at wood_level 0, else one painted first, behind every other,
// where its coverage reaches wood_level (in (0, 1)), as a painter lays the trunk under the
// crown.
struct CrownParts {
  cv::Mat label;  // CV_32SC1 the front part's cluster id, 0 = none
  cv::Mat depth;  // CV_32FC1 that part's mean view depth (> 0, scene units), 0 = none
  // Every part the camera sees, back to front: its cluster id, mean view depth and where its
  // centre lands (px; the samples' area-weighted mean position, projected).
  struct Part {
    uint32_t cluster = 0;
    float depth = 0;
    cv::Point2f centre;
  };
  std::vector<Part> order;
};
CrownParts project_crown_parts(const SurfaceSamples& samples, const Camera& camera, double sigma,
                               float level, uint32_t wood, float wood_level = 0.0f,
                               double wood_sigma = 0.0);

// The plants of a scene of many plants painted back to front, as project_crown_parts paints the
// parts, each instance's foliage (neither cluster 0 nor `wood`) one part labelled with its
// index + 1 (SurfaceSamples::instances): where one plant's crown stands in front of another's.
// A scene of one plant (no instance ids) gives empty labels.
CrownParts project_plant_parts(const SurfaceSamples& samples, const Camera& camera, double sigma,
                               float level, uint32_t wood);

}  // namespace sylva

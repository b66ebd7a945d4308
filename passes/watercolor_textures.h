// Textures of the watercolor pass (passes/watercolor.h): the paper relief, value-noise fBm
// generated from the seed or a grey-scale image tiled at 1 image px per reference px, with the
// gradient of its smoothed relief that the wash outlines wobble along (Bousseau et al.); and
// the world-space turbulence (watercolor_turbulence). Both are deterministic: the same
// parameters give the same bytes.
//
// Reads the paper image file when WatercolorParams::paper names one (InputError when it cannot
// be read), and for the turbulence the view-space position and depth images. Writes only the
// images it returns. Defines watercolor_paper() and watercolor_turbulence(), declared with the
// pass in passes/watercolor.h.
#pragma once

#include <opencv2/core.hpp>

#include "passes/watercolor.h"

namespace sylva::watercolor_internal {

// The paper as a function of canvas position (px, continuous; pixel (i, j) centred at (i + 0.5,
// j + 0.5)), defined everywhere, so a wash can carry its own grain as it moves (issue
// "Temporal coherence"): relief in [0, 1] (mean about 0.5, standard deviation about 0.18), and
// the gradient of the smoothed relief the wash outlines wobble along (Bousseau et al.).
// Generated: value-noise fBm over hashed lattices of five octaves, the finest one grain
// (watercolor.grain px at 1024 px) across, coarser ones the mottled sizing of real paper; the
// slope is that of the four coarser octaves. Loaded: the grey-scale image at 1 image px per px
// at 1024 px, tiled (InputError when it cannot be read); its slope that of the image blurred.
class PaperField {
 public:
  PaperField(const WatercolorParams& p, double scale);
  float relief(float x, float y) const;
  cv::Vec2f slope(float x, float y) const;

 private:
  float raw(float x, float y) const;     // generated: the five octaves' mean, unnormalised
  float coarse(float x, float y) const;  // generated: the four coarser octaves, unnormalised
  double m_period = 1.0;                 // generated: px of the finest lattice
  uint32_t m_seed = 0;
  float m_mean = 0.5f, m_gain = 1.0f;  // generated: the sum's mean and normalisation
  cv::Mat m_tile, m_gx, m_gy;          // loaded: relief and slope, tiled
};

// The paper relief at every pixel of `size` (canvas offset 0). SYLVA_CHECKs a non-empty size.
cv::Mat paper_relief(const PaperField& paper, const cv::Size& size);

}  // namespace sylva::watercolor_internal

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

// Paper relief in [0, 1] and, when asked for, the gradient of its smoothed relief (any scale;
// the wobble normalises it).
struct Paper {
  cv::Mat relief, gx, gy;
};

// The paper at `size` (relief in [0, 1], mean about 0.5, standard deviation about 0.18), with
// its gradient when `gradient` is set. SYLVA_CHECKs a non-empty size.
Paper make_paper(const cv::Size& size, const WatercolorParams& p, bool gradient);

}  // namespace sylva::watercolor_internal

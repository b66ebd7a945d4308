// The images the ink lines' crown classes are found on (passes/ink_marks.h), at a working
// resolution where ink.detail is kWorkingDetail px across, so renders of any size see the same
// shapes (and large ones cost less).
//
// Reads InkLineImages (passes/ink_lines.h) and the plant's and wood's masks at the frame's size;
// writes the images below at the working size.
#pragma once

#include <opencv2/core.hpp>

#include "core/gl/camera.h"
#include "passes/ink_lines.h"

namespace sylva {

inline constexpr double kWorkingDetail = 5.0;  // px the detail spans at the working resolution
inline constexpr float kPlantLevel = 0.25f;    // of the blurred coverage: the plant's mask

// The working size of a frame of `size` for a detail of `detail` px (>= 2): the frame divided by
// `factor` = max(1, detail / kWorkingDetail), rounded, at least 1 x 1; `factor` receives the
// frame's px per working px.
cv::Size working_size(cv::Size size, double detail, double& factor);

struct InkWorking {
  double factor = 1.0;  // output px per working px, >= 1
  // From the raster, area-averaged and blurred by a quarter of the detail: its coverage >=
  // kPlantLevel, the covered pixels' mean depth (0 off the plant; where none is covered, the
  // blurred mean around), the wood where it is at least a quarter of the coverage.
  cv::Mat plant, depth, wood;
  // CV_32SC1 crown parts from the id buffer (majority-filtered), or empty: with surface samples
  // the parts come from the scene instead (passes/crown_coverage.h).
  cv::Mat parts;
  // CV_32FC1 in [0, 1], what the outline follows: the crown's coverage from the scene
  // (crown_coverage, blurred as the raster's), or else the raster's blurred coverage.
  cv::Mat coverage;
  Camera camera;  // the frame's, sized to the working resolution
};

// `plant`, `wood`: CV_8UC1 masks at the frame's size; `detail`: px (>= 2).
InkWorking ink_working_images(const InkLineImages& in, const cv::Mat& plant, const cv::Mat& wood,
                              double detail);

}  // namespace sylva

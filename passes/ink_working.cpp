#include "passes/ink_working.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "passes/crown_coverage.h"
#include "passes/ink_abstraction.h"

namespace sylva {

cv::Size working_size(cv::Size size, double detail, double& factor) {
  factor = std::max(1.0, detail / kWorkingDetail);
  const cv::Size working(std::max(1, int(std::lround(size.width / factor))),
                         std::max(1, int(std::lround(size.height / factor))));
  factor = double(size.width) / working.width;
  return working;
}

namespace {

// Blurred by a quarter of the working detail, so the crown is the same level set whether one
// working pixel averages 1 or 16 rendered ones.
constexpr double kSigma = 0.25 * kWorkingDetail;

// The raster's coverage, depth and wood at the working size.
void raster_images(const InkLineImages& in, const cv::Mat& plant, const cv::Mat& wood,
                   cv::Size size, InkWorking& w) {
  cv::Mat cover, weighted, mean, density, spread, wood_share;
  plant.convertTo(cover, CV_32F, 1.0 / 255.0);
  cv::resize(in.depth.mul(cover), weighted, size, 0, 0, cv::INTER_AREA);
  cv::resize(cover, cover, size, 0, 0, cv::INTER_AREA);
  cv::GaussianBlur(cover, density, {0, 0}, kSigma);
  w.plant = density >= kPlantLevel;
  w.coverage = density;
  // Depth: the covered pixels' mean in each working pixel (steps between crown parts stay
  // sharp); where none is covered, the blurred mean around it.
  cv::divide(weighted, cv::max(cover, 1e-6f), mean);
  cv::GaussianBlur(weighted, spread, {0, 0}, kSigma);
  cv::divide(spread, cv::max(density, 1e-6f), spread);
  spread.copyTo(mean, cover <= 0.0f);
  w.depth = cv::Mat(size, CV_32FC1, cv::Scalar(0));
  mean.copyTo(w.depth, w.plant);
  wood.convertTo(wood_share, CV_32F, 1.0 / 255.0);
  cv::resize(wood_share, wood_share, size, 0, 0, cv::INTER_AREA);
  w.wood = (wood_share >= 0.25f) & w.plant;
}

}  // namespace

InkWorking ink_working_images(const InkLineImages& in, const cv::Mat& plant, const cv::Mat& wood,
                              double detail) {
  InkWorking w;
  const cv::Size size = working_size(plant.size(), detail, w.factor);
  raster_images(in, plant, wood, size, w);
  w.camera = in.camera;
  w.camera.width = size.width;
  w.camera.height = size.height;
  if (in.samples) {
    w.coverage = crown_coverage(*in.samples, in.camera, size, kSigma);
  } else if (!in.id.empty()) {
    cv::resize(in.id, w.parts, size, 0, 0, cv::INTER_NEAREST);
    w.parts.setTo(0, ~w.plant);
    w.parts = majority_labels(w.parts, int(std::lround(0.5 * kWorkingDetail)));
  }
  return w;
}

}  // namespace sylva

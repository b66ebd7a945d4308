#include "styles/turntable.h"

#include <charconv>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "styles/blob_raster.h"

namespace sylva {

void validate_turntable(const TurntablePath& path) {
  if (path.frames < 1 || path.frames > 100000)
    throw InputError("--frames", std::to_string(path.frames) + " is outside [1, 100000]");
  if (!(std::abs(path.degrees) <= 36000.0f))
    throw InputError("--degrees", "must be a number in [-36000, 36000]");
  if (path.axis != 'x' && path.axis != 'y' && path.axis != 'z')
    throw InputError("--axis", "must be x, y or z");
  if (!(path.zoom > 0.0f && path.zoom <= 100.0f))
    throw InputError("--zoom", "must be in (0, 100] (1 = the view's framing)");
}

Camera turntable_camera(const Camera& base, const glm::vec3& centre, const TurntablePath& path,
                        int frame) {
  SYLVA_CHECK(frame >= 0, "turntable_camera: negative frame");
  const glm::vec3 axis = path.axis == 'x'   ? glm::vec3(1, 0, 0)
                         : path.axis == 'z' ? glm::vec3(0, 0, 1)
                                            : glm::vec3(0, 1, 0);
  // The angle in double so frame 7 of 7000 is as exact as frame 7 of 70.
  const double degrees = double(path.degrees) * double(frame) / double(path.frames);
  const float angle = float(degrees * 3.14159265358979323846 / 180.0);
  // Turning the camera by +angle about the axis is turning the scene by -angle.
  glm::mat4 scene_turn(1.0f);
  scene_turn = glm::translate(scene_turn, centre);
  scene_turn = glm::rotate(scene_turn, -angle, axis);
  scene_turn = glm::translate(scene_turn, -centre);
  Camera c = base;
  c.view = base.view * scene_turn;
  c.eye = glm::vec3(glm::inverse(scene_turn) * glm::vec4(base.eye, 1.0f));
  c.proj = glm::scale(glm::mat4(1.0f), glm::vec3(path.zoom, path.zoom, 1.0f)) * base.proj;
  return c;
}

FrameRange parse_frame_range(const std::string& text, int frames) {
  FrameRange r{0, frames};
  if (text.empty() || text == ":") return r;
  const size_t colon = text.find(':');
  auto number = [&](const std::string& s, int fallback) {
    if (s.empty()) return fallback;
    int v = 0;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size())
      throw InputError("--frame-range", "'" + text + "' is not A:B (frames A to B-1)");
    return v;
  };
  if (colon == std::string::npos)
    throw InputError("--frame-range", "'" + text + "' is not A:B (frames A to B-1)");
  r.begin = number(text.substr(0, colon), 0);
  r.end = number(text.substr(colon + 1), frames);
  if (!(r.begin >= 0 && r.begin < r.end && r.end <= frames))
    throw InputError("--frame-range", "'" + text + "' must satisfy 0 <= A < B <= " +
                                          std::to_string(frames) + " (the frame count)");
  return r;
}

double frame_flicker(const cv::Mat& previous, const cv::Mat& current, const cv::Mat& mask_previous,
                     const cv::Mat& mask_current) {
  SYLVA_CHECK(previous.type() == CV_8UC4 && current.type() == CV_8UC4 &&
                  previous.size() == current.size() && mask_previous.size() == current.size() &&
                  mask_current.size() == current.size() && mask_previous.type() == CV_8UC1 &&
                  mask_current.type() == CV_8UC1,
              "frame_flicker: mismatched frames or masks");
  cv::Mat mask;
  cv::bitwise_or(mask_previous != 0, mask_current != 0, mask);
  const int n = cv::countNonZero(mask);
  if (n == 0) return 0.0;
  cv::Mat diff;
  cv::absdiff(previous, current, diff);
  const cv::Scalar sum = cv::sum(diff.setTo(cv::Scalar::all(0), mask == 0));
  return (sum[0] + sum[1] + sum[2]) / (3.0 * n);
}

std::vector<BlobOutline> turntable_blob_outlines(const RasterSetup& base, const glm::vec3& centre,
                                                 const TurntablePath& path, int frame,
                                                 const BlobParams& p, uint32_t branch_cluster) {
  SYLVA_CHECK(base.rasterizer != nullptr, "turntable_blob_outlines: no rasteriser");
  return rasterised_blob_outlines(*base.rasterizer,
                                  turntable_camera(base.camera, centre, path, frame), base.lighting,
                                  base.request, p, branch_cluster);
}

double blob_jitter(const BlobSet& previous, const BlobSet& current) {
  double sum = 0;
  size_t count = 0;
  for (const BlobOutline& b : current.blobs)
    for (const BlobOutline& a : previous.blobs) {
      if (a.cluster != b.cluster || a.wrap.points.size() != b.wrap.points.size()) continue;
      for (size_t i = 0; i < a.wrap.points.size(); ++i)
        sum += glm::length(b.wrap.points[i] - a.wrap.points[i]);
      count += a.wrap.points.size();
    }
  return count == 0 ? 0.0 : sum / static_cast<double>(count);
}

}  // namespace sylva

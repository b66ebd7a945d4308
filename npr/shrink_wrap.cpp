#include "npr/shrink_wrap.h"

#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace sylva {

void validate_shrink_wrap(const ShrinkWrapParams& p, const char* where) {
  const std::string w = where;
  if (p.control_points < 3 || p.control_points > 512)
    throw InputError(w + ".control_points",
                     "must be in [3, 512], got " + std::to_string(p.control_points));
  if (!(p.step > 0.0f && p.step <= 1.0f))
    throw InputError(w + ".step", "must be in (0, 1], got " + std::to_string(p.step));
}

ShrinkWrap shrink_wrap(const cv::Mat& mask, const ShrinkWrapParams& params) {
  SYLVA_CHECK(mask.type() == CV_8UC1, "shrink_wrap: mask must be CV_8UC1");
  ShrinkWrap out;
  glm::dvec2 sum(0.0);
  size_t count = 0;
  for (int y = 0; y < mask.rows; ++y) {
    const uint8_t* row = mask.ptr<uint8_t>(y);
    for (int x = 0; x < mask.cols; ++x)
      if (row[x]) {
        sum += glm::dvec2(x + 0.5, y + 0.5);
        ++count;
      }
  }
  if (count == 0) return out;
  const glm::vec2 c(sum / static_cast<double>(count));
  float far2 = 0, near2 = std::numeric_limits<float>::max();
  glm::vec2 nearest = c;
  for (int y = 0; y < mask.rows; ++y) {
    const uint8_t* row = mask.ptr<uint8_t>(y);
    for (int x = 0; x < mask.cols; ++x)
      if (row[x]) {
        const glm::vec2 pc(x + 0.5f, y + 0.5f);
        const glm::vec2 d = pc - c;
        const float d2 = glm::dot(d, d);
        far2 = std::max(far2, d2);
        if (d2 < near2) {
          near2 = d2;
          nearest = pc;
        }
      }
  }
  out.center = c;
  out.radius = std::sqrt(far2) + 1.0f;
  auto on_mask = [&](glm::vec2 p) {
    const int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
    return x >= 0 && y >= 0 && x < mask.cols && y < mask.rows && mask.at<uint8_t>(y, x) != 0;
  };
  const int n = params.control_points;
  out.points.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    // Clockwise on screen (y down) from straight up.
    glm::vec2 p = c + out.radius * glm::vec2(std::sin(a), -std::cos(a)), before = p;
    bool landed = true;
    while (!on_mask(p)) {
      if (glm::length(p - c) < 0.5f) {
        p = nearest;
        landed = false;
        break;
      }
      before = p;
      p += params.step * (c - p);  // Dudley: 20 % of the way to the centre, repeated
    }
    // Back toward where it came from, to the mask's edge on the way (bisection to 1/64 of the
    // step): the point then moves with the edge as the cluster's pixels change, instead of by
    // whole steps.
    for (int k = 0; landed && k < 6; ++k) {
      const glm::vec2 mid = 0.5f * (before + p);
      (on_mask(mid) ? p : before) = mid;
    }
    out.points.push_back(p);
  }
  return out;
}

}  // namespace sylva

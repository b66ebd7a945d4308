// The orthographic view the foliage-primitive tests look through (test_leaf_primitives.cpp,
// test_watercolor_marks.cpp): a camera on +z looking at the origin, the view 4 units across,
// kFrontSize px square.
#pragma once

#include <glm/gtc/matrix_transform.hpp>
#include <opencv2/core.hpp>

#include "core/gl/camera.h"

namespace sylva::test {

inline constexpr int kFrontSize = 256;

inline Camera front_camera() {
  Camera c;
  c.eye = {0, 0, 10};
  c.view = glm::lookAt(c.eye, glm::vec3(0.0f), glm::vec3(0, 1, 0));
  c.proj = glm::ortho(-2.0f, 2.0f, -2.0f, 2.0f, 0.1f, 100.0f);
  c.ortho = true;
  c.width = c.height = kFrontSize;
  return c;
}

// Where a world point lands in the frame of front_camera, px.
inline cv::Point2f to_px(const glm::vec3& p) {
  return {float((p.x + 2.0) / 4.0 * kFrontSize), float((2.0 - p.y) / 4.0 * kFrontSize)};
}

}  // namespace sylva::test

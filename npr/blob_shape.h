// A blob's approximate geometry (Dudley 2005 §4.2.1): a screen-aligned height field pointing
// at the viewer, with Gaussian peaks at the blob's regional centres. The control points of the
// outline are split into as many contiguous runs as there are peaks; each run's mean, averaged
// with the blob's centre, is a regional centre. Heights and positions are in pixels, so the
// shape is the same at any distance; its normals shade the colour wash and, under the blend
// lights, make the mask that mixes wash and leaf detail.
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace sylva {

struct BlobShape {
  glm::vec2 center{0.0f};
  std::vector<glm::vec2> peaks;  // regional centres, pixels
  float height = 0;              // peak height, pixels
  float sigma = 1;               // Gaussian standard deviation of each peak, pixels
};

// The regional centres of an outline's control points (`peaks` >= 1, clamped to the number of
// points): run k holds points [k n / peaks, (k + 1) n / peaks).
std::vector<glm::vec2> regional_centers(const std::vector<glm::vec2>& control_points,
                                        glm::vec2 center, int peaks);

// The shape for an outline: width = twice the mean distance of the control points from the
// centre (at least 1 px), peak height = height_fraction x width (Dudley: 0 flat, 1 as high as
// the blob is wide), each peak's sigma a quarter of the width.
BlobShape make_blob_shape(const std::vector<glm::vec2>& control_points, glm::vec2 center, int peaks,
                          float height_fraction);

// Height at p: the peaks' smooth union h = H (1 - prod_k (1 - g_k(p))), g_k a unit Gaussian,
// so overlapping peaks never rise above H.
float blob_height(const BlobShape& shape, glm::vec2 p);

// Unit normal of the height field at pixel position p, in view space (x right, y up, z toward
// the viewer; image y points down). A flat shape (H = 0) faces the viewer: (0, 0, 1).
glm::vec3 blob_normal(const BlobShape& shape, glm::vec2 p);

}  // namespace sylva

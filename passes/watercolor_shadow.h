// The watercolor's shadow glaze and its warm light and cool shade (issue "Watercolor that
// paints the tree as a painter would", item 4): where the key light does not reach through the
// crown (the scene's surface samples as a shadow map from the key light, npr/sample_shadow.h,
// the light falling off behind the first leaves), a transparent glaze is laid over the washes,
// soft-edged (the shadow evaluated on a coarse grid at the surface's world position and
// blurred at twice the wash blur, so it moves with the scene and never pops), in a cool hue
// (ultramarine-violet) by watercolor.warm_cool, the pigment's own darker value at 0. The washes'
// lit sides shift towards warm by the same parameter (passes/watercolor_layers.cpp), as
// painters and Gooch et al.'s tone shading contrast warm light with cool shade.
#pragma once

#include <glm/glm.hpp>
#include <opencv2/core.hpp>

#include "npr/surface_samples.h"
#include "passes/leaf_primitives.h"
#include "passes/watercolor_common.h"

namespace sylva::watercolor_internal {

// The share of the key light that does not reach each place of the plant (0 lit, 1 in full
// shadow), CV_32FC1 on a grid of `cell` px cells over the image of `depth`'s size, blurred by
// `sigma` px: from the view-space positions of the covered pixels (depth > 0), through
// view_to_world. Empty without a key light (light.on false or an empty sphere).
cv::Mat key_shadow(const ViewPositions& view, const glm::mat4& view_to_world,
                   const SurfaceSamples& samples, const KeyLight& light, int cell, float sigma);

// The shadow glaze over `density` (CV_32FC3, the glazed washes): per pixel the shadow (bilinear
// from the grid of `shadow`) times `strength` times how much paint is there (wash_cover), in
// the glaze colour's density: warm_cool 0 a neutral darkening, 1 ultramarine-violet.
void glaze_shadow(const cv::Mat& shadow, float strength, float warm_cool, cv::Mat& density);

}  // namespace sylva::watercolor_internal

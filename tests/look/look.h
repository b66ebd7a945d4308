// The look images (tests/look/look_images.cpp): each set writes its PNGs through `save`.
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <string>

namespace sylva::test {

using Save = std::function<void(const std::string& name, const cv::Mat& image)>;

void edges_look(const Save& save);       // look_edges.cpp
void ink_look(const Save& save);         // look_edges.cpp
void toon_look(const Save& save);        // look_toon.cpp
void watercolor_look(const Save& save);  // look_watercolor.cpp

}  // namespace sylva::test

// Toon looks: bands on an N·L ramp and spheres (tests/passes/toon_scenes.h) over light grey.
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "core/params.h"
#include "passes/toon.h"
#include "tests/look/look.h"
#include "tests/passes/toon_scenes.h"

namespace sylva::test {

namespace {

cv::Mat over_grey(const cv::Mat& bgra) {
  cv::Mat out(bgra.size(), CV_8UC3);
  for (int y = 0; y < bgra.rows; ++y)
    for (int x = 0; x < bgra.cols; ++x) {
      const cv::Vec4b c = bgra.at<cv::Vec4b>(y, x);
      const float a = float(c[3]) / 255.0f;
      for (int ch = 0; ch < 3; ++ch)
        out.at<cv::Vec3b>(y, x)[ch] = encode(decode(c[ch]) + (1.0f - a) * decode(225));
    }
  return out;
}

}  // namespace

// Toon bands on an N·L ramp for four settings, and a sphere in four looks, over light grey.
void toon_look(const Save& save) {
  std::vector<cv::Mat> rows;
  for (const char* setting : {"bands=3", "bands=5", "thresholds=0.2,0.6", "specular"}) {
    ToonParams p;
    ParamSet set;
    bind_toon_params(set, p);
    const std::string s = setting;
    if (s == "specular") {
      p.specular = true;
      p.specular_threshold = 0.9f;
    } else {
      const size_t eq = s.find('=');
      set.set_from_string("toon." + s.substr(0, eq), s.substr(eq + 1), "look");
    }
    cv::Mat row;
    cv::repeat(toon_shade(ramp(512, 1), headlight(), glm::mat4(1.0f), p), 40, 1, row);
    rows.push_back(row);
  }
  cv::Mat ramp_img;
  cv::vconcat(rows, ramp_img);
  save("ramp.png", over_grey(ramp_img));

  std::vector<cv::Mat> spheres;
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0));
  for (int variant = 0; variant < 4; ++variant) {
    ToonParams p;
    if (variant == 1) {
      p.bands = 4;
      p.specular = true;
    }
    if (variant == 2) {
      p.light = ToonLight::Sum;
      p.ka_weight = 1.0f;
    }
    if (variant == 3) {
      p.shadow = 0.7f;
      p.shadow_tint = glm::vec3(0.35f, 0.45f, 0.9f);
      p.thresholds = "0.15,0.7";
      p.tones = "0.6,0.85,1.05";
    }
    spheres.push_back(toon_shade(sphere(256), Lighting::three_point(), view, p));
  }
  cv::Mat sphere_img;
  cv::hconcat(spheres, sphere_img);
  save("sphere.png", over_grey(sphere_img));
}

}  // namespace sylva::test

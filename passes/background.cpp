#include "passes/background.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/color.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

const std::array<float, 256>& to_linear() {
  static const std::array<float, 256> t = [] {
    std::array<float, 256> a{};
    for (int i = 0; i < 256; ++i) {
      const double v = i / 255.0;
      a[size_t(i)] = srgb_to_linear(float(v));
    }
    return a;
  }();
  return t;
}

uint8_t to_srgb(float c) {
  return uint8_t(std::lround(linear_to_srgb(c) * 255.0f));
}

}  // namespace

cv::Mat over_background(const cv::Mat& image, const glm::vec4& background) {
  expect_image(image, CV_8UC4, cv::Size(), "image");
  if (!(background.a > 0.0f)) return image.clone();
  const std::array<float, 256>& lin = to_linear();
  const float bg[3] = {background.b, background.g, background.r};  // BGR order
  cv::Mat out(image.size(), CV_8UC4);
  cv::parallel_for_(cv::Range(0, image.rows), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      const cv::Vec4b* src = image.ptr<cv::Vec4b>(y);
      cv::Vec4b* dst = out.ptr<cv::Vec4b>(y);
      for (int x = 0; x < image.cols; ++x) {
        const float a = src[x][3] / 255.0f;
        for (int c = 0; c < 3; ++c)
          dst[x][c] = to_srgb(lin[src[x][c]] + (1.0f - a) * bg[c]);
        dst[x][3] = uint8_t(std::lround(255.0f * (a + (1.0f - a) * background.a)));
      }
    }
  });
  return out;
}

ImageHandle add_background_pass(RenderGraph& graph, ImageHandle image, const glm::vec4& background,
                                const std::string& name) {
  const auto out = graph.resource<cv::Mat>(name);
  graph.add_pass("background", {image}, {out}, [=](PassContext& ctx) {
    ctx.write(out, over_background(ctx.read<cv::Mat>(image), background));
  });
  return out;
}

}  // namespace sylva

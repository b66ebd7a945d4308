#include "passes/pass_common.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "core/error.h"

namespace sylva {

double reference_scale(const cv::Size& size) {
  return double(std::min(size.width, size.height)) / double(kReferenceResolution);
}

void expect_image(const cv::Mat& m, int type, const cv::Size& size, const char* what) {
  SYLVA_CHECK(!m.empty() && m.type() == type && (size.empty() || m.size() == size),
              std::string("image pass input '") + what + "' has the wrong type or size");
}

cv::Mat pieces_where(const cv::Mat& mask, const std::function<bool(const int* stats)>& pick) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  std::vector<uint8_t> taken(size_t(std::max(n, 1)), 0);
  for (int i = 1; i < n; ++i)
    taken[size_t(i)] = pick(stats.ptr<int>(i)) ? 255 : 0;
  cv::Mat out(mask.size(), CV_8UC1);
  for_bands(mask.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const int32_t* l = labels.ptr<int32_t>(y);
      uint8_t* o = out.ptr<uint8_t>(y);
      for (int x = 0; x < mask.cols; ++x)
        o[x] = taken[size_t(l[x])];
    }
  });
  return out;
}

void sort_unit_keys(std::vector<std::pair<float, size_t>>& pairs) {
  constexpr int kBins = 1 << 16;
  const auto bin = [](float key) {
    return key > 0.0f ? std::min(kBins - 1, int(key * float(kBins))) : 0;
  };
  std::vector<size_t> first(kBins + 1, 0);
  for (const auto& p : pairs)
    ++first[size_t(bin(p.first)) + 1];
  for (size_t b = 1; b < first.size(); ++b)
    first[b] += first[b - 1];
  std::vector<std::pair<float, size_t>> out(pairs.size());
  std::vector<size_t> next(first.begin(), first.end() - 1);
  for (const auto& p : pairs)
    out[next[size_t(bin(p.first))]++] = p;
  for (size_t b = 0; b + 1 < first.size(); ++b)
    if (first[b + 1] - first[b] > 1)
      std::sort(out.begin() + std::ptrdiff_t(first[b]), out.begin() + std::ptrdiff_t(first[b + 1]));
  pairs = std::move(out);
}

cv::Mat normalised_blur(const cv::Mat& weighted, const cv::Mat& weight, double sigma) {
  SYLVA_CHECK(
      weighted.type() == CV_32FC1 && weight.type() == CV_32FC1 && weighted.size() == weight.size(),
      "normalised_blur: two CV_32FC1 images of one size");
  cv::Mat blurred[2];
  const cv::Mat* in[2] = {&weighted, &weight};
  cv::parallel_for_(cv::Range(0, 2), [&](const cv::Range& r) {
    for (int i = r.start; i < r.end; ++i)
      cv::GaussianBlur(*in[i], blurred[i], {0, 0}, std::max(0.5, sigma));
  });
  cv::divide(blurred[0], cv::max(blurred[1], 1e-6f), blurred[0]);
  return blurred[0];
}

}  // namespace sylva
